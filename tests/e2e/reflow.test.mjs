// Screens of any shape: every page of every shipped bundle, shown in the real kiosk shell
// (through Docent) with touch, from a phone through a portrait tablet to landscape kiosks.
// Each page is screenshotted (target/e2e/reflow/<bundle>/<size>/<page>.png, not committed) and
// every `data-act` element must be at least 44x44 CSS px and the element a tap at its centre
// hits (document.elementFromPoint: nothing covers it, not even the shell's own bars).
//
// Where it must be: on the tablets and kiosks (600 px wide and more) inside the viewport as the
// page opens, nothing to scroll. On a phone the page may scroll down, and only down: a phone is
// a visitor's own device, where swiping is what everyone does, and fitting a tour stop's
// picture, facts and five buttons into 390x844 without it would shrink them all below what a
// visitor can read or tap. So on a phone each element is scrolled to (as a swipe would) and must
// then be inside the viewport; every box it scrolls in must let a finger scroll it
// (`overflow` not `hidden`), and nothing may stick out sideways.

import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser } from './lib/browser.mjs';
import { REPO, startDocent } from './lib/docent.mjs';
import { openShell, waitForShownPage } from './lib/kiosk.mjs';
import { measureTargets, targetProblems } from './lib/targets.mjs';

/** The screens tried, smallest first; `phone` ones may scroll (see above). */
export const SIZES = [
  { name: 'phone', width: 390, height: 844, phone: true },
  { name: 'portrait', width: 800, height: 1280 },
  { name: 'landscape', width: 1280, height: 800 },
  { name: 'full-hd', width: 1920, height: 1080 },
];

const OUT = path.join(REPO, 'target/e2e/reflow');

const bundles = fs
  .readdirSync(path.join(REPO, 'dialogs'), { withFileTypes: true })
  .filter((d) => d.isDirectory() && fs.existsSync(path.join(REPO, 'dialogs', d.name, 'docent.yaml')))
  .map((d) => d.name)
  .sort();

/** Every page of a bundle, relative to pages/ with forward slashes, sorted. */
function pagesOf(name) {
  const dir = path.join(REPO, 'dialogs', name, 'pages');
  if (!fs.existsSync(dir)) return [];
  return fs
    .readdirSync(dir, { recursive: true })
    .filter((f) => f.endsWith('.html'))
    .map((f) => f.split(path.sep).join('/'))
    .sort();
}

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

// Runs in a content page: what scrolls, and which box that clips its content keeps a part of the
// page out of a finger's reach. Self-contained (Playwright sends its source).
function scrolling() {
  const root = document.scrollingElement;
  const trapped = [];
  for (const el of document.querySelectorAll('body, body *')) {
    const style = getComputedStyle(el);
    const clips = ['hidden', 'clip'].includes(style.overflowY) || ['hidden', 'clip'].includes(style.overflowX);
    if (!clips) continue;
    const hidden = el.scrollHeight > el.clientHeight + 1 || el.scrollWidth > el.clientWidth + 1;
    // Only boxes holding a control matter: a picture's rounded corners clip nothing one taps.
    if (hidden && el.querySelector('[data-act]')) trapped.push(`${el.tagName.toLowerCase()}${el.className ? `.${el.className}` : ''}`);
  }
  return {
    scrollWidth: root.scrollWidth,
    scrollHeight: root.scrollHeight,
    width: innerWidth,
    height: innerHeight,
    trapped,
  };
}

for (const name of bundles) {
  test(`every page of ${name} reflows: each data-act reachable, tappable and at least 44 px, phone to 1920x1080`, { timeout: 300_000 }, async () => {
    const pages = pagesOf(name);
    assert.ok(pages.length > 0, `${name} has no pages`);
    const server = await startDocent(path.join(REPO, 'dialogs', name));
    const problems = [];
    try {
      for (const size of SIZES) {
        // The shell opens on the page shown last (the server's display state).
        const current = (await server.api('/api/state')).display.page;
        const context = await browser.newContext({
          viewport: { width: size.width, height: size.height },
          hasTouch: true,
          isMobile: Boolean(size.phone),
        });
        try {
          const shell = await context.newPage();
          let frame = await openShell(shell, server, current);
          for (const file of pages) {
            if (frame.url() !== `${server.base}/pages/${file}`) {
              // The page goes there itself, as a link would; the shell follows and reports it.
              await frame.evaluate((url) => location.assign(url), `${server.base}/pages/${file}`);
              frame = await waitForShownPage(shell, file);
            }
            await frame.evaluate(async () => {
              await document.fonts.ready;
              await Promise.all([...document.images].map((img) => img.decode().catch(() => {})));
            });
            const where = `${name} ${file} at ${size.width}x${size.height}`;
            const shot = path.join(OUT, name, `${size.width}x${size.height}`, `${file.replace(/\//g, '_')}.png`);
            fs.mkdirSync(path.dirname(shot), { recursive: true });
            await shell.screenshot({ path: shot });

            const scroll = await frame.evaluate(scrolling);
            if (scroll.scrollWidth > scroll.width + 1) problems.push(`${where}: the page is ${scroll.scrollWidth} px wide, it scrolls sideways`);
            if (!size.phone && scroll.scrollHeight > scroll.height + 1) problems.push(`${where}: the page is ${scroll.scrollHeight} px high, it must not scroll here`);
            for (const box of scroll.trapped) problems.push(`${where}: ${box} hides part of its content and cannot be scrolled`);

            const targets = await frame.evaluate(measureTargets, { selector: '[data-act]', scroll: Boolean(size.phone) });
            // A page with buttons must show some; an attract loop's or the closed page may have none.
            const offersActs = await frame.evaluate(() => document.querySelector('[data-act]') !== null);
            if (offersActs && targets.length === 0) problems.push(`${where}: no data-act element is shown`);
            // The shell's own bars and buttons may not cover a page's controls either. They are
            // fixed to the screen, so a centre measured after scrolling still holds.
            for (const t of targets.filter((t) => t.hitsItself)) {
              const onShell = await shell.evaluate(({ x, y }) => {
                const hit = document.elementFromPoint(x, y);
                return hit?.matches('iframe.docent-frame.shown') ? null : (hit?.id || hit?.tagName || 'nothing');
              }, t.centre);
              if (onShell) problems.push(`${where}: ${t.name} is covered by the shell's ${onShell}`);
            }
            for (const p of targetProblems(targets)) problems.push(`${where}: ${p}`);
            await frame.evaluate(() => window.scrollTo(0, 0));
          }
        } finally {
          await context.close();
        }
      }
    } finally {
      await server.stop();
    }
    assert.deepEqual(problems, [], `screenshots in ${path.relative(REPO, OUT)}/${name}`);
  });
}
