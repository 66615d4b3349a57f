// A kiosk tab that crashes, in headless Chromium against the real docent binary. The kiosk page
// takes its name from its address (`/?kiosk=entrance`); `Page.crash` kills its renderer, its
// websocket vanishes without a close frame, and Docent logs `client.left` with
// `ended: "lost"` and the name. The operator console names the kiosk in a banner at once, with
// what happens next and how long it has been gone; a new kiosk page of that name (what the kiosk
// PC's watchdog brings by restarting the browser) makes the banner go and the history say it is
// back. A page that reloads (a close it chose) brings no banner. Every wait is for an event or
// an element, with a deadline only.

import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext, watchExceptions } from './lib/browser.mjs';
import { corpusEvents, DEADLINE_MS, makeBundle, removeTemp, startDocent } from './lib/docent.mjs';
import { waitForShownPage } from './lib/kiosk.mjs';
import { newConsoleContext, signIn } from './lib/operator.mjs';
import { connectOperator } from './lib/ws-client.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

const PAGE = '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>home</title></head><body><p>Welcome</p></body></html>\n';

/** Opens the kiosk shell named `name` in a new page of `context`, showing its home page. */
async function openNamedKiosk(context, server, name) {
  const page = await context.newPage();
  const res = await page.goto(`${server.base}/?kiosk=${encodeURIComponent(name)}`);
  assert.equal(res.status(), 200);
  await waitForShownPage(page, 'index.html');
  return page;
}

test('kiosk and projector pages say hello with the name in their address, a bad one as their role', async () => {
  const bundle = makeBundle({ 'acts.yaml': '- Label: OK\n  Cmds: [DISPLAY_PAGE index.html]\n', 'pages/index.html': PAGE });
  const server = await startDocent(bundle);
  const operator = await connectOperator(server.wsUrl);
  const context = await newTouchContext(browser);
  try {
    const named = async (path) => {
      const page = await context.newPage();
      await page.goto(`${server.base}${path}`);
      return operator.waitForEvent((e) => e.type === 'client.connected' && e.role !== 'operator');
    };
    assert.equal((await named('/projector?projector=hall')).name, 'hall');
    assert.equal((await named('/?kiosk=%0Aentrance')).name, 'kiosk');
    assert.equal((await named('/?kiosk=' + 'x'.repeat(41))).name, 'kiosk');
    assert.equal((await named('/')).name, 'kiosk');
  } finally {
    await context.close();
    await operator.close();
    await server.stop();
    removeTemp(bundle);
  }
});

test('a crashed kiosk tab is named on the console until a kiosk of that name is back', { timeout: 90_000 }, async () => {
  const bundle = makeBundle({
    'acts.yaml': '- Label: OK\n  Cmds: [DISPLAY_PAGE index.html]\n',
    'pages/index.html': PAGE,
  });
  const server = await startDocent(bundle);
  const operator = await connectOperator(server.wsUrl);
  const consoleContext = await newConsoleContext(browser);
  const kiosks = await newTouchContext(browser);
  try {
    const console = await consoleContext.newPage();
    const exceptions = watchExceptions(console);
    await signIn(console, server);
    const banner = console.locator('#kiosk-banner');
    assert.equal(await banner.getAttribute('role'), 'alert');
    assert.equal(await banner.isHidden(), true);

    const kiosk = await openNamedKiosk(kiosks, server, 'entrance');
    const joined = await operator.waitForEvent((e) => e.type === 'client.connected' && e.role === 'kiosk');
    assert.equal(joined.name, 'entrance');

    // The renderer dies; the browser process lives on, as on a kiosk PC.
    const cdp = await kiosks.newCDPSession(kiosk);
    cdp.send('Page.crash').catch(() => {}); // never answered: the page is gone
    const left = await operator.waitForEvent((e) => e.type === 'client.left' && e.client === joined.client);
    assert.equal(left.ended, 'lost', JSON.stringify(left));
    assert.equal(left.name, 'entrance');
    assert.equal(left.code, undefined);

    const line = console.locator('#kiosk-banner p[data-name="entrance"]');
    await line.waitFor({ timeout: DEADLINE_MS });
    const said = await line.textContent();
    assert.match(
      said,
      /^Kiosk “entrance” lost its connection at \d\d:\d\d:\d\d without closing it \(its browser crashed, was killed, or the network failed\)\. Its watchdog restarts the browser; if it is not back within a minute, check the kiosk PC \(docs\/DEVICE\.md\)\. Gone for \d+\.\d s\.$/,
    );
    // How long it has been gone goes on counting.
    const gone = console.locator('#kiosk-banner .kiosk-gone');
    const first = await gone.textContent();
    await console.waitForFunction((before) => document.querySelector('#kiosk-banner .kiosk-gone')?.textContent !== before, first, {
      timeout: DEADLINE_MS,
    });

    // The watchdog's restart: a new page of that name.
    const again = await openNamedKiosk(kiosks, server, 'entrance');
    const back = await operator.waitForEvent((e) => e.type === 'client.connected' && e.name === 'entrance');
    await banner.waitFor({ state: 'hidden', timeout: DEADLINE_MS });
    const history = console.locator('#history li[data-type="client.back"]');
    await history.waitFor({ timeout: DEADLINE_MS });
    const away = ((back.mono_us - left.mono_us) / 1000 / 1000).toFixed(1); // as the console counts
    assert.match(await history.textContent(), new RegExp(`Kiosk “entrance” is back after ${away.replace('.', '\\.')} s`));

    // A reload closes the socket on purpose: no banner.
    await again.reload();
    const closed = await operator.waitForEvent((e) => e.type === 'client.left' && e.client === back.client);
    assert.equal(closed.ended, 'closed', JSON.stringify(closed));
    const rejoined = await operator.waitForEvent((e) => e.type === 'client.connected' && e.name === 'entrance');
    await console.locator(`#clients li[data-client="${rejoined.client}"]`).waitFor({ timeout: DEADLINE_MS });
    assert.equal(await banner.isHidden(), true);
    assert.deepEqual(exceptions, []);

    await operator.close();
    await server.stop();
    const logged = corpusEvents(server.corpus).filter((e) => e.type === 'client.left' && e.role === 'kiosk');
    assert.deepEqual(
      logged.map((e) => [e.name, e.ended]),
      [
        ['entrance', 'lost'],
        ['entrance', 'closed'],
        ['entrance', 'server'],
      ],
    );
  } finally {
    await kiosks.close();
    await consoleContext.close();
    await operator.close();
    await server.stop();
    removeTemp(bundle);
  }
});
