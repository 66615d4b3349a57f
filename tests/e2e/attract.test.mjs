// The kiosk's attract loop and opening hours in headless Chromium, on Playwright's fake page
// clock: after the configured quiet time the loop cycles its pages (each for its time); the
// first touch ends it on the home page without triggering what was under the finger, and is a
// visitor's first touch (a session starts), while the loop's pages start none; a schedule at a
// fixed wall-clock time shows the closed page, then each range's home page, by the kiosk's own
// clock. Every wait is for an event or a page on screen; time moves only by the fake clock.

import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext } from './lib/browser.mjs';
import { makeBundle, removeTemp, startDocent } from './lib/docent.mjs';
import { openShell, shownPage, waitForShownPage } from './lib/kiosk.mjs';
import { connectOperator } from './lib/ws-client.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

const PAGE = (title, body) => `<!DOCTYPE html><html lang="en"><title>${title}</title><body>${body}</body></html>`;
// A button covering the whole page: any touch lands on it.
const BIG_BUTTON = (label) => `<button data-act="${label}" style="position:fixed;inset:0">${label}</button>`;

async function withKiosk(files, body) {
  const dir = makeBundle(files);
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

/** Stops the page clock where it is (it ran on its own while the shell loaded). */
async function pauseNow(page) {
  await page.clock.pauseAt(await page.evaluate(() => Date.now() + 500));
}

const shownOnServer = (page) => (e) => e.type === 'display.changed' && e.page === page;

test('the attract loop cycles its pages, and the first touch ends it at home without triggering what it touched', { timeout: 90_000 }, async () => {
  const files = {
    'docent.yaml': 'home: index.html\nspeech: {adapter: log}\nkiosk:\n  idle: 0s\n  attract: {after: 5s, pages: [attract/a.html, attract/b.html], every: 3s}\n',
    'acts.yaml': '- Label: HELLO\n  Text: Hello!\n- Label: TEASER\n  Text: Look here!\n',
    'pages/index.html': PAGE('home', BIG_BUTTON('HELLO')),
    'pages/attract/a.html': PAGE('attract a', BIG_BUTTON('TEASER')),
    'pages/attract/b.html': PAGE('attract b', '<h1>Touch me</h1>'),
  };
  await withKiosk(files, async ({ server, operator, page }) => {
    await page.clock.install({ time: new Date(2025, 11, 1, 10, 0, 0) });
    await openShell(page, server, 'index.html');
    await operator.waitForEvent((e) => e.type === 'client.connected' && e.role === 'kiosk');
    await pauseNow(page);

    await page.clock.runFor(2_000);
    assert.equal(await shownPage(page), '/pages/index.html', 'not yet: the loop starts after 5 s');
    await page.clock.runFor(4_000);
    await operator.waitForEvent((e) => e.type === 'attract.started');
    await operator.waitForEvent(shownOnServer('attract/a.html'));
    assert.equal(await shownPage(page), '/pages/attract/a.html');

    await page.clock.runFor(3_000);
    await operator.waitForEvent(shownOnServer('attract/b.html'));
    assert.equal(await shownPage(page), '/pages/attract/b.html');
    await page.clock.runFor(3_000);
    await operator.waitForEvent(shownOnServer('attract/a.html')); // the next one: a.html again
    await waitForShownPage(page, 'attract/a.html');
    assert.ok(!operator.events().some((e) => e.type === 'session.started'), 'the loop is not a visitor session');

    // The first touch lands on a.html's full-page TEASER button: it must not trigger it.
    await page.touchscreen.tap(640, 400);
    const ended = await operator.waitForEvent((e) => e.type === 'attract.ended');
    assert.equal(ended.by, 'touch');
    await operator.waitForEvent((e) => e.type === 'session.started');
    const touch = await operator.waitForEvent((e) => e.type === 'touch');
    assert.equal(touch.element, 'the attract loop');
    await operator.waitForEvent(shownOnServer('index.html'));
    await waitForShownPage(page, 'index.html');

    // The next touch is an ordinary one: its act is the first one triggered, so the first
    // touch triggered nothing (the kiosk's frames arrive in order).
    await page.touchscreen.tap(640, 400);
    const triggered = await operator.waitForEvent((e) => e.type === 'act.triggered');
    assert.equal(triggered.label, 'HELLO');
    const acts = operator.events().filter((e) => e.type === 'act.triggered').map((e) => e.label);
    assert.deepEqual(acts, ['HELLO']);
  });
});

test('an attract act is triggered by the kiosk, as the attract loop\'s and not a visitor\'s', { timeout: 60_000 }, async () => {
  const files = {
    'docent.yaml': 'home: index.html\nspeech: {adapter: log}\nkiosk:\n  idle: 0s\n  attract: {after: 2s, act: INVITE}\n',
    'acts.yaml': '- Label: INVITE\n  Text: Come closer!\n',
    'pages/index.html': PAGE('home', '<p>Welcome</p>'),
  };
  await withKiosk(files, async ({ server, operator, page }) => {
    await page.clock.install({ time: new Date(2025, 11, 1, 10, 0, 0) });
    await openShell(page, server, 'index.html');
    await operator.waitForEvent((e) => e.type === 'client.connected' && e.role === 'kiosk');
    await pauseNow(page);
    await page.clock.runFor(3_000);
    await operator.waitForEvent((e) => e.type === 'attract.started');
    const triggered = await operator.waitForEvent((e) => e.type === 'act.triggered');
    assert.equal(triggered.label, 'INVITE');
    assert.equal(triggered.source, 'kiosk');
    assert.ok(!operator.events().some((e) => e.type === 'touch' || e.type === 'session.started'));
  });
});

/** A bundle open Mon-Fri 09:00-12:00 (home: school.html) and 12:00-17:00, closed.html otherwise. */
function scheduledFiles() {
  return {
    'docent.yaml': [
      'home: index.html',
      'speech: {adapter: log}',
      'kiosk: {idle: 0s}',
      'schedule:',
      '  closed: closed.html',
      '  open:',
      '    - {days: Mon-Fri, hours: 09:00-12:00, home: school.html}',
      '    - {days: Mon-Fri, hours: 12:00-17:00}',
      '',
    ].join('\n'),
    'acts.yaml': '- Label: HELLO\n  Text: Hello!\n',
    'pages/index.html': PAGE('home', BIG_BUTTON('HELLO')),
    'pages/school.html': PAGE('school', '<p>Welcome, class</p>'),
    'pages/closed.html': PAGE('closed', '<p>We open at nine</p>'),
  };
}

/**
 * Opens the kiosk on Monday 2025-12-01 at 08:59:30 by its own clock, and waits until it shows
 * closed.html and the server is told so (although its display state began at the home page).
 */
async function closedBeforeNine(page, server, operator) {
  await page.clock.install({ time: new Date(2025, 11, 1, 8, 59, 30) });
  await page.goto(`${server.base}/`);
  await waitForShownPage(page, 'closed.html');
  await operator.waitForEvent(shownOnServer('closed.html'));
  await pauseNow(page);
}

test('a schedule at a fixed time shows the closed page, then each range\'s home page', { timeout: 90_000 }, async () => {
  await withKiosk(scheduledFiles(), async ({ server, operator, page }) => {
    await closedBeforeNine(page, server, operator); // about 08:59:31

    await page.clock.runFor(40_000); // about 09:00:11
    await operator.waitForEvent(shownOnServer('school.html'));
    assert.equal(await shownPage(page), '/pages/school.html');

    await page.clock.runFor(3 * 60 * 60_000); // about 12:00:11: the school's home gives way
    await operator.waitForEvent(shownOnServer('index.html'));
    assert.equal(await shownPage(page), '/pages/index.html');

    await page.clock.runFor(5 * 60 * 60_000); // about 17:00:11: closing time
    await operator.waitForEvent(shownOnServer('closed.html')); // the next one: closed again
    assert.equal(await shownPage(page), '/pages/closed.html');
    assert.ok(!operator.events().some((e) => e.type === 'session.started'), 'no visitor');
  });
});

test('while no answer about the hours comes, the kiosk keeps to the changes it was told', { timeout: 90_000 }, async () => {
  await withKiosk(scheduledFiles(), async ({ server, operator, page }) => {
    await closedBeforeNine(page, server, operator);
    // From here on every question about the hours goes unanswered.
    let asked = 0;
    await page.route('**/api/schedule/**', (route) => {
      asked += 1;
      return route.abort();
    });

    await page.clock.runFor(40_000); // about 09:00:11
    await operator.waitForEvent(shownOnServer('school.html'));
    assert.equal(await shownPage(page), '/pages/school.html');
    await page.clock.runFor(3 * 60 * 60_000); // about 12:00:11
    await operator.waitForEvent(shownOnServer('index.html'));
    assert.equal(await shownPage(page), '/pages/index.html');
    assert.ok(asked > 0, 'the kiosk did not ask again after a change');
  });
});
