// What a visitor sees of a bundle's pages in the kiosk shell, in headless Chromium: a link to a
// page that is not there shows the friendly "not available" page in the bundle's style (never
// raw JSON), whose button leads home and triggers nothing, and the author finds the broken link
// in the corpus; a page that cannot be loaded at all (Docent gone) shows the same page, not the
// browser's error screen; and `docent` is there for a page's own inline scripts at load.

import assert from 'node:assert/strict';
import { rmSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext, watchExceptions } from './lib/browser.mjs';
import { corpusEvents, DEADLINE_MS, makeBundle, removeTemp, startDocent } from './lib/docent.mjs';
import { openShell, shownContentFrame, waitForShownPage } from './lib/kiosk.mjs';
import { connectOperator } from './lib/ws-client.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

const ACTS = '- Label: HELLO\n  Text: [Hello there]\n- Label: BYE\n  Text: [Goodbye]\n';
/** The bundle's own style: a background no browser default has. */
const STYLE = 'body { background: rgb(10, 120, 90); }\n';

const html = (title, { head = '', body = '' } = {}) =>
  '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">' +
  `<link rel="stylesheet" href="css/site.css">${head}<title>${title}</title></head>\n` +
  `<body><h1>${title}</h1>${body}</body></html>\n`;

/** Runs `body(ctx)` with a server on a bundle of `pages`, a touch page and an operator;
 * `ctx.dir` is the bundle folder. */
async function withKiosk(pages, body) {
  const files = { 'acts.yaml': ACTS, 'pages/css/site.css': STYLE };
  for (const [name, contents] of Object.entries(pages)) files[`pages/${name}`] = contents;
  const dir = makeBundle(files);
  const server = await startDocent(dir);
  const context = await newTouchContext(browser);
  const operator = await connectOperator(server.wsUrl);
  try {
    const page = await context.newPage();
    const errors = watchExceptions(page);
    await body({ server, page, operator, dir });
    assert.deepEqual(errors, [], 'uncaught exceptions in the kiosk');
  } finally {
    operator.close();
    await context.close();
    await server.stop();
    removeTemp(dir);
  }
  return server;
}

/** Waits until the shell shows the friendly page; returns its Playwright Frame. */
async function waitForUnavailable(page, { srcdoc = false } = {}) {
  await page.waitForFunction(
    (srcdoc) =>
      [...document.querySelectorAll('iframe.docent-frame.shown')].some((frame) => {
        try {
          const doc = frame.contentDocument;
          return (
            doc?.readyState === 'complete' &&
            doc.querySelector('meta[name="docent-page"][content="missing"]') !== null &&
            (frame.contentWindow.location.href === 'about:srcdoc') === srcdoc
          );
        } catch {
          return false;
        }
      }),
    srcdoc,
    { timeout: DEADLINE_MS, polling: 'raf' },
  );
  return shownContentFrame(page);
}

test('a link to a page deleted while Docent runs shows the friendly page in the bundle style, its button goes home, the corpus has it', { timeout: 60_000 }, async () => {
  const server = await withKiosk(
    {
      'index.html': html('Welcome', { body: '<a id="broken" href="opening%20hours.html">Opening hours</a><button data-act="HELLO">Hi</button>' }),
      // `docent check` refuses a link to a missing page, so the page exists at the start and
      // is deleted while Docent runs (the save is refused; the file is gone all the same).
      'opening hours.html': html('Opening hours'),
    },
    async ({ server, page, operator, dir }) => {
      rmSync(join(dir, 'pages', 'opening hours.html'));
      const home = await openShell(page, server, 'index.html');
      await home.locator('#broken').tap();

      const missing = await waitForUnavailable(page);
      assert.equal(await missing.locator('h1').textContent(), 'This page is not available.');
      assert.equal(await missing.locator('body').evaluate((b) => getComputedStyle(b).backgroundColor), 'rgb(10, 120, 90)', "not the bundle's style");
      assert.doesNotMatch(await missing.locator('body').innerText(), /not-found|"code"/);
      const event = await operator.waitForEvent((e) => e.type === 'page.missing');
      assert.deepEqual({ page: event.page, from: event.from }, { page: 'opening hours.html', from: 'index.html' });

      await missing.locator('a.docent-home').tap();
      await waitForShownPage(page, 'index.html');
      // The friendly page was never reported as shown, so the server's display state stayed
      // on the home page all along; and the way home triggered no act.
      assert.equal((await server.api('/api/state')).display.page, 'index.html');
      const changed = operator.events().filter((e) => e.type === 'display.changed' || e.type === 'act.triggered');
      assert.deepEqual(changed, []);
    },
  );
  const logged = corpusEvents(server.corpus).filter((e) => e.type === 'page.missing');
  assert.equal(logged.length, 1, JSON.stringify(logged));
  assert.equal(logged[0].page, 'opening hours.html');
  assert.equal(logged[0].from, 'index.html');
  assert.match(server.output(), /WARN.*"opening hours\.html", which is not in the bundle \(linked from "index\.html"\)/);
});

test('a page that cannot be loaded at all shows the friendly page, not the browser error screen', { timeout: 60_000 }, async () => {
  await withKiosk(
    {
      'index.html': html('Welcome', { body: '<a id="next" href="next.html">Next</a>' }),
      'next.html': html('Next'),
    },
    async ({ server, page }) => {
      const home = await openShell(page, server, 'index.html');
      // The network loses the page while the connection to Docent stays up (a whole outage
      // is outage.test.mjs's: taps then answer "one moment" and links stay put).
      await page.route('**/pages/next.html', (route) => route.abort('connectionfailed'));
      await home.locator('#next').tap();
      const shown = await waitForUnavailable(page, { srcdoc: true });
      assert.equal(await shown.locator('h1').textContent(), 'This page is not available.');
      assert.equal(await shown.locator('a.docent-home').getAttribute('href'), '/pages/index.html');
    },
  );
});

test('an inline page script can call docent.trigger at load, and docent.on and docent.ready work from the first script', { timeout: 60_000 }, async () => {
  const triggerAtLoad = `<script>
    docent.trigger("HELLO").then((answer) => { document.documentElement.dataset.answer = answer.type; });
  </script>`;
  const listenAtLoad = `<script>
    docent.on("triggered", (frame) => { document.body.dataset.heard = frame.label; });
    docent.ready(() => { document.getElementById("status").textContent = "ready"; });
  </script>`;
  await withKiosk(
    {
      'index.html': html('Slideshow', { head: triggerAtLoad, body: '<a id="next" href="listen.html">next</a>' }),
      'listen.html': html('Listening', { head: listenAtLoad, body: '<p id="status">not ready</p><button data-act="BYE">Bye</button>' }),
      'offers.html': html('Offers', { body: '<button data-act="HELLO">Hello</button>' }),
    },
    async ({ server, page, operator }) => {
      const home = await openShell(page, server, 'index.html');
      const triggered = await operator.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'HELLO');
      assert.equal(triggered.source, 'kiosk');
      await home.waitForFunction(() => document.documentElement.dataset.answer === 'triggered');

      await home.locator('#next').tap();
      const listen = await waitForShownPage(page, 'listen.html');
      assert.equal(await listen.locator('#status').textContent(), 'ready');
      await listen.locator('[data-act="BYE"]').tap();
      await listen.waitForFunction(() => document.body.dataset.heard === 'BYE');
    },
  );
});
