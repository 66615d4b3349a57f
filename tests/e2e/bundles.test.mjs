// Every shipped bundle's home page renders in headless Chromium at the kiosk's size (1280x800)
// without console errors, uncaught exceptions, failed requests or broken images, and every
// data-act on it names an act of the bundle. The screenshots in docs/screenshots/<bundle>.png
// (shown in the README) are written here, by this test.

import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext, VIEWPORT, watchProblems } from './lib/browser.mjs';
import { REPO, startDocent } from './lib/docent.mjs';

const SHIPPED = ['paper-fig4', 'info-terminal', 'museum-tour', 'poster-presenter'];
const SCREENSHOTS = path.join(REPO, 'docs/screenshots');

// Every folder of dialogs/ with an acts file is a bundle, so a new one is tested too.
const bundles = fs
  .readdirSync(path.join(REPO, 'dialogs'), { withFileTypes: true })
  .filter((d) => d.isDirectory())
  .filter((d) => fs.readdirSync(path.join(REPO, 'dialogs', d.name)).some((f) => /\.ya?ml$/.test(f)))
  .map((d) => d.name)
  .sort();

let browser;
before(async () => {
  browser = await launchBrowser();
  fs.mkdirSync(SCREENSHOTS, { recursive: true });
});
after(() => browser?.close());

test('the four use cases of the paper are shipped as bundles', () => {
  for (const name of SHIPPED) assert.ok(bundles.includes(name), `dialogs/${name} is missing`);
});

for (const name of bundles) {
  test(`the home page of ${name} renders without errors at 1280x800`, { timeout: 60_000 }, async () => {
    const server = await startDocent(path.join(REPO, 'dialogs', name));
    const context = await newTouchContext(browser);
    try {
      const state = await server.api('/api/state');
      const home = state.display.page;
      assert.ok(home, `${name} has no home page (display.page is ${home})`);

      const page = await context.newPage();
      const problems = watchProblems(page);
      const res = await page.goto(`${server.base}/pages/${home}`, { waitUntil: 'load' });
      assert.equal(res.status(), 200);

      const seen = await page.evaluate(async () => {
        await document.fonts.ready;
        await Promise.all([...document.images].map((img) => img.decode().catch(() => {})));
        return {
          brokenImages: [...document.images].filter((img) => !img.complete || img.naturalWidth === 0).map((img) => img.src),
          text: document.body.innerText.trim(),
          acts: [...document.querySelectorAll('[data-act]')].map((el) => el.dataset.act),
          width: document.documentElement.scrollWidth,
        };
      });
      assert.deepEqual(seen.brokenImages, [], 'images that did not load');
      assert.ok(seen.text.length > 0, 'the page shows no text');
      const { acts } = await server.api('/api/acts');
      const labels = new Set(acts.map((a) => a.label));
      assert.deepEqual(seen.acts.filter((a) => !labels.has(a)), [], 'data-act labels that are not acts of the bundle');
      assert.ok(seen.width <= VIEWPORT.width, `the page is ${seen.width} px wide: it scrolls sideways at 1280x800`);

      await page.screenshot({ path: path.join(SCREENSHOTS, `${name}.png`) });
      assert.deepEqual(problems, [], `problems on /pages/${home}`);
    } finally {
      await context.close();
      const exit = await server.stop();
      assert.deepEqual(exit, { code: 0, signal: null }, `docent did not exit cleanly:\n${server.output()}`);
    }
  });
}
