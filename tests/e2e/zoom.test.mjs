// Zoom on the kiosk: a pinch must not zoom the touchscreen and a double tap must not zoom a
// page. The same gesture first zooms an ordinary page (so the test can fail), then leaves the
// kiosk shell at scale 1, both in a plain browser (the shell's viewport forbids zooming) and in
// one with the `--disable-pinch` flag kiosk/launch.sh passes. Double-tap zoom is blocked by
// `touch-action: manipulation`, which the page script gives every page.

import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';

import { launchBrowser, VIEWPORT } from './lib/browser.mjs';
import { REPO, startDocent } from './lib/docent.mjs';
import { openShell } from './lib/kiosk.mjs';


/** Pinches out at the middle of `page` with the mouse-source gesture that zooms a desktop page. */
async function pinch(context, page) {
  const cdp = await context.newCDPSession(page);
  await cdp.send('Input.synthesizePinchGesture', {
    x: VIEWPORT.width / 2,
    y: VIEWPORT.height / 2,
    scaleFactor: 2.5,
    gestureSourceType: 'mouse',
  });
  return page.evaluate(() => window.visualViewport.scale);
}

async function withBrowser(extraArgs, body) {
  const browser = await launchBrowser(extraArgs);
  try {
    const context = await browser.newContext({ viewport: VIEWPORT, hasTouch: true });
    await body(context);
  } finally {
    await browser.close();
  }
}

test('a pinch does not zoom the kiosk, and a double tap cannot zoom a page', { timeout: 60_000 }, async () => {
  const server = await startDocent(path.join(REPO, 'dialogs/info-terminal'));
  try {
    // Even without the launcher's flag: the shell's viewport forbids zooming.
    await withBrowser([], async (context) => {
      const plain = await context.newPage();
      await plain.setContent('<html><body><p>an ordinary page</p></body></html>');
      const control = await pinch(context, plain);
      assert.ok(control > 1.5, `the gesture zooms an ordinary page (scale ${control}); otherwise this test proves nothing`);
      const page = await context.newPage();
      const frame = await openShell(page, server, 'index.html');
      assert.equal(await pinch(context, page), 1, 'a pinch zoomed the kiosk shell');
      const touchAction = await frame.evaluate(() => getComputedStyle(document.documentElement).touchAction);
      assert.equal(touchAction, 'manipulation', 'double-tap zoom is not blocked in the page');
    });
    // And with the flag the kiosk launcher passes.
    const launcher = fs.readFileSync(path.join(REPO, 'kiosk/launch.sh'), 'utf8');
    assert.match(launcher, /--disable-pinch/, 'kiosk/launch.sh passes --disable-pinch');
    await withBrowser(['--disable-pinch'], async (context) => {
      const page = await context.newPage();
      await openShell(page, server, 'index.html');
      assert.equal(await pinch(context, page), 1, 'a pinch zoomed the kiosk shell');
    });
  } finally {
    await server.stop();
  }
});
