// The replay and annotation page (`GET /sessions`) in headless Chromium, on a session a real
// Docent recorded (an operator and a kiosk over the websocket: the tour's introduction said with
// its page shown, a situation marked while it was said, a page the visitor followed, the session
// ended). Signed in, the page lists the session and opens it; seeking to the operator's mark
// shows the page and the utterance the log has at that time; a codebook key pressed twice saves
// an interval and Shift with a key a point, both found in annotations.jsonl as the page showed
// them; at 4× the playhead moves faster than at 1× (measured on the playhead's own reported
// time, awaiting it, never sleeping). With recordings (an Opus WebM and a later VP8 one, made
// by Debian's ffmpeg and listed in the manifest as the recorder lists its files) both play in
// step with the playhead, fetched by ticket with range requests; a save that fails is shown at
// once and can be tried again.

import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, watchProblems } from './lib/browser.mjs';
import { copyBundle, DEADLINE_MS, OPERATOR_TOKEN, REPO, removeTemp, startDocent } from './lib/docent.mjs';
import { connectOperator, DocentClient } from './lib/ws-client.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

/** museum-tour, its speech logged at 600 words a minute (the introduction takes ~4.5 s). */
function tourBundle() {
  const config = fs.readFileSync(path.join(REPO, 'dialogs/museum-tour/docent.yaml'), 'utf8');
  const fast = config.replace('speech: { voice: en-us, rate: 160,', 'speech: { adapter: log, voice: en-us, rate: 600,');
  assert.notEqual(fast, config, 'the speech line is there to change');
  return copyBundle('museum-tour', { 'docent.yaml': fast });
}

/** Records one session on `server`; returns its folder. */
async function recordSession(server) {
  const op = await connectOperator(server.wsUrl);
  const kiosk = await DocentClient.connect(server.wsUrl, { role: 'kiosk', name: 'e2e-kiosk' });
  kiosk.onFrame = (frame) => {
    if (frame.type === 'command') kiosk.send({ type: 'done', id: frame.id });
  };
  const mark = async (body) => {
    op.send({ type: 'mark', ...body });
    await op.waitFor((f) => f.type === 'marked');
  };
  await mark({ mark: 'session_start' });
  op.send({ type: 'trigger', label: 'ABOUT_TOUR' });
  await op.waitForEvent((e) => e.type === 'command.started' && e.verb === 'SAY');
  await mark({ mark: 'situation', value: 'question' });
  await op.waitForEvent((e) => e.type === 'command.done' && e.verb === 'SAY');
  kiosk.send({ type: 'page', page: 'card-punch.html' });
  await op.waitForEvent((e) => e.type === 'display.changed' && e.page === 'card-punch.html');
  await mark({ mark: 'group', value: 'children' });
  await mark({ mark: 'session_end' });
  await op.close();
  await kiosk.close();
  const sessions = path.join(server.corpus, 'sessions');
  const names = fs.readdirSync(sessions);
  assert.equal(names.length, 1, `${names}`);
  return path.join(sessions, names[0]);
}

/** An 8 s Opus WebM (a 440 Hz tone) at `file`, made by ffmpeg. */
function makeWebm(file) {
  fs.mkdirSync(path.dirname(file), { recursive: true });
  execFileSync('ffmpeg', ['-hide_banner', '-loglevel', 'error', '-f', 'lavfi', '-i', 'sine=frequency=440:duration=8', '-c:a', 'libopus', '-b:a', '32k', '-y', file]);
}

/** An 8 s VP8 and Opus WebM (a test picture and a tone) at `file`, made by ffmpeg. */
function makeVideoWebm(file) {
  fs.mkdirSync(path.dirname(file), { recursive: true });
  const inputs = ['-f', 'lavfi', '-i', 'testsrc=size=160x120:rate=10:duration=8', '-f', 'lavfi', '-i', 'sine=frequency=330:duration=8'];
  execFileSync('ffmpeg', ['-hide_banner', '-loglevel', 'error', ...inputs, '-c:v', 'libvpx', '-b:v', '100k', '-c:a', 'libopus', '-shortest', '-y', file]);
}

/** Lists `file` in the session's manifest, as the recorder does. */
function listMedia(dir, file, startUs, track = 'audio') {
  const manifestPath = path.join(dir, 'session.json');
  const manifest = JSON.parse(fs.readFileSync(manifestPath, 'utf8'));
  const mime = track === 'video' ? 'video/webm;codecs=vp8,opus' : 'audio/webm;codecs=opus';
  manifest.media = [...(manifest.media ?? []), { file, track, mime, start_us: startUs, recording: 1 }];
  fs.writeFileSync(manifestPath, JSON.stringify(manifest, null, 2));
}

/** Opens /sessions, signs in as Ana and opens session `name`. */
async function openSession(page, server, name) {
  await page.goto(`${server.base}/sessions`);
  await page.locator('#signin[open]').waitFor();
  await page.fill('#signin-token', OPERATOR_TOKEN);
  await page.fill('#signin-name', 'Ana');
  await page.click('#signin-submit');
  await page.locator('body[data-state="ready"]').waitFor();
  await page.click(`button[data-session="${name}"]`);
  await page.locator('body[data-state="open"]').waitFor();
}

/** What the log says was shown and said at the situation mark. */
function atTheMark(dir) {
  const log = fs.readFileSync(path.join(dir, 'events.jsonl'), 'utf8').trim().split('\n').map((l) => JSON.parse(l));
  const markUs = log.find((e) => e.type === 'situation.marked').session_us;
  const page = log.filter((e) => e.type === 'display.changed' && e.session_us <= markUs).at(-1).page;
  const started = log.find((e) => e.type === 'command.started' && e.verb === 'SAY');
  const ended = log.find((e) => e.type === 'command.done' && e.command === started.command);
  assert.ok(started.session_us <= markUs && markUs < ended.session_us, 'the mark fell while it spoke');
  const said = log.find((e) => e.type === 'command.sent' && e.command === started.command);
  const text = said.arg ?? log.find((e) => e.type === 'act.triggered' && e.trigger === started.trigger).text;
  return { markUs, page, text };
}

/**
 * The controls Chromium's accessibility tree has without a name (buttons, fields, the timeline
 * slider, frames): each as `role "name"`. (axe-core is not among the test dependencies; this
 * asks the browser itself what a screen reader would be told.)
 */
async function unnamedControls(page) {
  const cdp = await page.context().newCDPSession(page);
  const { nodes } = await cdp.send('Accessibility.getFullAXTree');
  const roles = new Set(['button', 'combobox', 'slider', 'textbox', 'checkbox', 'Iframe', 'link', 'listbox']);
  const controls = nodes.filter((n) => !n.ignored && roles.has(n.role?.value));
  assert.ok(controls.length > 15, `the tree has the page's controls: ${controls.length}`);
  return controls.filter((n) => !(n.name?.value ?? '').trim()).map((n) => `${n.role.value} ${JSON.stringify(n.name?.value ?? '')}`);
}

/** The playhead's reported time, µs. */
const playheadUs = (page) => page.locator('#playhead').getAttribute('data-time-us').then(Number);

/** Awaits the playhead reaching `us` or beyond; returns how fast it went there (session µs per wall ms). */
async function pace(page, fromUs, toUs) {
  return page.evaluate(
    ([from, to]) =>
      new Promise((resolve) => {
        const playhead = document.getElementById('playhead');
        const started = performance.now();
        const startUs = Number(playhead.dataset.timeUs);
        const check = () => {
          const now = Number(playhead.dataset.timeUs);
          if (now >= to) resolve((now - startUs) / (performance.now() - started));
          else requestAnimationFrame(check);
        };
        check();
      }),
    [fromUs, toUs],
  );
}

test('a recorded session replays in step with its log and is annotated by key', { timeout: 90_000 }, async (t) => {
  const bundle = tourBundle();
  const server = await startDocent(bundle);
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  try {
    const dir = await recordSession(server);
    const name = path.basename(dir);
    const want = atTheMark(dir);
    const page = await context.newPage();
    const problems = watchProblems(page);

    await openSession(page, server, name);

    // Seek to the operator's mark: what the page shows is what the log says.
    await page.click('.tier-marks button.mark-situation');
    await page.locator(`#playhead[data-time-us="${want.markUs}"]`).waitFor();
    assert.equal(await page.locator('#now-page').textContent(), want.page);
    assert.equal(await page.locator('#now-utterance').textContent(), want.text);
    assert.equal(await page.locator('#now-page-frame').getAttribute('src'), `/pages/${want.page}`);

    // `q` begins "question" here, one second on `q` ends it; Shift+W marks "watching" there.
    await page.keyboard.press('q');
    await page.locator('#pending').filter({ hasText: 'situation: question' }).waitFor();
    await page.focus('#timeline');
    await page.keyboard.press('ArrowRight');
    await page.locator(`#playhead[data-time-us="${want.markUs + 1_000_000}"]`).waitFor();
    await page.keyboard.press('q');
    await page.locator('#annotations tr').nth(0).waitFor();
    await page.keyboard.press('Shift+W');
    await page.locator('#annotations tr').nth(1).waitFor();
    await page.locator('#save-status', { hasText: 'Saved' }).waitFor();
    assert.equal(await page.locator('#save-error').isHidden(), true);
    const lines = fs.readFileSync(path.join(dir, 'annotations.jsonl'), 'utf8').trim().split('\n').map((l) => JSON.parse(l));
    const saved = lines.map(({ tier, code, start_us, end_us, annotator }) => ({ tier, code, start_us, end_us, annotator }));
    const end = want.markUs + 1_000_000;
    assert.deepEqual(saved, [
      { tier: 'situation', code: 'question', start_us: want.markUs, end_us: end, annotator: 'Ana' },
      { tier: 'behaviour', code: 'watching', start_us: end, end_us: end, annotator: 'Ana' },
    ]);
    assert.equal(await page.locator('.tier-coded button.annotation').count(), 2, 'both on the timeline');
    const events = fs.readFileSync(path.join(dir, 'events.jsonl'), 'utf8');
    assert.doesNotMatch(events, /watching/, 'annotations never go into the event log');

    // Playing from the start: 4× moves the playhead faster than 1×.
    await page.focus('#timeline');
    await page.keyboard.press('Home');
    await page.locator('#playhead[data-time-us="0"]').waitFor();
    await page.click('#play');
    const normal = await pace(page, 0, 500_000);
    await page.selectOption('#speed', '4');
    const from = await playheadUs(page);
    const fast = await pace(page, from, from + 2_000_000);
    await page.click('#play');
    t.diagnostic(`playhead pace: ${normal.toFixed(0)} µs per ms at 1×, ${fast.toFixed(0)} at 4×`);
    assert.ok(fast > 2 * normal, `4× went ${fast.toFixed(0)} µs per ms, 1× ${normal.toFixed(0)}`);
    assert.ok(normal > 500 && normal < 1_500, `1× went ${normal.toFixed(0)} µs per ms`);

    assert.deepEqual(await unnamedControls(page), [], 'every control has a name');
    assert.deepEqual(problems, [], 'no console errors or failed requests');
  } finally {
    await context.close();
    await server.stop();
    removeTemp(bundle);
  }
});

test('recordings play in step with the playhead, by ticket with ranges; a failed save is shown and tried again', { timeout: 90_000 }, async (t) => {
  const bundle = tourBundle();
  const server = await startDocent(bundle);
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  try {
    const dir = await recordSession(server);
    const name = path.basename(dir);
    makeWebm(path.join(dir, 'media/audio-1.webm'));
    const startUs = 1_000_000;
    listMedia(dir, 'media/audio-1.webm', startUs);
    // The camera's recording began later, 1.5 s into the session.
    makeVideoWebm(path.join(dir, 'media/video-1.webm'));
    const videoStartUs = 1_500_000;
    listMedia(dir, 'media/video-1.webm', videoStartUs, 'video');
    const page = await context.newPage();
    const problems = watchProblems(page);
    const media = [];
    page.on('response', (res) => {
      if (res.url().includes('/session-media/')) media.push({ status: res.status(), range: res.request().headers().range ?? null });
    });
    await openSession(page, server, name);

    const audio = page.locator('#media audio');
    assert.equal(await audio.count(), 1);
    assert.equal(await page.locator('#media video').count(), 1);
    const src = await audio.getAttribute('src');
    assert.match(src, /^\/session-media\/[0-9a-f]{32}\/media\/audio-1\.webm$/);
    assert.doesNotMatch(src, new RegExp(OPERATOR_TOKEN), 'no credential in an address');

    // From 2 s on the session clock, the recording plays from 1 s into itself, and stays in step.
    await page.focus('#timeline');
    await page.keyboard.press('Home');
    await page.keyboard.press('ArrowRight');
    await page.keyboard.press('ArrowRight');
    await page.locator('#playhead[data-time-us="2000000"]').waitFor();
    await page.click('#play');
    // Once they play, compare each with the clock at every frame for a second of the audio.
    const drift = await page.evaluate(
      ([audioStart, videoStart]) =>
        new Promise((resolve) => {
          const audio = document.querySelector('#media audio');
          const video = document.querySelector('#media video');
          const playhead = document.getElementById('playhead');
          let worst = 0;
          let frames = 0;
          const check = () => {
            const clockUs = Number(playhead.dataset.timeUs);
            if (!audio.paused && !video.paused && audio.currentTime > 1.5) {
              const apart = [
                Math.abs(audio.currentTime - (clockUs - audioStart) / 1e6),
                Math.abs(video.currentTime - (clockUs - videoStart) / 1e6),
              ];
              worst = Math.max(worst, ...apart);
              frames += 1;
            }
            if (audio.currentTime > 2.5) resolve({ worst, frames });
            else requestAnimationFrame(check);
          };
          check();
        }),
      [startUs, videoStartUs],
    );
    await page.click('#play');
    t.diagnostic(`recordings (audio, video) vs clock over ${drift.frames} frames: at most ${(drift.worst * 1000).toFixed(0)} ms apart`);
    assert.ok(drift.frames > 10 && drift.worst < 0.2, `the recording drifted up to ${drift.worst} s from the clock`);
    assert.ok(media.some((m) => m.status === 206 && m.range), `range requests: ${JSON.stringify(media)}`);

    // A save that cannot be written is said at once; once it can, Try again saves it.
    const file = path.join(dir, 'annotations.jsonl');
    fs.mkdirSync(file);
    await page.focus('#timeline');
    await page.keyboard.press('Shift+Q');
    const error = page.locator('#save-error');
    await error.waitFor();
    assert.match(await error.textContent(), /Not saved: situation: question at .* \(annotations-unwritable\)/);
    assert.equal(await page.locator('#annotations tr').count(), 0, 'nothing shown as saved');
    fs.rmdirSync(file);
    await error.locator('button', { hasText: 'Try again' }).click();
    await page.locator('#annotations tr').waitFor();
    assert.equal(await error.isHidden(), true);
    const lines = fs.readFileSync(file, 'utf8').trim().split('\n').map((l) => JSON.parse(l));
    assert.deepEqual(lines.map((l) => [l.tier, l.code, l.start_us === l.end_us]), [['situation', 'question', true]]);

    const unexpected = problems.filter((p) => !(p.includes('503') && p.includes('/annotations')));
    assert.deepEqual(unexpected, [], 'no console errors or failed requests but the refused save');
  } finally {
    await context.close();
    await server.stop();
    removeTemp(bundle);
  }
});
