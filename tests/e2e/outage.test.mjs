// A calm outage (docs/AUTHORING.md, "While Docent is away"), in headless Chromium: the server
// is killed and started again on the same port while a kiosk shows the info terminal's map.
// Meanwhile the page shows a calm notice over none of its buttons, a tap answers "one moment"
// at once and fires nothing, then or later; after the return the kiosk is live within 2 s on
// the page the visitor was on. And the server side of that: a kiosk's hello names its page,
// a restarted server adopts a page of the bundle, refuses anything else, and lets a page the
// tour moved to while no kiosk was connected win.

import assert from 'node:assert/strict';
import path from 'node:path';
import { after, before, test } from 'node:test';

import WebSocket from 'ws';

import { launchBrowser, newTouchContext, watchExceptions } from './lib/browser.mjs';
import { copyBundle, DEADLINE_MS, freePort, removeTemp, REPO, startDocent, withDeadline } from './lib/docent.mjs';
import { openShell, shownPage, waitForShownPage } from './lib/kiosk.mjs';
import { outage, recordConnections } from './lib/outage.mjs';
import { DocentClient, connectOperator } from './lib/ws-client.mjs';

const BUNDLE = path.join(REPO, 'dialogs/info-terminal');
const LIVE_WITHIN_MS = 2_000;

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

/** Whether two client rectangles overlap. */
const overlap = (a, b) => a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height && b.y < a.y + a.height;

test('an outage shows a calm notice over no button, taps fire nothing, and the kiosk is back within 2 s on its page', { timeout: 120_000 }, async () => {
  let server = await startDocent(BUNDLE, { port: await freePort() });
  const context = await newTouchContext(browser);
  try {
    const tab = await context.newPage();
    const exceptions = watchExceptions(tab);
    await openShell(tab, server, 'index.html');
    await server.trigger('SHOW_MAP');
    let frame = await waitForShownPage(tab, 'map.html');
    await recordConnections(tab);

    // A short blip, then an outage long enough for the notice.
    for (const lengthMs of [300, 2_500]) {
      const tapped = [];
      const result = await outage({
        server,
        bundle: BUNDLE,
        tab,
        lengthMs,
        during: async () => {
          if (lengthMs < 1_000) return; // a blip passes without a word
          const notice = frame.locator('.docent-offline-notice');
          await notice.waitFor({ state: 'visible', timeout: DEADLINE_MS });
          assert.match(await notice.textContent(), /moment/);
          const box = await notice.boundingBox();
          for (const button of await frame.locator('[data-act]').all()) {
            assert.ok(!overlap(box, await button.boundingBox()), `the notice covers ${await button.textContent()}`);
          }
          // A tap on "Today's schedule" answers at once, and goes nowhere.
          const schedule = frame.locator('[data-act="SHOW_SCHEDULE"]');
          await schedule.tap();
          tapped.push('SHOW_SCHEDULE');
          assert.equal(await schedule.getAttribute('data-docent-busy'), '', 'the tapped button does not say "one moment"');
          assert.equal(await shownPage(tab), '/pages/map.html');
        },
      });
      server = result.server;
      assert.ok(result.liveMs <= LIVE_WITHIN_MS, `the kiosk was live ${result.liveMs} ms after the server accepted again`);
      // The visitor is still on the map, and it is live: the notice and the busy mark are gone.
      assert.equal(await shownPage(tab), '/pages/map.html', 'the kiosk left the page the visitor was on');
      frame = await waitForShownPage(tab, 'map.html');
      assert.equal(await frame.locator('.docent-offline-notice:visible').count(), 0);
      assert.equal(await frame.locator('[data-docent-busy]').count(), 0);
      const state = await server.api('/api/state');
      assert.equal(state.display.page, 'map.html', 'the restarted server did not adopt the kiosk\'s page');

      // A tap now works; the one during the outage never reaches the new server.
      const operator = await connectOperator(server.wsUrl);
      await frame.locator('[data-act="DESCRIBE_MAP"]').tap();
      await operator.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'DESCRIBE_MAP');
      const triggered = operator.events().filter((e) => e.type === 'act.triggered').map((e) => e.label);
      assert.deepEqual(triggered, ['DESCRIBE_MAP'], `stale triggers after the outage (tapped while away: ${tapped})`);
      await operator.close();
    }
    assert.deepEqual(exceptions, []);
  } finally {
    await context.close();
    await server.stop();
  }
});

/** A kiosk's hello naming `page`; resolves with every frame up to and including the welcome. */
async function kioskHello(wsUrl, page) {
  const client = new DocentClient(new WebSocket(wsUrl));
  await withDeadline(new Promise((resolve) => client.ws.once('open', resolve)), DEADLINE_MS, 'no connection');
  client.send({ type: 'hello', role: 'kiosk', name: 'e2e-kiosk', page });
  await client.waitFor((f) => f.type === 'welcome');
  return client;
}

test('a kiosk\'s hello names its page: adopted if of the bundle, refused otherwise, and a page the tour moved to meanwhile wins', { timeout: 60_000 }, async () => {
  const server = await startDocent(BUNDLE);
  try {
    // Not a page of the bundle: refused with a reason, and the kiosk is sent the server's page.
    let kiosk = await kioskHello(server.wsUrl, '../docent.yaml');
    const [refused, welcome] = kiosk.frames;
    assert.equal(refused.type, 'error');
    assert.equal(refused.code, 'unknown-page');
    assert.match(refused.message, /not a page of this bundle/);
    assert.equal(welcome.state.display.page, 'index.html');
    await kiosk.close();

    // A page of the bundle: the (fresh) server adopts it instead of sending the kiosk home.
    kiosk = await kioskHello(server.wsUrl, 'map.html');
    assert.equal(kiosk.frames[0].type, 'welcome');
    assert.equal(kiosk.frames[0].state.display.page, 'map.html');
    await kiosk.close();
    assert.equal((await server.api('/api/state')).display.page, 'map.html');

    // The tour moved on while no kiosk was connected: the returning kiosk is sent there.
    const operator = await connectOperator(server.wsUrl);
    await server.trigger('SHOW_SCHEDULE');
    await operator.waitForEvent((e) => e.type === 'command.failed' && e.verb === 'DISPLAY_PAGE');
    kiosk = await kioskHello(server.wsUrl, 'map.html');
    assert.equal(kiosk.frames[0].state.display.page, 'schedule.html');
    await kiosk.close();
    await operator.close();
  } finally {
    await server.stop();
  }
});

test('after a restart a kiosk whose page is gone from the bundle goes home', { timeout: 60_000 }, async () => {
  // Served from a copy with one more page; restarted on the original, which lacks it.
  const copy = copyBundle('info-terminal', {
    'pages/extra.html': '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>Extra</title></head><body><h1>Extra</h1></body></html>\n',
  });
  let server = await startDocent(copy, { port: await freePort() });
  const context = await newTouchContext(browser);
  try {
    const tab = await context.newPage();
    const frame = await openShell(tab, server, 'index.html');
    await tab.evaluate(() => {
      window.e2eErrors = [];
      window.docentShell.on('error', (f) => window.e2eErrors.push(f.code));
    });
    await recordConnections(tab);
    await frame.evaluate(() => { location.href = 'extra.html'; });
    await waitForShownPage(tab, 'extra.html');
    ({ server } = await outage({ server, bundle: BUNDLE, tab, lengthMs: 200 }));
    await waitForShownPage(tab, 'index.html');
    assert.deepEqual(await tab.evaluate(() => window.e2eErrors), ['unknown-page']);
  } finally {
    await context.close();
    await server.stop();
    removeTemp(copy);
  }
});
