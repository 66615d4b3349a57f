// Live reload in headless Chromium: the real `docent` binary watches a bundle in a temporary
// folder (watching is on by default). A kiosk showing a page reloads it when the page file is
// saved; an operator console shows the banner for a save with errors, at the problem's file,
// line and column (a note listed as a note, not counted as an error), and hides it once a
// fixed save is live. Every wait is for an event, a frame
// or an element, with a deadline only.

import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext, watchExceptions } from './lib/browser.mjs';
import { DEADLINE_MS, makeBundle, removeTemp, startDocent } from './lib/docent.mjs';
import { openShell, waitForShownPage } from './lib/kiosk.mjs';
import { newConsoleContext, signIn } from './lib/operator.mjs';
import { connectOperator } from './lib/ws-client.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

const page = (title) =>
  `<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>${title}</title></head>\n` +
  `<body><h1 id="title">${title}</h1><button data-act="GREET">Hello</button></body></html>\n`;

const acts = (text) => `- Label: GREET\n  Text:\n    - ${text}\n`;
const BROKEN = '- Label: GREET\n  Text:\n    - Hello\n  Cmds:\n    - FLY_AWAY now\n';

/** Runs `body` with a watched bundle, a server and an operator websocket; cleans up after. */
async function withWatchedServer(body) {
  const bundle = makeBundle({ 'acts.yaml': acts('Hello'), 'pages/index.html': page('First version') });
  const server = await startDocent(bundle);
  const operator = await connectOperator(server.wsUrl);
  try {
    await body({ bundle, server, operator });
  } finally {
    await operator.close();
    await server.stop();
    removeTemp(bundle);
  }
}

test('a kiosk showing a page reloads it when the page file is saved', { timeout: 60_000 }, async () => {
  await withWatchedServer(async ({ bundle, server, operator }) => {
    const context = await newTouchContext(browser);
    try {
      const kiosk = await context.newPage();
      const exceptions = watchExceptions(kiosk);
      const frame = await openShell(kiosk, server, 'index.html');
      assert.equal(await frame.locator('#title').textContent(), 'First version');
      fs.writeFileSync(path.join(bundle, 'pages/index.html'), page('Second version'));
      const live = await operator.waitForEvent((e) => e.type === 'bundle.reloaded');
      assert.deepEqual(live.changed, ['pages/index.html']);
      // The shell swaps in a fresh load of the same page: wait for its new content.
      await kiosk.waitForFunction(
        () => document.querySelector('iframe.docent-frame.shown')?.contentDocument?.getElementById('title')?.textContent === 'Second version',
        null,
        { timeout: DEADLINE_MS, polling: 'raf' },
      );
      const shown = await waitForShownPage(kiosk, 'index.html');
      assert.equal(await shown.locator('#title').textContent(), 'Second version');
      assert.deepEqual(exceptions, []);
    } finally {
      await context.close();
    }
  });
});

test('an operator console shows the banner for a broken save and hides it after the fix', { timeout: 60_000 }, async () => {
  await withWatchedServer(async ({ bundle, server, operator }) => {
    const context = await newConsoleContext(browser);
    try {
      const console = await context.newPage();
      const exceptions = watchExceptions(console);
      await signIn(console, server);
      const banner = console.locator('#reload-banner');
      assert.equal(await banner.isHidden(), true);

      // A Mac's `.DS_Store` beside the broken save: listed as a note, not counted as an error.
      fs.writeFileSync(path.join(bundle, '.DS_Store'), '\0\0\0\u0001Bud1\0');
      fs.writeFileSync(path.join(bundle, 'acts.yaml'), BROKEN);
      await operator.waitForEvent((e) => e.type === 'bundle.refused');
      await banner.waitFor({ state: 'visible', timeout: DEADLINE_MS });
      const problem = banner.locator('li[data-code="unknown-verb"]');
      assert.match(await problem.textContent(), /^acts\.yaml, line 5, column 7: .*FLY_AWAY/);
      assert.match(await banner.textContent(), /1 error\(s\) and was not put live/);
      const note = banner.locator('li[data-code="ignored-files"]');
      assert.match(await note.textContent(), /^\.DS_Store, line 1, column 1: .*\(note: ignored-files\)$/);

      // A console opened now shows the same banner (from its welcome).
      const late = await context.newPage();
      await signIn(late, server, 'e2e-late');
      await late.locator('#reload-banner li[data-code="unknown-verb"]').waitFor({ timeout: DEADLINE_MS });
      await late.close();

      fs.writeFileSync(path.join(bundle, 'acts.yaml'), acts('Hello again'));
      await operator.waitForEvent((e) => e.type === 'bundle.reloaded');
      await banner.waitFor({ state: 'hidden', timeout: DEADLINE_MS });
      assert.deepEqual(exceptions, []);
    } finally {
      await context.close();
    }
  });
});
