#!/usr/bin/env node
// tap-speech: a visitor's tap to espeak-ng's first audio byte, against its floor, espeak-ng
// alone on the same text (issue 27).
//
//   cargo build --release && DOCENT_BIN=target/release/docent node bench/tap-speech.mjs \
//     [--runs 50] [--warmup 5] [--gap 100]
//
// Docent runs with `speech: {adapter: espeak}` and `--speech-wav DIR`, so its espeak adapter
// starts `espeak-ng --stdin -v en-us -s 160 -w DIR/<command id>.wav` per SAY
// (server/adapters/speech_espeak.rs). The tap is a kiosk's websocket `trigger` frame (role
// `kiosk`, `via: touch`), as the shell sends it for a tap on a `data-act` button; the act's
// `Text` becomes a SAY. The floor starts the same espeak-ng command on the same text from this
// process (spawn, its stdin a file holding the text), with `-w` into a second folder.
//
// The first audio byte is the moment the WAV file first holds more than its 44-byte header,
// seen the same way for both: fs.watch (inotify) on the folder, a stat() of the file at each
// event. espeak-ng writes through a stdio buffer, so its first write(2) carries the header
// and the first 4 KiB of audio (about 90 ms of sound at 22,050 Hz, 16 bit): the figure is the
// moment audio could first reach a player reading the file, for Docent and floor alike. Times
// are this process's performance.now(): the trigger frame sent / the spawn, to the event.
// Runs alternate Docent and floor (which goes first alternates); each waits for the previous
// SAY's `command.done` (an operator client watches the events), so no speech is queued.

import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

import { makeBundle, removeTemp, startDocent, tempDir, withDeadline } from '../tests/e2e/lib/docent.mjs';
import { connectOperator, DocentClient } from '../tests/e2e/lib/ws-client.mjs';
import { environment, environmentLine, parseArgs, pause, ratio, save, summary, tableRows } from './lib/report.mjs';

const USAGE = 'usage: node bench/tap-speech.mjs [--runs N (50)] [--warmup N (5)] [--gap MS (100)]';
const TEXT = 'Welcome to the museum. Let me show you the first room.';
const VOICE = 'en-us';
const RATE = 160;
const WAV_HEADER = 44;
const DEADLINE_MS = 10_000;

/**
 * Watches `dir` for WAV files; `next()` resolves with the performance.now() at which the next
 * new file first held audio (more than its header).
 */
function firstByteWatcher(dir) {
  const seen = new Set();
  let waiter = null;
  const watcher = fs.watch(dir, (_event, name) => {
    const at = performance.now();
    if (!name || seen.has(name) || !waiter) return;
    let size = 0;
    try {
      size = fs.statSync(path.join(dir, name)).size;
    } catch {
      return; // removed already
    }
    if (size <= WAV_HEADER) return;
    seen.add(name);
    const w = waiter;
    waiter = null;
    w({ at, name, size });
  });
  return {
    next: () =>
      withDeadline(new Promise((resolve) => (waiter = resolve)), DEADLINE_MS, `no audio in ${dir} within ${DEADLINE_MS} ms`),
    close: () => watcher.close(),
  };
}

/**
 * The floor: espeak-ng alone, as Docent starts it, its standard input the text in a file (so
 * the text is there at once, not written by this process's event loop after the spawn).
 * Resolves once it has exited.
 */
function espeakAlone(dir, n, watcher, textFile) {
  const first = watcher.next();
  const input = fs.openSync(textFile, 'r');
  const t0 = performance.now();
  const child = spawn('espeak-ng', ['--stdin', '-v', VOICE, '-s', String(RATE), '-w', path.join(dir, `floor-${n}.wav`)], {
    stdio: [input, 'ignore', 'ignore'],
  });
  // spawn() returns once the child has exec'd (libuv waits for it): the cost of starting a
  // process from this one, which Docent pays in its own way for its espeak-ng.
  const spawned = performance.now();
  fs.closeSync(input);
  const exited = new Promise((resolve) => child.once('exit', resolve));
  return first.then(async (f) => {
    await exited;
    return { ms: f.at - t0, spawn_ms: spawned - t0, after_spawn_ms: f.at - spawned, size: f.size };
  });
}

/** `x` rounded to 0.1 with its sign: +1.5, -0.5. */
function signed(x) {
  const r = Math.round(x * 10) / 10;
  return r >= 0 ? `+${r}` : String(r);
}

async function main() {
  const opts = parseArgs(process.argv.slice(2), { runs: 50, warmup: 5, gap: 100 }, USAGE);
  const bundle = makeBundle({
    'docent.yaml': `home: index.html\nspeech: {adapter: espeak, voice: ${VOICE}, rate: ${RATE}}\n`,
    'acts.yaml': `- Label: HELLO\n  Text: [${TEXT}]\n`,
    'pages/index.html':
      '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>home</title></head>' +
      '<body><button data-act="HELLO">Hello</button></body></html>\n',
  });
  const docentWav = tempDir('docent-bench-wav-');
  const floorWav = tempDir('docent-bench-floor-wav-');
  const docentFiles = firstByteWatcher(docentWav);
  const floorFiles = firstByteWatcher(floorWav);
  const textDir = tempDir('docent-bench-text-');
  const textFile = path.join(textDir, 'text.txt');
  fs.writeFileSync(textFile, TEXT);
  let server;
  const clients = [];
  try {
    server = await startDocent(bundle, { args: ['--no-watch', '--speech-wav', docentWav] });
    const operator = await connectOperator(server.wsUrl, 'bench-observer');
    clients.push(operator);
    const kiosk = await DocentClient.connect(server.wsUrl, { role: 'kiosk', name: 'bench-kiosk' });
    clients.push(kiosk);

    const docentTap = async (n) => {
      const done = operator.waitForEvent((e) => ['command.done', 'command.failed', 'command.cancelled'].includes(e.type), {
        timeout: DEADLINE_MS,
      });
      const first = docentFiles.next();
      const ref = `tap-${n}`;
      const t0 = performance.now();
      kiosk.send({ type: 'trigger', label: 'HELLO', ref, via: 'touch' });
      const answer = await kiosk.waitFor((f) => f.ref === ref, { timeout: DEADLINE_MS });
      const triggered = performance.now();
      if (answer.type !== 'triggered') throw new Error(`the tap was refused: ${JSON.stringify(answer)}`);
      const f = await first;
      const outcome = await done;
      if (outcome.type !== 'command.done') throw new Error(`the SAY did not finish: ${JSON.stringify(outcome)}`);
      return { ms: f.at - t0, answered_ms: triggered - t0, size: f.size };
    };

    const samples = { docent: [], floor: [] };
    const loadBefore = os.loadavg()[0];
    for (let i = 0; i < opts.warmup + opts.runs; i++) {
      const order = i % 2 === 0 ? ['docent', 'floor'] : ['floor', 'docent'];
      for (const which of order) {
        const t = which === 'docent' ? await docentTap(i) : await espeakAlone(floorWav, i, floorFiles, textFile);
        if (i >= opts.warmup) samples[which].push(t);
        await pause(opts.gap);
      }
    }
    const env = environment(loadBefore);
    const docent = summary(samples.docent.map((t) => t.ms));
    const floor = summary(samples.floor.map((t) => t.ms));
    const rows = [
      ['Docent: kiosk trigger sent → first audio byte in the WAV', docent],
      ['floor: espeak-ng spawned → first audio byte in the WAV', floor],
      ['  Docent: trigger sent → `triggered` answer received', summary(samples.docent.map((t) => t.answered_ms))],
      ['  floor: spawn() called → returned (fork and exec from Node)', summary(samples.floor.map((t) => t.spawn_ms))],
      ['  floor: spawn() returned → first audio byte', summary(samples.floor.map((t) => t.after_spawn_ms))],
    ];
    const lines = [
      `tap-speech: ${opts.runs} runs each (after ${opts.warmup} warm-up), Docent and floor interleaved, ` +
        `${opts.gap} ms apart after each utterance's end; espeak-ng -v ${VOICE} -s ${RATE}, "${TEXT}"`,
      environmentLine(env) + `; ${env.espeak}`,
      '',
      ...tableRows(rows),
      '',
      `Docent / floor at p50: ${ratio(docent.p50, floor.p50)}x (${signed(docent.p50 - floor.p50)} ms), ` +
        `at p90: ${ratio(docent.p90, floor.p90)}x`,
    ];
    save('tap-speech', lines, {
      bench: 'tap-speech',
      runs: opts.runs,
      warmup: opts.warmup,
      text: TEXT,
      docent_first_byte_ms: docent,
      floor_first_byte_ms: floor,
      trigger_answered_ms: rows[2][1],
      ratio_p50: ratio(docent.p50, floor.p50),
      ratio_p90: ratio(docent.p90, floor.p90),
      ...env,
    });
  } finally {
    for (const c of clients) await c.close().catch(() => {});
    await server?.stop().catch(() => {});
    docentFiles.close();
    floorFiles.close();
    for (const dir of [bundle, docentWav, floorWav, textDir]) removeTemp(dir);
    if (server) removeTemp(server.corpusDir);
  }
}

main().catch((error) => {
  console.error(`tap-speech: ${error.stack ?? error}`);
  process.exitCode = 1;
});
