// The projector page's highlights in headless Chromium: HIGHLIGHT lights the right pixels, and
// the poster presenter advances by its page timers, lighting each section's area. Films and
// what the projector reports about them: projector.test.mjs. An operator websocket client
// reads the server's events; every wait is for an event, with a deadline only.

import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, watchProblems } from './lib/browser.mjs';
import { copyBundle, makeBundle, REPO, removeTemp } from './lib/docent.mjs';
import { openShell } from './lib/kiosk.mjs';
import { openProjector, withProjectorServer } from './lib/projector.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

/** Runs `body(ctx)` with a server on `bundle`, a page and an operator (see lib/projector.mjs). */
const withServer = (bundle, body, options) => withProjectorServer(browser, bundle, body, options);

/**
 * The size of a PNG and the RGB colour of each of `points` (`[x, y]`), decoded by the browser in
 * `page` (a canvas drawing the PNG as a data URL).
 */
function samplePng(page, png, points) {
  const url = `data:image/png;base64,${png.toString('base64')}`;
  return page.evaluate(
    async ({ src, points }) => {
      const image = new Image();
      image.src = src;
      await image.decode();
      const canvas = document.createElement('canvas');
      canvas.width = image.naturalWidth;
      canvas.height = image.naturalHeight;
      const context = canvas.getContext('2d');
      context.drawImage(image, 0, 0);
      const colours = points.map(([x, y]) => Array.from(context.getImageData(x, y, 1, 1).data.slice(0, 3)));
      return { width: canvas.width, height: canvas.height, colours };
    },
    { src: url, points },
  );
}

test('HIGHLIGHT lights the right pixels of the projector page', { timeout: 60_000 }, async () => {
  const bundle = makeBundle({
    'docent.yaml': 'speech: {adapter: log}\nprojector: {highlight_edge: 0}\n',
    'acts.yaml': '- Label: AREA\n  Cmds: [HIGHLIGHT 0.10 0.20 0.35 0.25]\n',
    'pages/index.html': '<!DOCTYPE html><title>home</title>',
  });
  try {
    await withServer(bundle, async ({ server, page, operator }) => {
      const problems = watchProblems(page);
      await openProjector(page, server, operator);
      await server.trigger('AREA');
      await page.waitForSelector('.docent-highlight');
      // Two frames, so that what is painted is what the screenshot shows.
      await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
      // Lit: x 100..450, y 100..225 of 1000 x 500; sampled inside, and outside, the border.
      const lit = [];
      for (const x of [105, 150, 275, 440, 444]) for (const y of [105, 110, 160, 215, 219]) lit.push([x, y]);
      const dark = [[50, 50], [500, 300], [95, 150], [455, 150], [200, 95], [200, 230], [990, 490]];
      const shot = await samplePng(page, await page.screenshot(), [...lit, ...dark]);
      assert.deepEqual([shot.width, shot.height], [1000, 500]);
      for (const [i, [x, y]] of lit.entries()) {
        assert.deepEqual(shot.colours[i], [255, 255, 255], `(${x}, ${y}) should be lit`);
      }
      for (const [i, [x, y]] of dark.entries()) {
        assert.deepEqual(shot.colours[lit.length + i], [0, 0, 0], `(${x}, ${y}) should be black`);
      }
      assert.deepEqual(problems, [], 'problems in the projector page');
    });
  } finally {
    removeTemp(bundle);
  }
});

test('the poster presenter advances by its page timers through every area', { timeout: 90_000 }, async () => {
  // The shipped pages advance by touch only; this copy gives each Next button a 300 ms timer.
  const pages = path.join(REPO, 'dialogs/poster-presenter/pages');
  const files = { 'docent.yaml': 'home: index.html\ncontexts: [TextGroup, TextChild]\nspeech: {adapter: log, rate: 600}\n' };
  for (const name of ['index.html', 'section-1.html', 'section-2.html', 'section-3.html', 'section-4.html']) {
    const html = fs.readFileSync(path.join(pages, name), 'utf8');
    const timed = html.replace(/(<button type="button" class="next" )/, '$1data-act-after="300ms" ');
    assert.notEqual(timed, html, `${name} has a Next button`);
    files[`pages/${name}`] = timed;
  }
  const bundle = copyBundle('poster-presenter', files);
  try {
    await withServer(bundle, async ({ server, page, operator }) => {
      const problems = watchProblems(page);
      // HIGHLIGHT is done only when a projector painted it: the poster needs its projector.
      const projector = await page.context().newPage();
      await openProjector(projector, server, operator);
      await openShell(page, server, 'index.html');
      const expected = ['SECTION_1', 'SECTION_2', 'SECTION_3', 'SECTION_4', 'CLOSING'];
      for (const label of expected) {
        const fired = await operator.waitForEvent((e) => e.type === 'act.triggered' && e.label === label);
        assert.equal(fired.source, 'kiosk', `${label} was triggered by ${fired.source}`);
      }
      await operator.waitForEvent((e) => e.type === 'display.changed' && e.page === 'end.html');
      const triggered = operator.events().filter((e) => e.type === 'act.triggered').map((e) => e.label);
      assert.deepEqual(triggered, expected);
      // Each section lit its own area on the projector.
      const areas = operator
        .events()
        .filter((e) => e.type === 'display.changed' && e.highlight)
        .map((e) => e.highlight.split(/\s+/).slice(0, 2).join(' '))
        .filter((area, i, all) => area !== all[i - 1]); // a DISPLAY_PAGE repeats the area
      assert.deepEqual(areas, ['0.02 0.17', '0.51 0.17', '0.02 0.58', '0.51 0.58']);
      assert.deepEqual(problems, [], 'problems in the kiosk shell');
    }, { touch: true });
  } finally {
    removeTemp(bundle);
  }
});
