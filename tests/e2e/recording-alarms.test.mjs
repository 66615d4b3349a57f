// Issue 28, findings 1 and 2, in headless Chromium with a fake microphone. (1) A kiosk that
// records and is closed normally (its tab closed, or navigated away) is no device failure: the
// corpus has no `recording.failed`, its recording stops as `kiosk-left`, and a console that
// signs in afterwards shows no recording alarm. A real device failure (the track ends while the
// page stays) shows one alert for that kiosk, which clears when the kiosk records again or the
// session ends; five failures of the same kiosk are never more than one alert, and a console
// signing in later shows only what is still wrong. (2) Alt+Down, Down, Enter on the console's
// consent selector asks first and deletes nothing; Escape cancels; once confirmed the recording
// is deleted, and the history and the corpus say so (with its bytes). The confirmation's
// screenshot at 1366x768 goes to target/e2e/recording-alarms/ (not committed). Every wait is
// for an event or a page state, with a deadline only.

import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext, watchExceptions } from './lib/browser.mjs';
import { corpusEvents, DEADLINE_MS, makeBundle, REPO, removeTemp, startDocent } from './lib/docent.mjs';
import { openShell, shownContentFrame } from './lib/kiosk.mjs';
import { signIn } from './lib/operator.mjs';
import { connectOperator } from './lib/ws-client.mjs';

const OUT = path.join(REPO, 'target/e2e/recording-alarms');
const AXE = fs.readFileSync(path.join(REPO, 'tests/e2e/node_modules/axe-core/axe.min.js'), 'utf8');
const LAPTOP = { width: 1366, height: 768 };

let browser;
before(async () => {
  browser = await launchBrowser(['--use-fake-device-for-media-stream', '--use-fake-ui-for-media-stream']);
  fs.mkdirSync(OUT, { recursive: true });
});
after(() => browser?.close());

function bundle() {
  return makeBundle({
    'acts.yaml': '- Label: HELLO\n  Text: [Hi]\n',
    'docent.yaml': 'speech: {adapter: log}\ncorpus: {session_idle: 0s}\n',
    'pages/index.html': '<html><body><button id="hello" data-act="HELLO" style="width:300px;height:200px">Hello</button></body></html>',
  });
}

async function withServer(body) {
  const files = bundle();
  const server = await startDocent(files);
  const op = await connectOperator(server.wsUrl);
  try {
    await body(server, op);
  } finally {
    await op.close().catch(() => {});
    await server.stop();
    removeTemp(files);
  }
}

// Runs in the kiosk's pages: keeps every stream the page opens, so the test can end a track
// as an unplugged device does, while the page stays.
function keepStreams() {
  if (!navigator.mediaDevices) return; // about:blank, where a kiosk navigated away
  const get = navigator.mediaDevices.getUserMedia.bind(navigator.mediaDevices);
  window.e2eStreams = [];
  navigator.mediaDevices.getUserMedia = async (constraints) => {
    const stream = await get(constraints);
    window.e2eStreams.push(stream);
    return stream;
  };
}

async function openKiosk(server, inBrowser = browser) {
  const context = await newTouchContext(inBrowser);
  await context.addInitScript(keepStreams);
  const page = await context.newPage();
  const errors = watchExceptions(page);
  await openShell(page, server, 'index.html');
  return { context, page, errors };
}

/** A visitor's tap: the touch that starts a session (consent `recorded`, the default). */
async function tap(page) {
  await (await shownContentFrame(page)).tap('#hello');
}

/** The kiosk's microphone ends as an unplugged one does; the page stays. */
function unplug(page) {
  return page.evaluate(() => window.e2eStreams.at(-1).getAudioTracks()[0].dispatchEvent(new Event('ended')));
}

/** Until the kiosk's current recording has stored a chunk. */
function aChunkStored(page) {
  return page.waitForFunction(() => window.docentRecorder.current?.acked > 0, null, { timeout: DEADLINE_MS });
}

async function newConsole(server, name, viewport = LAPTOP) {
  const context = await browser.newContext({ viewport });
  const page = await context.newPage();
  await signIn(page, server, name);
  // The /api/state snapshot is in: what it shows is what is current.
  await page.waitForFunction(() => Number(document.body.dataset.snapshots ?? 0) >= 1, null, { timeout: DEADLINE_MS });
  return { context, page };
}

// Runs in the console: the recording alarms it shows, one text per alert (an alert element
// without one line per kiosk counts as one).
function shownAlarms() {
  const alert = document.querySelector('#recording-alert');
  if (alert.hidden) return [];
  const lines = [...alert.querySelectorAll('p')].map((p) => p.textContent);
  return lines.length ? lines : [alert.textContent];
}

function alarms(page) {
  return page.evaluate(shownAlarms);
}

async function waitForAlarms(page, count) {
  await page.waitForFunction((n) => {
    const alert = document.querySelector('#recording-alert');
    return (alert.hidden ? 0 : Math.max(1, alert.querySelectorAll('p').length)) === n;
  }, count, { timeout: DEADLINE_MS });
}

test('a kiosk closed or navigated away while recording is no failure; a console signing in later shows no alarm', async () => {
  await withServer(async (server, op) => {
    // The evening shutdown: the kiosk's browser itself is closed.
    const kioskBrowser = await launchBrowser(['--use-fake-device-for-media-stream', '--use-fake-ui-for-media-stream']);
    let closed;
    let first;
    try {
      closed = await openKiosk(server, kioskBrowser);
      await tap(closed.page);
      first = await op.waitForEvent((e) => e.type === 'recording.started');
      await aChunkStored(closed.page);
    } finally {
      await kioskBrowser.close();
    }
    const firstStop = await op.waitForEvent((e) => e.type === 'recording.stopped' && e.recording === first.recording);
    assert.equal(firstStop.reason, 'kiosk-left', JSON.stringify(op.events().filter((e) => e.type.startsWith('recording.'))));

    const navigated = await openKiosk(server);
    const second = await op.waitForEvent((e) => e.type === 'recording.started' && e.recording !== first.recording);
    await aChunkStored(navigated.page);
    await navigated.page.close(); // a watchdog restart closes the tab
    const secondStop = await op.waitForEvent((e) => e.type === 'recording.stopped' && e.recording === second.recording);
    assert.equal(secondStop.reason, 'kiosk-left');
    // Reported before its connection ended, a failure would be in the log before the stop.
    assert.deepEqual(op.events().filter((e) => e.type === 'recording.failed'), [], 'closing or leaving a page fails nothing');

    const reloaded = await openKiosk(server);
    const third = await op.waitForEvent((e) => e.type === 'recording.started' && e.recording > second.recording);
    await aChunkStored(reloaded.page);
    await reloaded.page.goto('about:blank'); // navigated away
    const thirdStop = await op.waitForEvent((e) => e.type === 'recording.stopped' && e.recording === third.recording);
    assert.equal(thirdStop.reason, 'kiosk-left');
    assert.deepEqual(op.events().filter((e) => e.type === 'recording.failed'), [], 'navigating away fails nothing');

    // A kiosk whose device did fail, then left: its failure ended with it.
    const failing = await openKiosk(server);
    const fourth = await op.waitForEvent((e) => e.type === 'recording.started' && e.recording > third.recording);
    await unplug(failing.page);
    const failed = await op.waitForEvent((e) => e.type === 'recording.failed');
    assert.equal(failed.recording, fourth.recording);
    await failing.context.close();
    await op.waitForEvent((e) => e.type === 'client.left' && e.client === failed.client);

    const late = await newConsole(server, 'late-console');
    assert.deepEqual(await alarms(late.page), [], 'no kiosk is connected: nothing is wrong now');
    assert.equal(await late.page.locator('#recording-status').getAttribute('data-state'), 'off');
    const history = await late.page.locator('#history li').allTextContents();
    assert.ok(history.some((line) => /recording failed on kiosk #\d+ \(no-device\)/.test(line)), `the past is in the history: ${history.join(' | ')}`);
    await late.context.close();
    await navigated.context.close();
    await reloaded.context.close();
    assert.deepEqual([...closed.errors, ...navigated.errors, ...reloaded.errors], []);

    const recordingFailed = corpusEvents(server.corpus).filter((e) => e.type === 'recording.failed');
    assert.deepEqual(recordingFailed.map((e) => e.recording), [fourth.recording], 'only the unplugged device failed');
  });
});

test('a device failure is one alert for its kiosk, cleared when it records again or the session ends; five failures, one alert', async () => {
  await withServer(async (server, op) => {
    const watching = await newConsole(server, 'watching-console');
    const kiosk = await openKiosk(server);
    await tap(kiosk.page);
    let started = await op.waitForEvent((e) => e.type === 'recording.started');
    for (let n = 1; n <= 5; n++) {
      await unplug(kiosk.page);
      await op.waitForEvent((e) => e.type === 'recording.failed' && e.recording === started.recording);
      await waitForAlarms(watching.page, 1);
      const [alarm] = await alarms(watching.page);
      assert.match(alarm, new RegExp(`Recording failed on kiosk #${started.client}.*\\(no-device\\).*Plug it in`));
      if (n === 5) break;
      // The next session records again: the alarm clears once the kiosk records.
      op.send({ type: 'mark', mark: 'session_start' });
      const previous = started.recording;
      started = await op.waitForEvent((e) => e.type === 'recording.started' && e.recording !== previous);
      await waitForAlarms(watching.page, 0);
      assert.equal(await watching.page.locator('#recording-status').getAttribute('data-state'), 'recording');
    }
    // Still wrong now: a console signing in sees it once.
    const later = await newConsole(server, 'later-console');
    await waitForAlarms(later.page, 1);
    const state = await server.api('/api/state');
    assert.deepEqual(state.recording.kiosks.map((k) => k.state), ['failed']);

    op.send({ type: 'mark', mark: 'session_end' });
    await op.waitForEvent((e) => e.type === 'session.ended');
    await waitForAlarms(watching.page, 0);
    await waitForAlarms(later.page, 0);
    const afterEnd = await newConsole(server, 'after-end-console');
    assert.deepEqual(await alarms(afterEnd.page), [], 'the session ended: its failure is history');
    assert.equal(corpusEvents(server.corpus).filter((e) => e.type === 'recording.failed').length, 5);
    for (const c of [watching, later, afterEnd, kiosk]) await c.context.close();
  });
});

test('Alt+Down, Down, Enter on consent asks first; Escape cancels; confirmed, the recording is deleted and said so', async () => {
  await withServer(async (server, op) => {
    const operator = await newConsole(server, 'consent-console');
    const page = operator.page;
    const kiosk = await openKiosk(server);
    await tap(kiosk.page);
    const started = await op.waitForEvent((e) => e.type === 'recording.started');
    await aChunkStored(kiosk.page);
    await page.locator('#consent:not([disabled])').waitFor({ timeout: DEADLINE_MS });
    const media = path.join(server.corpus, 'sessions');
    const mediaFiles = () => fs.readdirSync(media).flatMap((dir) => {
      const folder = path.join(media, dir, 'media');
      return fs.existsSync(folder) ? fs.readdirSync(folder) : [];
    });
    assert.ok(mediaFiles().length > 0, 'recorded');

    const dialog = page.locator('#consent-confirm');
    await page.focus('#consent');
    await page.keyboard.press('Alt+ArrowDown');
    await page.keyboard.press('ArrowDown');
    await page.keyboard.press('Enter');
    await dialog.waitFor({ state: 'visible', timeout: DEADLINE_MS });
    assert.equal(await dialog.getAttribute('role'), 'alertdialog');
    assert.match(await dialog.textContent(), new RegExp(`Delete the recording of session ${started.session} \\(\\d+ s, 1 file, [\\d.]+ (KB|MB|bytes)\\)\\? This cannot be undone\\.`));
    assert.equal(await page.evaluate(() => document.activeElement?.id), 'consent-confirm-cancel', 'Cancel is the default');
    await page.screenshot({ path: path.join(OUT, 'consent-confirm-1366x768.png') });
    await page.addScriptTag({ content: AXE });
    const axe = await page.evaluate(() => window.axe.run(document, { runOnly: { type: 'tag', values: ['wcag2a', 'wcag2aa', 'wcag21aa', 'wcag22aa'] } }));
    const serious = axe.violations.filter((v) => v.impact === 'serious' || v.impact === 'critical').map((v) => `${v.id} at ${v.nodes[0].target.join(' ')}`);
    assert.deepEqual(serious, [], 'the open confirmation passes axe');

    await page.keyboard.press('Escape');
    await dialog.waitFor({ state: 'hidden', timeout: DEADLINE_MS });
    assert.equal(await page.inputValue('#consent'), 'recorded');

    // Enter on the focused Cancel cancels too.
    await page.selectOption('#consent', 'withdrawn');
    await dialog.waitFor({ state: 'visible', timeout: DEADLINE_MS });
    await page.keyboard.press('Enter');
    await dialog.waitFor({ state: 'hidden', timeout: DEADLINE_MS });
    assert.ok(mediaFiles().length > 0, 'nothing deleted by a slip, Escape or Cancel');
    assert.deepEqual(corpusEvents(server.corpus).filter((e) => e.type === 'consent.changed' || e.type === 'recording.deleted'), []);

    await page.selectOption('#consent', 'declined');
    await dialog.waitFor({ state: 'visible', timeout: DEADLINE_MS });
    await page.click('#consent-confirm-delete');
    const changed = await op.waitForEvent((e) => e.type === 'consent.changed');
    const deleted = await op.waitForEvent((e) => e.type === 'recording.deleted');
    assert.deepEqual([changed.consent, deleted.consent, deleted.session], ['declined', 'declined', started.session]);
    assert.ok(deleted.bytes > 0 && deleted.files.includes('media/audio-1.webm'), JSON.stringify(deleted));
    assert.deepEqual(mediaFiles(), []);
    const history = page.locator('#history li');
    await history.filter({ hasText: `recording of session ${started.session} deleted (consent declined): 1 file` }).waitFor({ timeout: DEADLINE_MS });
    await history.filter({ hasText: `consent of session ${started.session}: declined` }).waitFor({ timeout: DEADLINE_MS });
    const logged = corpusEvents(server.corpus).filter((e) => e.type === 'consent.changed' || e.type === 'recording.deleted').map((e) => e.type);
    assert.deepEqual(logged, ['consent.changed', 'recording.deleted']);
    await operator.context.close();
    await kiosk.context.close();
  });
});
