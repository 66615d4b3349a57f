#!/usr/bin/env node
// recording-overhead: what recording a visitor session costs the kiosk device and the network
// (issue 12's figures): CPU of all of Chromium's processes (browser, renderer, audio and GPU
// services, from CDP SystemInfo.getProcessInfo's cumulative cpuTime) and of Docent (from
// /proc/PID/stat), over the same length of time with the kiosk idle on its home page, recording
// audio, and recording audio and video; and the upload rate (the recording's acknowledged bytes
// per second, from `recording.stopped`).
//
//   cargo build && node bench/recording-overhead.mjs [--seconds 30]
//
// Chromium's fake microphone and camera (`--use-fake-device-for-media-stream`); the camera is a
// synthetic picture, so a real camera's video costs more. Prints a table and one JSON line and
// saves both to bench/results/recording-overhead-latest.txt.

import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

import { makeBundle, removeTemp, REPO, startDocent } from '../tests/e2e/lib/docent.mjs';
import { launchBrowser, newTouchContext } from '../tests/e2e/lib/browser.mjs';
import { openShell } from '../tests/e2e/lib/kiosk.mjs';
import { connectOperator } from '../tests/e2e/lib/ws-client.mjs';

const seconds = Number(process.argv[process.argv.indexOf('--seconds') + 1]) || 30;
/** Clock ticks per second of /proc/PID/stat (USER_HZ, 100 on Linux). */
const TICK = 100;

/** Chromium's CPU seconds so far, all processes together. */
async function chromiumCpu(cdp) {
  const { processInfo } = await cdp.send('SystemInfo.getProcessInfo');
  return processInfo.reduce((sum, p) => sum + p.cpuTime, 0);
}

/** A process's CPU seconds so far (user + system). */
function processCpu(pid) {
  const fields = fs.readFileSync(`/proc/${pid}/stat`, 'utf8').split(') ')[1].split(' ');
  return (Number(fields[11]) + Number(fields[12])) / TICK;
}

function wait(ms) {
  return new Promise((resolve) => setTimeout(resolve, ms));
}

async function phase(record, recordIt) {
  const bundle = makeBundle({
    'acts.yaml': '- Label: HELLO\n  Text: [Hi]\n',
    'docent.yaml': `speech: {adapter: log}\ncorpus: {session_start: marked, record: ${record}}\n`,
    'pages/index.html': '<html><body><h1>Welcome</h1></body></html>',
  });
  const server = await startDocent(bundle);
  const browser = await launchBrowser(['--use-fake-device-for-media-stream', '--use-fake-ui-for-media-stream']);
  const op = await connectOperator(server.wsUrl);
  try {
    const cdp = await browser.newBrowserCDPSession();
    const context = await newTouchContext(browser);
    const page = await context.newPage();
    await openShell(page, server, 'index.html');
    let started = null;
    let session = null;
    if (recordIt) {
      op.send({ type: 'mark', mark: 'session_start' });
      session = await op.waitForEvent((e) => e.type === 'session.started');
      started = await op.waitForEvent((e) => e.type === 'recording.started');
    }
    await wait(2000); // settle: getUserMedia and the first chunks are not the steady state
    const [c0, d0, t0] = [await chromiumCpu(cdp), processCpu(server.process.pid), performance.now()];
    await wait(seconds * 1000); // the measured interval itself
    const [c1, d1, t1] = [await chromiumCpu(cdp), processCpu(server.process.pid), performance.now()];
    const elapsed = (t1 - t0) / 1000;
    let rate = null;
    if (recordIt) {
      op.send({ type: 'mark', mark: 'session_end' });
      const stopped = await op.waitForEvent((e) => e.type === 'recording.stopped');
      const ended = await op.waitForEvent((e) => e.type === 'session.ended');
      // From the recording's first sample to the session's end, on the hub's clock.
      rate = stopped.bytes / ((ended.mono_us - session.mono_us - started.start_us) / 1e6);
    }
    await context.close();
    return { chromium: (c1 - c0) / elapsed, docent: (d1 - d0) / elapsed, rate };
  } finally {
    await op.close().catch(() => {});
    await browser.close();
    await server.stop();
    removeTemp(bundle);
  }
}

const idle = await phase('[audio]', false);
const audio = await phase('[audio]', true);
const video = await phase('[audio, video]', true);
const pct = (x) => `${(x * 100).toFixed(1)} %`;
const rows = [
  ['kiosk idle, not recording', idle],
  ['recording audio', audio],
  ['recording audio + video', video],
].map(([name, r]) => `| ${name} | ${pct(r.chromium)} | ${pct(r.docent)} | ${r.rate === null ? '-' : `${(r.rate / 1024).toFixed(1)} KiB/s`} |`);
const table = [
  `recording overhead over ${seconds} s each, ${os.cpus().length} cores (${os.cpus()[0]?.model ?? 'unknown'}), ${new Date().toISOString()}`,
  '| kiosk | Chromium CPU (of one core) | Docent CPU | upload rate |',
  '| --- | --- | --- | --- |',
  ...rows,
].join('\n');
const json = JSON.stringify({ seconds, idle, audio, video });
console.log(`${table}\n${json}`);
fs.writeFileSync(path.join(REPO, 'bench/results/recording-overhead-latest.txt'), `${table}\n${json}\n`);
