// DISPLAY_PAGE in headless Chromium: done only once the kiosk shell has revealed the page (its
// bytes are held back until the test has seen that nothing claimed it shown), failed with the
// shell's reason when the page is not available, and failed at once when no touchscreen is
// connected. An operator websocket client reads the events; every wait is for an event.

import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext } from './lib/browser.mjs';
import { makeBundle, removeTemp, startDocent } from './lib/docent.mjs';
import { openShell, shownPage } from './lib/kiosk.mjs';
import { connectOperator } from './lib/ws-client.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

const ACTS = `- Label: MAP
  Cmds: [DISPLAY_PAGE map.html, WAIT, SAY Here is the map]
`;

function bundle() {
  return makeBundle({
    'docent.yaml': 'speech: {adapter: log}\n',
    'acts.yaml': ACTS,
    'pages/index.html': '<!DOCTYPE html><title>home</title><p>home</p>',
    'pages/map.html': '<!DOCTYPE html><title>map</title><p>map</p>',
  });
}

const is = (type, command) => (e) => e.type === type && e.command === command;

async function withServer(body) {
  const dir = bundle();
  const server = await startDocent(dir);
  const context = await newTouchContext(browser);
  const operator = await connectOperator(server.wsUrl);
  try {
    await body({ server, operator, page: await context.newPage() });
  } finally {
    await operator.close();
    await context.close();
    await server.stop();
    removeTemp(dir);
  }
}

test('DISPLAY_PAGE with no touchscreen connected fails at once and the WAIT reports it', { timeout: 60_000 }, async () => {
  await withServer(async ({ server, operator }) => {
    const [page, wait, say] = (await server.trigger('MAP')).commands.map((c) => c.id);
    const failed = await operator.waitForEvent(is('command.failed', page));
    assert.equal(failed.reason, 'no touchscreen connected');
    await operator.waitForEvent(is('command.failed', wait));
    assert.ok(!operator.events().some(is('command.sent', say)));
  });
});

test('DISPLAY_PAGE is done only after the kiosk shell revealed the page', { timeout: 60_000 }, async () => {
  await withServer(async ({ server, operator, page }) => {
    await openShell(page, server, 'index.html');
    await operator.waitForEvent((e) => e.type === 'client.connected' && e.role === 'kiosk');
    let requested;
    const asked = new Promise((resolve) => (requested = resolve));
    let release;
    const released = new Promise((resolve) => (release = resolve));
    await page.route('**/pages/map.html', async (route) => {
      requested();
      await released;
      await route.continue();
    });
    const [shown, wait, say] = (await server.trigger('MAP')).commands.map((c) => c.id);
    await asked;
    await operator.waitForEvent(is('command.started', shown));
    assert.ok(!operator.events().some(is('command.done', shown)), 'done before the page arrived');
    assert.equal(await shownPage(page), '/pages/index.html');
    release();
    await operator.waitForEvent(is('command.done', shown));
    assert.equal(await shownPage(page), '/pages/map.html', 'the page is on screen when it is done');
    await operator.waitForEvent(is('command.done', wait));
    await operator.waitForEvent(is('command.sent', say));
  });
});

test('a DISPLAY_PAGE the touchscreen cannot show fails with its reason', { timeout: 60_000 }, async () => {
  await withServer(async ({ server, operator, page }) => {
    await openShell(page, server, 'index.html');
    await operator.waitForEvent((e) => e.type === 'client.connected' && e.role === 'kiosk');
    // The file is gone after the bundle was loaded: the server answers its friendly 404 page.
    await page.route('**/pages/map.html', (route) => route.fulfill({
      status: 404,
      contentType: 'text/html',
      body: '<!DOCTYPE html><meta name="docent-page" content="missing"><title>not available</title>',
    }));
    const [shown] = (await server.trigger('MAP')).commands.map((c) => c.id);
    const failed = await operator.waitForEvent(is('command.failed', shown));
    assert.equal(failed.reason, 'the touchscreen could not show map.html: it is not available');
  });
});
