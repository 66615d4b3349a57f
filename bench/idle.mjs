#!/usr/bin/env node
// idle: what Docent costs while nothing happens: CPU time and resident memory of
// `docent serve dialogs/museum-tour` with one kiosk (the Chromium kiosk shell showing the
// tour's home page) connected for a minute, beside its floors (issue 27).
//
//   cargo build --release && DOCENT_BIN=target/release/docent node bench/idle.mjs [--seconds 60] [--settle 5]
//
// Three phases of `--seconds` each, one after the other, each after `--settle` s untimed:
//   kiosk         Docent and one headless Chromium (1280x800, touch) on the kiosk shell `/`;
//   server alone  Docent with no client at all (the server's own floor: timers, the watcher);
//   static        `python3 -m http.server` serving the tour's pages/ and the same Chromium
//                 showing index.html directly (the floor of a kiosk with no Docent behind it).
// CPU is utime + stime from /proc/PID/stat over the phase (10 ms ticks), as % of one core;
// RSS is VmRSS at the phase's start and end, and PSS (smaps_rollup) at its end. Chromium's
// figures add up all its processes (the browser and its children: renderers, GPU, network,
// utility), read the same way; its summed RSS counts shared pages in every process, its
// summed PSS once.

import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

import { freePort, REPO, removeTemp, startDocent, withDeadline } from '../tests/e2e/lib/docent.mjs';
import { launchBrowser, newTouchContext, watchExceptions } from '../tests/e2e/lib/browser.mjs';
import { openShell } from '../tests/e2e/lib/kiosk.mjs';
import { environment, environmentLine, parseArgs, pause, save } from './lib/report.mjs';

const USAGE = 'usage: node bench/idle.mjs [--seconds N (60)] [--settle N (5)]';
const TOUR = path.join(REPO, 'dialogs/museum-tour');
const TICKS_PER_S = 100; // CLK_TCK on Linux
const PYTHON = process.env.PYTHON_BIN ?? (fs.existsSync('/usr/bin/python3') ? '/usr/bin/python3' : 'python3');

/** utime + stime of `pid` in ticks, and its parent pid; null when it is gone. */
function stat(pid) {
  try {
    const text = fs.readFileSync(`/proc/${pid}/stat`, 'utf8');
    const fields = text.slice(text.lastIndexOf(')') + 2).split(' ');
    // fields[0] is field 3 (state): ppid is field 4, utime 14, stime 15.
    return { ppid: Number(fields[1]), ticks: Number(fields[11]) + Number(fields[12]) };
  } catch {
    return null;
  }
}

function rssKiB(pid) {
  try {
    return Number(/VmRSS:\s+(\d+)/.exec(fs.readFileSync(`/proc/${pid}/status`, 'utf8'))?.[1] ?? NaN);
  } catch {
    return NaN;
  }
}

/** Proportional set size of `pid` in KiB (shared pages split among their users), or NaN. */
function pssKiB(pid) {
  try {
    return Number(/^Pss:\s+(\d+)/m.exec(fs.readFileSync(`/proc/${pid}/smaps_rollup`, 'utf8'))?.[1] ?? NaN);
  } catch {
    return NaN;
  }
}

/** `pid` and all its descendants, from /proc. */
function tree(pid) {
  const parents = new Map();
  for (const name of fs.readdirSync('/proc')) {
    if (!/^\d+$/.test(name)) continue;
    const s = stat(Number(name));
    if (s) parents.set(Number(name), s.ppid);
  }
  const all = new Set([pid]);
  let grew = true;
  while (grew) {
    grew = false;
    for (const [child, parent] of parents) {
      if (all.has(parent) && !all.has(child)) {
        all.add(child);
        grew = true;
      }
    }
  }
  return [...all];
}

/** CPU ticks and RSS (KiB) of a set of processes (one, or a tree read now). */
function sample(pids) {
  let ticks = 0;
  let rss = 0;
  let pss = 0;
  for (const pid of pids) {
    ticks += stat(pid)?.ticks ?? 0;
    rss += rssKiB(pid) || 0;
    pss += pssKiB(pid) || 0;
  }
  return { ticks, rss, pss, at: performance.now() };
}

/** Measures `who` ({name: () => pids}) over `seconds`; CPU % of one core and RSS in MiB. */
async function measure(who, seconds) {
  const before = Object.fromEntries(Object.entries(who).map(([k, pids]) => [k, sample(pids())]));
  await pause(seconds * 1000);
  const result = {};
  for (const [k, pids] of Object.entries(who)) {
    const after = sample(pids());
    const wall = (after.at - before[k].at) / 1000;
    const cpuS = (after.ticks - before[k].ticks) / TICKS_PER_S;
    result[k] = {
      cpu_s: Math.round(cpuS * 100) / 100,
      cpu_pct: Math.round((cpuS / wall) * 10000) / 100,
      rss_start_mib: Math.round((before[k].rss / 1024) * 10) / 10,
      rss_end_mib: Math.round((after.rss / 1024) * 10) / 10,
      pss_end_mib: Math.round((after.pss / 1024) * 10) / 10,
    };
  }
  return result;
}

/** `python3 -m http.server` on the tour's folder; resolves once it answers. */
async function staticServer() {
  const port = await freePort();
  const child = spawn(PYTHON, ['-m', 'http.server', String(port), '--bind', '127.0.0.1', '--directory', TOUR], {
    stdio: 'ignore',
  });
  const base = `http://127.0.0.1:${port}`;
  await withDeadline(
    (async () => {
      for (;;) {
        try {
          await fetch(`${base}/pages/index.html`);
          return;
        } catch {
          await pause(10);
        }
      }
    })(),
    20_000,
    'python3 -m http.server did not answer',
  );
  return { child, base };
}

async function main() {
  const opts = parseArgs(process.argv.slice(2), { seconds: 60, settle: 5 }, USAGE);
  const loadBefore = os.loadavg()[0];
  const phases = {};
  let server;
  let browser;
  let python;
  let corpus;
  try {
    browser = await launchBrowser();
    // Chromium's processes: this process's descendants but Docent and the static server (the
    // browser is a child of this process; playwright-core gives no handle on its pid).
    const chromium = () =>
      tree(process.pid).filter((pid) => pid !== process.pid && pid !== server?.process.pid && pid !== python?.child.pid);

    server = await startDocent(TOUR);
    corpus = server.corpusDir;
    const docent = () => [server.process.pid];
    const kioskContext = await newTouchContext(browser);
    const kiosk = await kioskContext.newPage();
    const errors = watchExceptions(kiosk);
    await openShell(kiosk, server, 'index.html');
    await pause(opts.settle * 1000);
    phases.kiosk = await measure({ docent, chromium }, opts.seconds);
    if (errors.length) throw new Error(`the kiosk failed: ${errors.join('; ')}`);
    await kioskContext.close();

    await pause(opts.settle * 1000);
    phases.alone = await measure({ docent }, opts.seconds);
    await server.stop();
    server = null;

    python = await staticServer();
    const staticContext = await newTouchContext(browser);
    const page = await staticContext.newPage();
    await page.goto(`${python.base}/pages/index.html`);
    await pause(opts.settle * 1000);
    phases.static = await measure({ python: () => [python.child.pid], chromium }, opts.seconds);
    await staticContext.close();

    const env = environment(loadBefore);
    const row = (name, m) => `| ${name} | ${m.cpu_s} | ${m.cpu_pct} | ${m.rss_start_mib} | ${m.rss_end_mib} | ${m.pss_end_mib} |`;
    const lines = [
      `idle: ${opts.seconds} s per phase after ${opts.settle} s settling; CPU = utime + stime from /proc over the phase, ` +
        `% of one core; RSS = VmRSS, PSS = Pss of smaps_rollup (Chromium: all its processes summed; ` +
        `its RSS sum counts shared pages once per process, its PSS sum does not)`,
      environmentLine(env) + `; ${env.chromium}`,
      '',
      '| process, phase | CPU s | CPU % | RSS start MiB | RSS end MiB | PSS end MiB |',
      '|---|---|---|---|---|---|',
      row('docent serve museum-tour, one kiosk connected', phases.kiosk.docent),
      row('  Chromium kiosk shell on Docent', phases.kiosk.chromium),
      row('docent serve museum-tour, no client (floor)', phases.alone.docent),
      row('python3 -m http.server, the same page open (floor)', phases.static.python),
      row('  Chromium on the static page', phases.static.chromium),
    ];
    save('idle', lines, { bench: 'idle', seconds: opts.seconds, settle: opts.settle, ...phases, ...env });
  } finally {
    await browser?.close().catch(() => {});
    if (server) await server.stop().catch(() => {});
    python?.child.kill('SIGTERM');
    removeTemp(corpus);
  }
}

main().catch((error) => {
  console.error(`idle: ${error.stack ?? error}`);
  process.exitCode = 1;
});
