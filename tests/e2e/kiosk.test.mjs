// The kiosk shell (`GET /`) in headless Chromium, driven as a visitor would drive it: taps on a
// touch screen, page timers, a server restart, idle visitors. Each test runs the real `docent`
// binary; an operator websocket client reads the server's events, so every wait is for an
// event (a frame, a page shown), with a deadline only.

import assert from 'node:assert/strict';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext, watchExceptions, watchProblems } from './lib/browser.mjs';
import { copyBundle, corpusEvents, freePort, makeBundle, removeTemp, REPO, startDocent } from './lib/docent.mjs';
import { openShell, waitForShownPage } from './lib/kiosk.mjs';
import { connectAutoAdapter, connectOperator } from './lib/ws-client.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

/** Runs `body(ctx)` with a server on `bundle`, a touch page and an operator; cleans up after. */
async function withKiosk(bundle, body, { port } = {}) {
  const server = await startDocent(bundle, { port });
  const context = await newTouchContext(browser);
  const cleanup = [() => context.close(), () => server.stop()];
  try {
    const operator = await connectOperator(server.wsUrl);
    cleanup.unshift(() => operator.close());
    const page = await context.newPage();
    await body({ server, page, operator, cleanup });
  } finally {
    for (const step of cleanup) await step();
  }
}

const page = (title, body = '') =>
  `<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>${title}</title></head>\n` +
  `<body><h1>${title}</h1>${body}</body></html>\n`;

test('tapping a data-act button changes the page and its SAY reaches a ws adapter and the corpus log', { timeout: 60_000 }, async () => {
  // The museum tour with speech sent to websocket adapters and a fast simulated drive, so that
  // "Start the tour" (GO_TO_MINICOMPUTER: SAY, drive, WAIT, DISPLAY_PAGE) ends quickly.
  const bundle = copyBundle('museum-tour', {
    'docent.yaml': [
      'home: index.html',
      'contexts: [TextGroup, TextChild]',
      'languages: [en, de]',
      'speech: {adapter: ws}',
      'drive:',
      '  speed: 100',
      '  pose_rate: 50',
      '  bounds: { min_x: 0, min_y: 0, max_x: 20, max_y: 12 }',
      '',
    ].join('\n'),
  });
  try {
    let server;
    let say;
    await withKiosk(bundle, async (kiosk) => {
      server = kiosk.server;
      const adapter = await connectAutoAdapter(server.wsUrl, ['SAY'], 'e2e-speech');
      kiosk.cleanup.unshift(() => adapter.close());
      const problems = watchProblems(kiosk.page);

      const home = await openShell(kiosk.page, server, 'index.html');
      await home.locator('[data-act="GO_TO_MINICOMPUTER"]').first().tap();

      say = await adapter.waitFor((f) => f.type === 'command' && f.verb === 'SAY');
      assert.equal(say.label, 'GO_TO_MINICOMPUTER');
      assert.ok(say.arg.length > 0, 'the SAY has no text');
      await waitForShownPage(kiosk.page, 'minicomputer.html');
      await kiosk.operator.waitForEvent((e) => e.type === 'command.done' && e.command === say.id);
      assert.deepEqual(problems, [], 'problems in the kiosk shell');
    });

    // The server has stopped gracefully: the corpus log is complete.
    const events = corpusEvents(server.corpus);
    const triggered = events.find((e) => e.type === 'act.triggered' && e.trigger === say.trigger);
    assert.equal(triggered?.label, 'GO_TO_MINICOMPUTER');
    assert.equal(triggered.source, 'kiosk', 'the act was not triggered by the kiosk');
    const sent = events.find((e) => e.type === 'command.sent' && e.command === say.id);
    assert.deepEqual([sent?.verb, sent?.arg, sent?.adapter], ['SAY', say.arg, 'ws']);
    assert.ok(events.some((e) => e.type === 'command.done' && e.command === say.id), 'no command.done for the SAY');
    assert.ok(events.some((e) => e.type === 'display.changed' && e.page === 'minicomputer.html'));
  } finally {
    removeTemp(bundle);
  }
});

test('after a server restart on the same port the kiosk stays on its page and is connected again', { timeout: 90_000 }, async () => {
  const bundle = path.join(REPO, 'dialogs/info-terminal');
  const port = await freePort();
  const context = await newTouchContext(browser);
  let server = await startDocent(bundle, { port });
  try {
    const page = await context.newPage();
    const exceptions = watchExceptions(page);
    await openShell(page, server, 'index.html');
    await server.trigger('SHOW_MAP');
    const map = await waitForShownPage(page, 'map.html');

    assert.equal(await map.locator('.docent-offline-notice').count(), 0, 'outage notice while connected');
    await server.stop();
    // After a moment without a connection the page says, calmly, that the robot will be back.
    await map.locator('.docent-offline-notice').waitFor({ state: 'visible', timeout: 15_000 });
    server = await startDocent(bundle, { port });
    // The kiosk tells the new run where it is (hello.page): it stays on the map.
    await map.locator('.docent-offline-notice').waitFor({ state: 'hidden', timeout: 15_000 });
    assert.equal((await server.api('/api/state')).display.page, 'map.html');
    // And it is connected again: a display command reaches it.
    await server.trigger('SHOW_SCHEDULE');
    await waitForShownPage(page, 'schedule.html');
    const state = await server.api('/api/state');
    assert.ok(
      Object.values(state.clients).some((c) => c.role === 'kiosk'),
      `no kiosk among the clients after the restart: ${JSON.stringify(state.clients)}`,
    );
    assert.deepEqual(exceptions, []);
  } finally {
    await context.close();
    await server.stop();
  }
});

test('the context menu is blocked inside a content page', { timeout: 60_000 }, async () => {
  await withKiosk(path.join(REPO, 'dialogs/info-terminal'), async ({ server, page }) => {
    const problems = watchProblems(page);
    const frame = await openShell(page, server, 'index.html');
    // Registered last, on the window: runs after the shell's or page script's own handlers.
    await frame.evaluate(() => {
      window.e2eContextMenus = [];
      window.addEventListener('contextmenu', (e) => window.e2eContextMenus.push(e.defaultPrevented));
    });
    const heading = await frame.locator('h1').boundingBox();
    await page.mouse.click(heading.x + heading.width / 2, heading.y + heading.height / 2, { button: 'right' });
    await frame.waitForFunction(() => window.e2eContextMenus.length > 0, null, { timeout: 10_000 });
    assert.deepEqual(await frame.evaluate(() => window.e2eContextMenus), [true], 'the contextmenu event was not cancelled');
    assert.deepEqual(problems, [], 'problems in the kiosk shell');
  });
});

test('a data-act-after timer fires its act, and leaving the page first cancels it', { timeout: 60_000 }, async () => {
  const bundle = makeBundle({
    'acts.yaml': [
      ['SHOW_TIMED', 'timed.html'],
      ['TIMER_FIRED', 'fired.html'],
      ['SHOW_SLOW', 'slow.html'],
      ['SLOW_TIMER_FIRED', 'fired.html'],
      ['LEAVE', 'left.html'],
      ['SENTINEL', 'index.html'],
    ]
      .map(([label, target]) => `- Label: ${label}\n  Cmds:\n    - DISPLAY_PAGE ${target}\n`)
      .join(''),
    'pages/index.html': page('Home'),
    'pages/timed.html': page('Timed', '<button type="button" data-act="TIMER_FIRED" data-act-after="300ms">Next</button>'),
    'pages/fired.html': page('Fired'),
    'pages/slow.html': page('Slow', '<button type="button" data-act="SLOW_TIMER_FIRED" data-act-after="1s">Next</button>'),
    // Its own timer is the clock that says the slow page's timer would long have fired.
    'pages/left.html': page('Left', '<button type="button" data-act="SENTINEL" data-act-after="2s">Home</button>'),
  });
  try {
    await withKiosk(bundle, async ({ server, page: shell, operator }) => {
      const problems = watchProblems(shell);
      await openShell(shell, server, 'index.html');

      // Fires: the act is triggered by the kiosk no sooner than 300 ms after the page changed.
      await server.trigger('SHOW_TIMED');
      const shown = await operator.waitForEvent((e) => e.type === 'display.changed' && e.page === 'timed.html');
      const fired = await operator.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'TIMER_FIRED');
      assert.equal(fired.source, 'kiosk');
      const delayMs = (fired.mono_us - shown.mono_us) / 1000;
      assert.ok(delayMs >= 300, `the 300ms timer fired after ${delayMs} ms`);
      await waitForShownPage(shell, 'fired.html');

      // Cancelled: leave the slow page (1 s timer) at once; its act must never come.
      await server.trigger('SHOW_SLOW');
      const slow = await operator.waitForEvent((e) => e.type === 'display.changed' && e.page === 'slow.html');
      await waitForShownPage(shell, 'slow.html');
      await server.trigger('LEAVE');
      const left = await operator.waitForEvent((e) => e.type === 'display.changed' && e.page === 'left.html');
      const stayedMs = (left.mono_us - slow.mono_us) / 1000;
      assert.ok(stayedMs < 1000, `the test left the slow page only after ${stayedMs} ms: inconclusive`);
      await waitForShownPage(shell, 'left.html');
      await operator.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'SENTINEL');
      const stray = operator.events().filter((e) => e.type === 'act.triggered' && e.label === 'SLOW_TIMER_FIRED');
      assert.deepEqual(stray, [], 'the timer of a page no longer shown fired');
      await waitForShownPage(shell, 'index.html');
      assert.deepEqual(problems, [], 'problems in the kiosk shell');
    });
  } finally {
    removeTemp(bundle);
  }
});

/** A bundle whose kiosk returns home after 1 s without a touch. */
const idleBundle = () =>
  makeBundle({
    'docent.yaml': 'home: index.html\nkiosk: {idle: 1s}\n',
    'acts.yaml': '- Label: SHOW_OTHER\n  Cmds:\n    - DISPLAY_PAGE other.html\n',
    'pages/index.html': page('Home'),
    'pages/other.html': page('Other', '<p>Nothing to press here.</p>'),
  });

/** Shows other.html, touches it once and waits until the kiosk is back home; returns the ms. */
async function idleReturn({ server, page: shell }) {
  await openShell(shell, server, 'index.html');
  await server.trigger('SHOW_OTHER');
  const frame = await waitForShownPage(shell, 'other.html');
  const touched = Date.now();
  await frame.locator('p').tap();
  await waitForShownPage(shell, 'index.html', { timeout: 10_000 });
  return Date.now() - touched;
}

test('after the idle time without a touch the kiosk returns to the home page', { timeout: 60_000 }, async () => {
  const bundle = idleBundle();
  try {
    await withKiosk(bundle, async (kiosk) => {
      const problems = watchProblems(kiosk.page);
      const idleMs = await idleReturn(kiosk);
      assert.ok(idleMs >= 1000, `returned home ${idleMs} ms after the last touch; the idle time is 1 s`);
      assert.deepEqual(problems, [], 'problems in the kiosk shell');
    });
  } finally {
    removeTemp(bundle);
  }
});
test('the idle return home is known to the server: display state and corpus log', { timeout: 60_000 }, async () => {
  // Otherwise GET /api/state and the corpus say the kiosk still shows other.html, and a
  // reconnecting kiosk would be sent back there.
  const bundle = idleBundle();
  try {
    await withKiosk(bundle, async (kiosk) => {
      await idleReturn(kiosk);
      await kiosk.operator.waitForEvent((e) => e.type === 'display.changed' && e.page === 'index.html', {
        timeout: 5_000,
        what: 'the server publishing display.changed to index.html after the idle return',
      });
      const state = await kiosk.server.api('/api/state');
      assert.equal(state.display.page, 'index.html');
    });
  } finally {
    removeTemp(bundle);
  }
});

test('the corpus names a visitor\'s touches, with the element, and never a page\'s timer or the idle return', { timeout: 60_000 }, async () => {
  const bundle = makeBundle({
    'docent.yaml': 'home: index.html\nspeech: {adapter: log}\nkiosk: {idle: 1s}\n',
    'acts.yaml': '- Label: HINT\n  Text: [Touch the screen.]\n- Label: GREET\n  Text: [Hello!]\n',
    'pages/index.html': page('Home', '<p data-act="HINT" data-act-after="300ms"></p><a id="more" href="other.html">More</a>'),
    'pages/other.html': page('Other', '<button type="button" id="hello" data-act="GREET">Hello</button>'),
  });
  try {
    await withKiosk(bundle, async ({ server, page: shell, operator }) => {
      const problems = watchProblems(shell);
      const home = await openShell(shell, server, 'index.html');
      // The page's timer: a trigger from the kiosk, but no visitor, so no session and no touch.
      await operator.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'HINT');
      const early = operator.events().filter((e) => e.type === 'touch' || e.type === 'session.started');
      assert.deepEqual(early, [], 'a timer is not a touch');

      await home.locator('#more').tap();
      const link = await operator.waitForEvent((e) => e.type === 'touch');
      assert.equal(link.link, 'other.html');
      assert.equal(link.page, 'index.html');
      assert.equal(link.element, 'a#more[href=other.html] "More"');
      const other = await waitForShownPage(shell, 'other.html');
      await other.locator('#hello').tap();
      const tap = await operator.waitForEvent((e) => e.type === 'touch');
      assert.deepEqual([tap.act, tap.page, tap.element], ['GREET', 'other.html', 'button#hello[data-act=GREET] "Hello"']);

      // The idle return home and the timer there again: neither is a touch.
      await waitForShownPage(shell, 'index.html', { timeout: 10_000 });
      const back = await operator.waitForEvent((e) => e.type === 'display.changed' && e.page === 'index.html' && e.seq > tap.seq);
      await operator.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'HINT' && e.seq > back.seq);
      const touches = operator.events().filter((e) => e.type === 'touch');
      assert.equal(touches.length, 2, JSON.stringify(touches));
      const started = operator.events().filter((e) => e.type === 'session.started');
      assert.equal(started.length, 1);
      assert.ok(started[0].seq < link.seq, 'the first touch started the session, before its own event');
      assert.deepEqual(problems, [], 'problems in the kiosk shell');
    });
  } finally {
    removeTemp(bundle);
  }
});

test('a kiosk may trigger only the acts its pages offer', { timeout: 60_000 }, async () => {
  const bundle = makeBundle({
    'acts.yaml': [
      '- Label: OFFERED',
      '  Text: Hello.',
      '- Label: SECRET',
      '  Text: Only the operator says this.',
      '',
    ].join('\n'),
    'docent.yaml': 'speech: {adapter: log}\n',
    'pages/index.html': page('Home', '<button data-act="OFFERED">Hello</button>'),
  });
  try {
    await withKiosk(bundle, async ({ server, page: shell, operator }) => {
      const home = await openShell(shell, server, 'index.html');
      // A page script asks for an act no page offers, as a tampered page or a stranger would.
      const refused = await home.evaluate(() => docent.trigger('SECRET'));
      assert.equal(refused.type, 'error');
      assert.equal(refused.code, 'not-offered');
      const logged = await operator.waitForEvent((e) => e.type === 'trigger.refused');
      assert.deepEqual([logged.label, logged.code, logged.source], ['SECRET', 'not-offered', 'kiosk']);
      // What the page offers still works.
      await home.locator('[data-act="OFFERED"]').tap();
      const act = await operator.waitForEvent((e) => e.type === 'act.triggered');
      assert.deepEqual([act.label, act.source], ['OFFERED', 'kiosk']);
    });
  } finally {
    removeTemp(bundle);
  }
});
