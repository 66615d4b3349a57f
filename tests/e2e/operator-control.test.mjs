// The operator console (`GET /operator`) in headless Chromium, controlling the robot: Stop on
// Esc against a long SAY and a running drive, over HTTP before the first welcome and when the
// websocket does not answer, during an IME composition; a dialog manager's proposals accepted
// with F9 and dismissed with Shift+F9 across two consoles; corpus marks; and the screenshot in
// docs/OPERATOR.md (docs/screenshots/operator.png, written by this file only). Each test runs
// the real `docent` binary with operator and dialog-manager credentials; observers on the
// websocket read the server's events, so every wait is for an event or an element, with a
// deadline only.

import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext, watchProblems } from './lib/browser.mjs';
import { makeBundle, removeTemp, REPO } from './lib/docent.mjs';
import { openShell } from './lib/kiosk.mjs';
import {
  chosenLabel,
  connectWithToken,
  FAKE_MEDIA,
  museumTour,
  openConsole,
  operatorToken,
  routeConsoleSocket,
  signIn,
  submitCredential,
  waitOnline,
  withConsoleServer,
} from './lib/operator.mjs';

let browser;
before(async () => {
  browser = await launchBrowser(FAKE_MEDIA);
});
after(() => browser?.close());

/** lib/operator.mjs's `withConsoleServer` with this file's browser. */
const withServer = (bundle, body) => withConsoleServer(browser, bundle, body);

test('Esc stops a long SAY and a running drive; Alt+<Key> fires an act', { timeout: 90_000 }, async () => {
  const words = Array.from({ length: 120 }, (_, i) => `word${i}`).join(' ');
  const bundle = makeBundle({
    'docent.yaml': [
      'home: index.html',
      // A story of two minutes, on purpose: allowed up to 150 s (the default would refuse it).
      'speech: {adapter: log, rate: 60, max_seconds: 150}',
      'drive:',
      '  speed: 0.2',
      '  pose_rate: 20',
      '  bounds: { min_x: 0, min_y: 0, max_x: 100, max_y: 100 }',
      '',
    ].join('\n'),
    'acts.yaml': [
      '- Label: LONG_STORY',
      '  Key: L',
      '  Text:',
      `    - ${words}`,
      '- Label: DRIVE_FAR',
      '  Group: Moving',
      '  Key: D',
      '  Cmds:',
      '    - SET_WAYPOINT 90 90',
      '    - DRIVE_START',
      '',
    ].join('\n'),
    'pages/index.html': '<!doctype html><title>home</title><h1>home</h1>\n',
  });
  try {
    const events = await withServer(bundle, async ({ observer, server, newPage }) => {
      const page = await newPage();
      const problems = watchProblems(page);
      await signIn(page, server);
      assert.ok(await page.locator('.act-group h3', { hasText: 'Moving' }).count(), 'no group "Moving"');

      await page.keyboard.press('Alt+KeyD');
      const drive = await observer.waitForEvent((e) => e.type === 'command.started' && e.verb === 'DRIVE_START');
      await observer.waitForEvent((e) => e.type === 'pose' && e.moving);
      await page.keyboard.press('Alt+KeyL');
      const say = await observer.waitForEvent((e) => e.type === 'command.started' && e.verb === 'SAY');
      assert.equal(say.label, 'LONG_STORY');
      await page.locator('#speaking', { hasText: 'word0 word1' }).waitFor();
      await page.locator(`#queue li[data-command="${drive.command}"]`).waitFor();

      // Esc, with the focus in the search field as it usually is.
      await page.focus('#search');
      await page.keyboard.press('Escape');
      const stop = await observer.waitForEvent((e) => e.type === 'stop');
      assert.equal(stop.source, 'operator');
      await observer.waitForEvent((e) => e.type === 'command.cancelled' && e.command === say.command);
      await observer.waitForEvent((e) => e.type === 'command.cancelled' && e.command === drive.command);
      const halted = await observer.waitForEvent((e) => e.type === 'pose' && !e.moving);
      const state = await server.api('/api/state');
      assert.equal(state.pose.moving, false);
      assert.deepEqual([state.pose.x, state.pose.y], [halted.x, halted.y], 'the robot moved on after the stop');
      assert.equal(state.speaking, null);
      assert.ok(halted.x < 90 && halted.y < 90, 'the robot reached its goal before the stop');
      // The console shows it: silence, nothing running.
      await page.locator('#speaking', { hasText: 'silent' }).waitFor();
      await page.locator('#queue', { hasText: 'nothing running' }).waitFor();
      // The history does not let the cut-off story read as told.
      const told = page.locator(`#history li[data-trigger="${say.trigger}"]`);
      await told.locator('.history-outcome', { hasText: 'not said: stop request' }).waitFor();
      assert.ok(await told.evaluate((li) => li.classList.contains('not-carried-out')));
      assert.deepEqual(problems, [], 'problems in the console');
    });
    const afterStop = events.slice(events.findIndex((e) => e.type === 'stop'));
    assert.ok(!afterStop.some((e) => e.type === 'pose' && e.moving), 'a moving pose after the stop');
  } finally {
    removeTemp(bundle);
  }
});

test('Esc stops before the first welcome and during an IME composition; a websocket stop unanswered within 500 ms goes over HTTP too', { timeout: 90_000 }, async () => {
  const bundle = museumTour();
  try {
    const events = await withServer(bundle, async ({ server, observer, newPage }) => {
      const page = await newPage();
      const socket = await routeConsoleSocket(page);
      const httpStops = [];
      page.on('request', (request) => {
        if (new URL(request.url()).pathname === '/api/stop') httpStops.push(request);
      });
      const nextHttpStop = () => page.waitForRequest((request) => new URL(request.url()).pathname === '/api/stop');

      // Signed in, but the server never answers the hello: Esc stops over HTTP with the credential.
      socket.mode = 'silent';
      await openConsole(page, server);
      await submitCredential(page, operatorToken(server), 'Ada');
      await socket.waitForSocket(1);
      await page.locator('#link[data-state="connecting"]').waitFor();
      let request = nextHttpStop();
      await page.keyboard.press('Escape');
      const first = await request;
      assert.deepEqual([first.method(), first.headers().authorization], ['POST', `Bearer ${operatorToken(server)}`]);
      const early = await observer.waitForEvent((e) => e.type === 'stop');
      assert.equal(early.source, 'http');
      await page.locator('#notice', { hasText: 'not connected' }).waitFor();

      // A half-open socket: welcomed, but the stop frame is lost on its way. Half a second
      // without the `stopped` answer, the console stops over HTTP as well.
      socket.mode = 'dropStops';
      socket.closeAll();
      await socket.waitForSocket(2);
      await waitOnline(page);
      await page.evaluate(() => addEventListener('keydown', (e) => e.key === 'Escape' && (window.e2eEscapeAt = e.timeStamp), { capture: true }));
      request = nextHttpStop();
      await page.keyboard.press('Escape');
      await request;
      const late = await observer.waitForEvent((e) => e.type === 'stop' && e.seq > early.seq);
      assert.equal(late.source, 'http');
      // The page's own clock: from the key press to the start of the HTTP request.
      const after = await page.evaluate(async () => {
        const stops = () => performance.getEntriesByType('resource').filter((r) => r.name.endsWith('/api/stop'));
        while (stops().length < 2) await new Promise((resolve) => requestAnimationFrame(resolve));
        return Math.round(stops()[1].startTime - window.e2eEscapeAt);
      });
      assert.ok(after >= 450 && after < 5_000, `the HTTP stop came ${after} ms after Esc`);
      assert.ok(socket.sockets[1].sent.some((m) => JSON.parse(m).type === 'stop'), 'the console did not try its websocket first');
      await page.locator('#notice', { hasText: 'did not answer' }).waitFor();

      // A healthy socket whose every event frame arrives twice; Esc while an IME composes
      // a word in the search field stops over the websocket, which answers.
      socket.mode = 'pass';
      socket.duplicate = true;
      socket.closeAll();
      await socket.waitForSocket(3);
      await waitOnline(page);
      await page.keyboard.press('Alt+KeyW');
      const greeting = await observer.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'GREETING');
      await page.focus('#search');
      await page.evaluate(() => {
        window.e2eEscapes = [];
        addEventListener('keydown', (e) => e.key === 'Escape' && window.e2eEscapes.push(e.isComposing), { capture: true });
      });
      const cdp = await page.context().newCDPSession(page);
      await cdp.send('Input.imeSetComposition', { text: 'す', selectionStart: 1, selectionEnd: 1 });
      await page.keyboard.press('Escape');
      const composed = await observer.waitForEvent((e) => e.type === 'stop' && e.seq > late.seq);
      assert.equal(composed.source, 'operator');
      assert.deepEqual(await page.evaluate(() => window.e2eEscapes), [true], 'Esc was not pressed during a composition');
      // Answered (`stopped`): nothing waits for an answer, so no HTTP stop follows.
      await page.locator('#stop[data-pending="0"]').waitFor();
      assert.equal(httpStops.length, 2, 'an answered stop went over HTTP too');
      // Each event once, although every one arrived twice.
      await page.locator(`#history li[data-seq="${composed.seq}"]`).waitFor();
      const seqs = await page.locator('#history li').evaluateAll((items) => items.map((i) => i.dataset.seq));
      assert.equal(new Set(seqs).size, seqs.length, `history shows an event twice: ${seqs}`);
      assert.ok(seqs.includes(String(greeting.seq)), `no GREETING in the history: ${seqs}`);
    });
    const stops = events.filter((e) => e.type === 'stop' && e.source !== 'server'); // not the server's own at shutdown
    assert.deepEqual(stops.map((e) => e.source), ['http', 'http', 'operator']);
  } finally {
    removeTemp(bundle);
  }
});

test('proposals come newest first with their age; F9 accepts the newest, Shift+F9 dismisses the newest; a leaving dialog manager\'s proposal is withdrawn; two consoles see each other', { timeout: 90_000 }, async () => {
  const bundle = museumTour();
  try {
    const events = await withServer(bundle, async ({ server, observer, newPage, cleanup }) => {
      const dm = await connectWithToken(server, 'dm', 'e2e-dm');
      cleanup.unshift(() => dm.close());
      // Two proposals made before any console is open: consoles find them pending when they sign in.
      dm.send({ type: 'propose', label: 'GREETING', context: null, reason: 'visitor smiled', ref: 'p1' });
      const first = await dm.waitFor((f) => f.type === 'proposed' && f.ref === 'p1');
      dm.send({ type: 'propose', label: 'FAREWELL', context: 'TextChild', reason: 'visitor leaving', ref: 'p2' });
      const second = await dm.waitFor((f) => f.type === 'proposed' && f.ref === 'p2');

      const a = await newPage();
      const b = await newPage();
      const problems = [...watchProblems(a), ...watchProblems(b)];
      await signIn(a, server, 'Ada');
      await signIn(b, server, 'Bob');
      const order = (page) => page.locator('#proposal-list li').evaluateAll((items) => items.map((i) => Number(i.dataset.proposal)));
      for (const page of [a, b]) {
        await page.locator(`#proposal-list li[data-proposal="${first.proposal}"]`).waitFor();
        assert.deepEqual(await order(page), [second.proposal, first.proposal], 'not newest first');
        assert.match(await page.locator('#proposal-list li').first().textContent(), /visitor leaving/);
      }
      // Each shows its age, and it counts on.
      const age = a.locator(`#proposal-list li[data-proposal="${first.proposal}"] .proposal-age`);
      const was = await age.textContent();
      assert.match(was, /^(just now|\d+ s ago)$/);
      await a.waitForFunction((t) => document.querySelector('#proposal-list li:last-child .proposal-age').textContent !== t, was);
      assert.match(await age.textContent(), /^\d+ s ago$/);

      // F9: the newest (FAREWELL, the one that just came) is accepted.
      await a.keyboard.press('F9');
      const accepted = await observer.waitForEvent((e) => e.type === 'proposal.accepted');
      assert.equal(accepted.proposal, second.proposal, 'F9 did not accept the newest proposal');
      const fired = await observer.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'FAREWELL');
      assert.equal(fired.source, 'operator');
      assert.equal(fired.trigger, accepted.trigger);
      for (const page of [a, b]) await page.locator(`#proposal-list li[data-proposal="${second.proposal}"]`).waitFor({ state: 'detached' });
      // Bob's history shows Ada's act with its text.
      const line = b.locator(`#history li[data-seq="${fired.seq}"]`);
      await line.waitFor();
      assert.ok((await line.textContent()).includes(fired.text));
      assert.match(await line.textContent(), new RegExp(`operator #${accepted.client}`));
      // Replayed history and live events may overlap: each event is shown once.
      const seqs = await b.locator('#history li').evaluateAll((items) => items.map((i) => i.dataset.seq));
      assert.equal(new Set(seqs).size, seqs.length, `history shows an event twice: ${seqs}`);

      // Shift+F9 on Bob's console: the newest left (GREETING) is dismissed.
      await b.keyboard.press('Shift+F9');
      const dismissed = await observer.waitForEvent((e) => e.type === 'proposal.dismissed');
      assert.equal(dismissed.proposal, first.proposal);
      await a.locator('#proposals').waitFor({ state: 'hidden' });
      await b.locator('#proposals').waitFor({ state: 'hidden' });

      // A dialog manager that leaves takes its waiting proposal with it.
      const planner = await connectWithToken(server, 'dm', 'e2e-planner');
      planner.send({ type: 'propose', label: 'ANY_QUESTIONS', context: null, reason: 'a pause', ref: 'p3' });
      const third = await planner.waitFor((f) => f.type === 'proposed' && f.ref === 'p3');
      await a.locator(`#proposal-list li[data-proposal="${third.proposal}"]`).waitFor();
      await planner.close();
      const withdrawn = await observer.waitForEvent((e) => e.type === 'proposal.withdrawn');
      assert.equal(withdrawn.proposal, third.proposal);
      await a.locator('#proposals').waitFor({ state: 'hidden' });
      const note = a.locator(`#history li[data-seq="${withdrawn.seq}"]`);
      await note.waitFor();
      assert.match(await note.textContent(), /withdrawn proposal \d+: ANY_QUESTIONS/);
      assert.deepEqual(problems, [], 'problems in the consoles');
    });
    const acts = events.filter((e) => e.type === 'act.triggered').map((e) => e.label);
    assert.deepEqual(acts, ['FAREWELL'], 'the dismissed or withdrawn proposal was dispatched');
    assert.deepEqual(events.filter((e) => e.type.startsWith('proposal.')).map((e) => e.type), [
      'proposal.made',
      'proposal.made',
      'proposal.accepted',
      'proposal.dismissed',
      'proposal.made',
      'proposal.withdrawn',
    ]);
  } finally {
    removeTemp(bundle);
  }
});

test('session, visitor group, situation marks and a typed note reach the corpus; the children group sets the context', { timeout: 90_000 }, async () => {
  const bundle = museumTour();
  try {
    const events = await withServer(bundle, async ({ server, observer, newPage }) => {
      const page = await newPage();
      const problems = watchProblems(page);
      await signIn(page, server);
      await page.click('#session-start');
      const started = await observer.waitForEvent((e) => e.type === 'session.started');
      await page.locator('#session', { hasText: `session ${started.session}` }).waitFor();
      assert.equal(await page.inputValue('#consent'), 'recorded', "the site's default consent");
      await page.selectOption('#consent', 'declined');
      // It would delete the session's recordings: asked first (recording-alarms.test.mjs).
      await page.click('#consent-confirm-delete');
      await observer.waitForEvent((e) => e.type === 'consent.changed' && e.consent === 'declined');
      await page.selectOption('#consent', 'withdrawn');
      await observer.waitForEvent((e) => e.type === 'consent.changed' && e.consent === 'withdrawn');
      await page.waitForFunction(() => document.querySelector('#consent').disabled, null, { timeout: 10_000 });
      await page.click('#visitor-groups button[data-group="children"]');
      await observer.waitForEvent((e) => e.type === 'visitor.group' && e.group === 'children');
      await page.waitForFunction(() => document.querySelector('#context').value === 'TextChild');
      await page.keyboard.press('Alt+Shift+Digit1');
      await observer.waitForEvent((e) => e.type === 'situation.marked' && e.situation === 'question');
      await page.click('#situation-buttons button[data-situation="laughter"]');
      await observer.waitForEvent((e) => e.type === 'situation.marked' && e.situation === 'laughter');
      // A note by keyboard: Alt+Shift+N to the field, type, Enter; the field empties once it is logged.
      await page.keyboard.press('Alt+Shift+KeyN');
      assert.equal(await page.evaluate(() => document.activeElement?.id), 'note');
      await page.keyboard.type('the boy asks about the punch cards');
      await page.keyboard.press('Enter');
      await observer.waitForEvent((e) => e.type === 'note.written');
      await page.waitForFunction(() => document.querySelector('#note').value === '');
      await page.click('#session-end');
      await observer.waitForEvent((e) => e.type === 'session.ended');
      await page.locator('#session', { hasText: 'no session' }).waitFor();
      assert.deepEqual(problems, [], 'problems in the console');
    });
    const marks = events
      .filter((e) => ['session.started', 'visitor.group', 'situation.marked', 'note.written', 'session.ended'].includes(e.type))
      .map((e) => [e.type, e.group ?? e.situation ?? e.text ?? null, e.source]);
    assert.deepEqual(marks, [
      ['session.started', null, 'operator'],
      ['visitor.group', 'children', 'operator'],
      ['situation.marked', 'question', 'operator'],
      ['situation.marked', 'laughter', 'operator'],
      ['note.written', 'the boy asks about the punch cards', 'operator'],
      ['session.ended', null, 'operator'],
    ]);
    const group = events.find((e) => e.type === 'visitor.group');
    assert.equal(group.context, 'TextChild');
  } finally {
    removeTemp(bundle);
  }
});

test('screenshot of the console on the museum tour (docs/screenshots/operator.png)', { timeout: 90_000 }, async () => {
  const bundle = museumTour({ speed: 1.5, camera: 'webrtc' });
  try {
    await withServer(bundle, async ({ server, observer, newPage, cleanup }) => {
      const kiosk = await newPage(newTouchContext);
      await openShell(kiosk, server, 'index.html');
      const projector = await newPage();
      await projector.goto(`${server.base}/projector`);
      const page = await newPage();
      const problems = watchProblems(page);
      await signIn(page, server, 'Ada');

      await page.click('#session-start');
      await page.click('#visitor-groups button[data-group="group"]');
      await observer.waitForEvent((e) => e.type === 'context.changed' && e.context === 'TextGroup');
      await page.keyboard.press('Alt+KeyW'); // the museum tour's key for GREETING
      await observer.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'GREETING');
      await page.keyboard.type('first stop');
      await page.keyboard.press('Enter');
      await observer.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'GO_TO_MINICOMPUTER');
      await observer.waitForEvent((e) => e.type === 'pose' && e.x > 2.5);

      const dm = await connectWithToken(server, 'dm', 'tour-planner');
      cleanup.unshift(() => dm.close());
      dm.send({ type: 'propose', label: 'ANY_QUESTIONS', context: null, reason: 'visitors stopped at the exhibit', ref: 'p' });
      await page.locator('#proposal-list li').waitFor();
      // Browsing rather than searching, to show the groups, keys, favourites and recently used:
      // two stars, and Down to the act to show in the preview.
      for (const label of ['ANY_QUESTIONS', 'DONT_KNOW']) await page.click(`.act-row:has(.act[data-label="${label}"]) .star`);
      for (let i = 0; i < 60 && (await chosenLabel(page)) !== 'FOLLOW_ME'; i++) await page.keyboard.press('ArrowDown');
      assert.equal(await chosenLabel(page), 'FOLLOW_ME');
      await page.locator('#map .robot:not([hidden])').waitFor();
      await page.locator('#camera[data-state="live"]').waitFor();
      await page.waitForFunction(() => document.querySelector('#camera video')?.currentTime > 0);

      const file = path.join(REPO, 'docs/screenshots/operator.png');
      fs.mkdirSync(path.dirname(file), { recursive: true });
      await page.screenshot({ path: file });
      assert.ok(fs.statSync(file).size > 20_000, 'the screenshot is suspiciously small');
      assert.deepEqual(problems, [], 'problems in the console');
    });
  } finally {
    removeTemp(bundle);
  }
});
