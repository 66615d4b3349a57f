// Recording a visitor session from the kiosk in headless Chromium (docs/CORPUS.md,
// "Recording"): a touch starts the session, the shell records Chromium's fake microphone and
// uploads the chunks; the WebM in the session's media/ decodes with Debian's ffmpeg, lasts as
// long as the recording ran, and is byte for byte the chunks the page produced even though one
// upload was cut before it reached the server and another lost its answer; a kiosk whose
// browser refuses the microphone is shown on a signed-in console at once; a declined session
// records nothing. The alignment test replaces the microphone by a WebAudio click sounded when
// the page sends a trigger, and measures each click in the decoded audio against the trigger's
// logged `session_us`. Every wait is for an event or a page state, with a deadline only.

import assert from 'node:assert/strict';
import { execFileSync, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext, watchExceptions } from './lib/browser.mjs';
import { corpusEvents, DEADLINE_MS, makeBundle, removeTemp, startDocent, tempDir } from './lib/docent.mjs';
import { openShell, shownContentFrame } from './lib/kiosk.mjs';
import { newConsoleContext, signIn } from './lib/operator.mjs';
import { connectOperator } from './lib/ws-client.mjs';

const FAKE_DEVICES = ['--use-fake-device-for-media-stream'];
const FAKE_PERMISSION = '--use-fake-ui-for-media-stream';

/** Measured bounds (docs/CORPUS.md, "Recording"): a sound's place in the file against when the
 * page made it, and against its trigger's logged `session_us`. */
const ALIGNMENT_BOUND_MS = 60;
const END_TO_END_BOUND_MS = 250;

let browser;
before(async () => {
  browser = await launchBrowser([...FAKE_DEVICES, FAKE_PERMISSION]);
});
after(() => browser?.close());

function bundle(corpus = '{session_idle: 0s}') {
  return makeBundle({
    'acts.yaml': '- Label: HELLO\n  Text: [Hi]\n- Label: TICK\n  Text: [Tick]\n',
    'docent.yaml': `speech: {adapter: log}\ncorpus: ${corpus}\n`,
    'pages/index.html': '<html><body><button id="hello" data-act="HELLO" style="width:300px;height:200px">Hello</button><button data-act="TICK">Tick</button></body></html>',
  });
}

async function withServer(files, body) {
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

async function openKiosk(inBrowser, server, init) {
  const context = await newTouchContext(inBrowser);
  if (init) await context.addInitScript(init);
  const page = await context.newPage();
  const errors = watchExceptions(page);
  await openShell(page, server, 'index.html');
  return { context, page, errors };
}

/** A visitor's tap on the page's button: the touch that starts a session. */
async function tap(page) {
  const frame = await shownContentFrame(page);
  await frame.tap('#hello');
}

function sessionDir(server, number) {
  const started = corpusEvents(server.corpus).find((e) => e.type === 'session.started' && e.session === number);
  const sessions = path.join(server.corpus, 'sessions');
  for (const dir of fs.readdirSync(sessions)) {
    const manifest = JSON.parse(fs.readFileSync(path.join(sessions, dir, 'session.json'), 'utf8'));
    if (manifest.started.seq === started.seq) return path.join(sessions, dir);
  }
  throw new Error(`no folder for session ${number}`);
}

/**
 * Decodes `file` with ffmpeg and returns the audio's length in seconds (from its last packet)
 * and what ffmpeg said on the way (its errors; none for a whole recording).
 */
function decode(file) {
  const run = spawnSync('ffmpeg', ['-v', 'error', '-i', file, '-f', 'null', '-'], { encoding: 'utf8' });
  assert.equal(run.status, 0, `ffmpeg decodes ${file}: ${run.stderr}`);
  const packets = execFileSync('ffprobe', ['-v', 'error', '-select_streams', 'a:0', '-show_entries', 'packet=pts_time,duration_time', '-of', 'csv=p=0', file], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] })
    .trim().split('\n').map((line) => line.split(',').map(Number));
  const [pts, duration] = packets.at(-1);
  return { seconds: pts + duration, errors: run.stderr.trim() };
}

test('a session a touch started records the microphone into a playable WebM, whole across cut uploads', async () => {
  await withServer(bundle(), async (server, op) => {
    const { context, page, errors } = await openKiosk(browser, server);
    const sent = new Map(); // seq -> bytes, as the page produced them
    let cutBefore = false;
    let cutAfter = false;
    await page.route('**/api/recordings/*/chunks/*', async (route) => {
      const seq = Number(route.request().url().split('/').at(-1));
      const body = route.request().postDataBuffer() ?? Buffer.alloc(0);
      if (sent.has(seq)) assert.deepEqual(body, sent.get(seq), `chunk ${seq} is resent unchanged`);
      sent.set(seq, body);
      if (seq === 1 && !cutBefore) {
        cutBefore = true; // cut before it reaches the server
        return route.abort('connectionreset');
      }
      if (seq === 3 && !cutAfter) {
        cutAfter = true; // stored by the server, its answer lost
        await route.fetch();
        return route.abort('connectionreset');
      }
      return route.continue();
    });
    await tap(page);
    const started = await op.waitForEvent((e) => e.type === 'recording.started');
    assert.equal(started.file, 'media/audio-1.webm');
    assert.equal(started.track, 'audio');
    // Five chunks stored: about five seconds recorded.
    await page.waitForFunction(() => window.docentRecorder.current?.acked > 0 && window.docentRecorder.current.next >= 6 && window.docentRecorder.current.queued === 0, null, { timeout: DEADLINE_MS });
    op.send({ type: 'mark', mark: 'session_end' });
    const stopped = await op.waitForEvent((e) => e.type === 'recording.stopped');
    assert.equal(stopped.reason, 'session-ended');
    assert.ok(cutBefore && cutAfter, 'both cuts happened');
    await context.close();
    assert.deepEqual(errors, []);

    const dir = sessionDir(server, started.session);
    const file = path.join(dir, 'media/audio-1.webm');
    const expected = Buffer.concat([...sent.keys()].sort((a, b) => a - b).map((seq) => sent.get(seq)));
    const stored = fs.readFileSync(file);
    assert.equal(stored.length, stopped.bytes);
    assert.ok(stored.equals(expected), `the file is the ${sent.size} chunks in order, once each (${stored.length} vs ${expected.length} bytes)`);
    assert.equal(stopped.chunks, sent.size);
    const events = corpusEvents(server.corpus);
    const ended = events.find((e) => e.type === 'session.ended');
    const recordedS = (ended.session_us - started.start_us) / 1e6;
    const { seconds, errors: decodeErrors } = decode(file);
    assert.equal(decodeErrors, '', 'the whole recording decodes without a word from ffmpeg');
    assert.ok(Math.abs(seconds - recordedS) < 1.2, `decoded ${seconds} s, recorded from start to session end ${recordedS} s`);
    const manifest = JSON.parse(fs.readFileSync(path.join(dir, 'session.json'), 'utf8'));
    assert.deepEqual(manifest.media.map((m) => [m.file, m.track, m.start_us]), [['media/audio-1.webm', 'audio', started.start_us]]);
    console.log(`recording: ${stored.length} bytes in ${seconds.toFixed(2)} s = ${(stored.length / seconds / 1024).toFixed(1)} KiB/s audio`);
  });
});

test('the next session ends the running recording with its last chunk and starts a new file', async () => {
  await withServer(bundle(), async (server, op) => {
    const { context, page } = await openKiosk(browser, server);
    await tap(page);
    const first = await op.waitForEvent((e) => e.type === 'recording.started');
    await page.waitForFunction(() => window.docentRecorder.current?.next >= 2, null, { timeout: DEADLINE_MS });
    op.send({ type: 'mark', mark: 'session_start' });
    const stopped = await op.waitForEvent((e) => e.type === 'recording.stopped' && e.recording === first.recording);
    assert.equal(stopped.reason, 'session-ended', 'stopped in order, its last chunk uploaded');
    const second = await op.waitForEvent((e) => e.type === 'recording.started' && e.recording !== first.recording);
    assert.notEqual(second.session, first.session);
    assert.equal(second.file, 'media/audio-1.webm', 'the first file of the new session');
    await context.close();
  });
});

test('with video on, the kiosk records its camera and microphone into one playable WebM', async () => {
  await withServer(bundle('{session_idle: 0s, record: [audio, video]}'), async (server, op) => {
    const { context, page } = await openKiosk(browser, server);
    await tap(page);
    const started = await op.waitForEvent((e) => e.type === 'recording.started');
    assert.deepEqual([started.file, started.track, started.mime], ['media/video-1.webm', 'video', 'video/webm;codecs=vp8,opus']);
    await page.waitForFunction(() => window.docentRecorder.current?.next >= 6 && window.docentRecorder.current.queued === 0, null, { timeout: DEADLINE_MS });
    op.send({ type: 'mark', mark: 'session_end' });
    const stopped = await op.waitForEvent((e) => e.type === 'recording.stopped');
    await context.close();
    const file = path.join(sessionDir(server, started.session), 'media/video-1.webm');
    const streams = execFileSync('ffprobe', ['-v', 'error', '-show_entries', 'stream=codec_type,codec_name', '-of', 'csv=p=0', file], { encoding: 'utf8' })
      .trim().split('\n').sort();
    assert.deepEqual(streams, ['opus,audio', 'vp8,video']);
    const { seconds, errors } = decode(file);
    // Chromium writes WebM times in whole milliseconds, so two Opus packets may share one; only
    // ffmpeg's null output notes it (the decoders do not), and nothing else may be said.
    const said = errors.split('\n').filter((line) => line && !/non monotonically increasing dts to muxer/.test(line));
    assert.deepEqual(said, []);
    console.log(`recording with video: ${stopped.bytes} bytes in ${seconds.toFixed(2)} s = ${(stopped.bytes / seconds / 1024).toFixed(1)} KiB/s audio and video`);
  });
});

test('kill -9 mid-session leaves a playable recording and a readable log; the next start cuts what was not acknowledged', async () => {
  const files = bundle();
  const corpus = tempDir('docent-e2e-recording-kill-');
  const server = await startDocent(files, { corpus });
  const op = await connectOperator(server.wsUrl);
  let dir;
  try {
    const { context, page } = await openKiosk(browser, server);
    await tap(page);
    const started = await op.waitForEvent((e) => e.type === 'recording.started');
    await page.waitForFunction(() => window.docentRecorder.current?.next >= 4 && window.docentRecorder.current.queued === 0, null, { timeout: DEADLINE_MS });
    server.process.kill('SIGKILL');
    await server.stop();
    await context.close();
    dir = sessionDir(server, started.session);
    const file = path.join(dir, 'media/audio-1.webm');
    const index = fs.readFileSync(`${file}.chunks`, 'utf8').trim().split('\n');
    const acked = Number(index.at(-1).split(' ')[1]);
    assert.ok(index.length >= 3 && fs.statSync(file).size >= acked, `${index.length} chunks indexed`);
    // What a kill in the middle of an append leaves: bytes beyond the index.
    fs.appendFileSync(file, Buffer.from('a torn half of a chunk'));
    assert.ok(corpusEvents(server.corpus).some((e) => e.type === 'recording.started'), 'the log reads');
    const again = await startDocent(files, { corpus });
    try {
      await again.waitForOutput(/unacknowledged; cut back to its last acknowledged chunk/);
      assert.equal(fs.statSync(file).size, acked, 'cut back to the acknowledged length');
      const { seconds, errors } = decode(file);
      // A recording cut short ends inside a WebM cluster of unknown size, as a live stream
      // does: ffmpeg says so, once, and plays every block before it.
      assert.match(errors, /^(\[matroska,webm @ \w+\] File ended prematurely at pos\. \d+ \(0x[0-9a-f]+\))?$/);
      assert.ok(seconds >= index.length - 1.5, `${seconds} s decoded from ${index.length} chunks`);
    } finally {
      await again.stop();
    }
  } finally {
    await op.close().catch(() => {});
    await server.stop();
    removeTemp(files);
    removeTemp(corpus);
  }
});

test('a kiosk whose browser refuses the microphone is shown on a signed-in console at once', async () => {
  const refusing = await launchBrowser(FAKE_DEVICES); // no fake permission prompt: refused
  try {
    await withServer(bundle(), async (server, op) => {
      const consoleContext = await newConsoleContext(browser);
      const consolePage = await consoleContext.newPage();
      await signIn(consolePage, server, 'recording-test');
      const { context, page } = await openKiosk(refusing, server);
      await tap(page);
      const failed = await op.waitForEvent((e) => e.type === 'recording.failed');
      assert.equal(failed.code, 'permission-denied');
      const alert = consolePage.locator('#recording-alert[role="alert"]');
      await alert.waitFor({ state: 'visible', timeout: DEADLINE_MS });
      assert.match(await alert.textContent(), /refused the microphone/);
      assert.equal(await consolePage.locator('#recording-status').getAttribute('data-state'), 'failed');
      const state = await server.api('/api/state');
      assert.equal(state.recording.kiosks[0].state, 'failed');
      await context.close();
      await consoleContext.close();
    });
  } finally {
    await refusing.close();
  }
});

test('a declined session records nothing; the next one, with consent, does', async () => {
  await withServer(bundle('{session_idle: 0s, consent: declined}'), async (server, op) => {
    const { context, page } = await openKiosk(browser, server);
    await tap(page);
    const first = await op.waitForEvent((e) => e.type === 'session.started');
    assert.equal(first.consent, 'declined');
    op.send({ type: 'mark', mark: 'session_start' });
    const second = await op.waitForEvent((e) => e.type === 'session.started' && e.session !== first.session);
    op.send({ type: 'mark', mark: 'consent', value: 'recorded' });
    const started = await op.waitForEvent((e) => e.type === 'recording.started');
    assert.equal(started.session, second.session);
    // The recording controller handles events in order: by now the first session was handled.
    assert.deepEqual(await page.evaluate(() => window.docentRecorder.asked.map((a) => a.session)), [second.session]);
    assert.equal(fs.existsSync(path.join(sessionDir(server, first.session), 'media')), false);
    await context.close();
  });
});

// Replaces the microphone by a WebAudio stream that is silent except for a 5 ms, 2 kHz click
// sounded the moment the page sends a `trigger` frame. Runs in the kiosk's pages.
function clickOnTrigger() {
  const audio = new AudioContext();
  const destination = audio.createMediaStreamDestination();
  // A silent source keeps the stream running: with no input Chromium's recorder never starts.
  const silence = audio.createConstantSource();
  silence.offset.value = 0;
  silence.connect(destination);
  silence.start();
  const send = WebSocket.prototype.send;
  window.triggerSends = []; // performance.now() of each click
  WebSocket.prototype.send = function (data) {
    if (typeof data === 'string' && data.includes('"type":"trigger"')) {
      window.triggerSends.push(performance.now());
      const osc = audio.createOscillator();
      osc.frequency.value = 2000;
      osc.connect(destination);
      osc.start();
      osc.stop(audio.currentTime + 0.005);
    }
    return send.call(this, data);
  };
  navigator.mediaDevices.getUserMedia = async () => {
    await audio.resume();
    return destination.stream;
  };
}

/** Times (s) in `file` where sound begins after at least 100 ms of silence. */
function onsets(file) {
  const pcm = execFileSync('ffmpeg', ['-v', 'error', '-i', file, '-f', 's16le', '-ac', '1', '-ar', '48000', '-'], { maxBuffer: 64 << 20 });
  const samples = new Int16Array(pcm.buffer, pcm.byteOffset, pcm.length / 2);
  const found = [];
  let quiet = Infinity;
  for (let i = 0; i < samples.length; i++) {
    if (Math.abs(samples[i]) > 2000) {
      if (quiet >= 4800) found.push(i / 48000);
      quiet = 0;
    } else {
      quiet += 1;
    }
  }
  return found;
}

test('alignment: clicks sounded at triggers lie where the recording start_us puts them', async () => {
  await withServer(bundle(), async (server, op) => {
    const { context, page } = await openKiosk(browser, server, clickOnTrigger);
    await tap(page);
    const started = await op.waitForEvent((e) => e.type === 'recording.started');
    const triggers = 12;
    for (let n = 0; n < triggers; n++) {
      await page.evaluate(() => window.docentShell.trigger('TICK'));
      await op.waitForEvent((e) => (e.type === 'act.triggered' || e.type === 'trigger.refused') && e.label === 'TICK');
      // The next click a chunk later: well apart, and paced by the recorder itself.
      const next = await page.evaluate(() => window.docentRecorder.current.next);
      await page.waitForFunction((n) => window.docentRecorder.current.next > n, next, { timeout: DEADLINE_MS });
    }
    const { startTime, sends } = await page.evaluate(() => ({
      startTime: window.docentRecorder.current.startTime,
      sends: window.triggerSends.slice(-12),
    }));
    op.send({ type: 'mark', mark: 'session_end' });
    await op.waitForEvent((e) => e.type === 'recording.stopped');
    await context.close();
    const events = corpusEvents(server.corpus).filter((e) => (e.type === 'act.triggered' || e.type === 'trigger.refused') && e.label === 'TICK');
    const file = path.join(sessionDir(server, started.session), 'media/audio-1.webm');
    // Where each click lies in the file, in ms from its first sample; the first onset may be the
    // touch that started the session (HELLO), sounded before the recording began or not.
    const found = onsets(file).map((s) => s * 1e3);
    // Each click is the onset near when the page sounded it (100 ms before to 150 ms after); one lost to
    // an audio drop-out of the loaded machine is counted, and at least ten must be found.
    const matched = sends.map((sent, i) => {
      const expected = sent - startTime;
      const at = found.find((t) => t >= expected - 100 && t <= expected + 150);
      return at === undefined ? null : { at, expected, event: events[i] };
    }).filter(Boolean);
    assert.ok(matched.length >= 10, `clicks found at ${found.map((t) => t.toFixed(0)).join(', ')} ms; sounded at ${sends.map((t) => (t - startTime).toFixed(0)).join(', ')} ms`);
    // (a) The recording's own placement: the click against the moment the page sounded it,
    // both on the kiosk's clock from the recording's first sample (startTime).
    const placement = matched.map(({ at, expected }) => at - expected);
    // (b) End to end: the click placed by start_us against its trigger's logged session_us,
    // which adds the clock exchange's error and the time the trigger took to reach the log.
    const endToEnd = matched.map(({ at, event }) => started.start_us / 1e3 + at - event.session_us / 1e3);
    const stats = (errors) => {
      const mean = errors.reduce((a, b) => a + b, 0) / errors.length;
      return { mean, max: Math.max(...errors.map(Math.abs)), list: errors.map((e) => e.toFixed(1)).join(', ') };
    };
    const a = stats(placement);
    const b = stats(endToEnd);
    console.log(`alignment over ${matched.length} of ${triggers} clicks: placement mean ${a.mean.toFixed(1)} ms, max |error| ${a.max.toFixed(1)} ms [${a.list}]; ` +
      `end to end against the log mean ${b.mean.toFixed(1)} ms, max ${b.max.toFixed(1)} ms [${b.list}]; clock error bound ${(started.clock_error_us / 1e3).toFixed(2)} ms`);
    assert.ok(a.max <= ALIGNMENT_BOUND_MS, `placement error ${a.max.toFixed(1)} ms within ${ALIGNMENT_BOUND_MS} ms`);
    assert.ok(b.max <= END_TO_END_BOUND_MS, `end-to-end error ${b.max.toFixed(1)} ms within ${END_TO_END_BOUND_MS} ms`);
  });
});
