#!/usr/bin/env node
// startup: `docent serve` from spawn to accepting connections, for dialogs/museum-tour and for
// the generated 10,000-act bundle, against a trivial server process (issue 27).
//
//   cargo build --release && cargo build --release --example check-bench &&
//     DOCENT_BIN=target/release/docent node bench/startup.mjs [--runs 10]
//
// The 10,000-act bundle is the one `docent check`'s benchmark makes (bench/check.rs: 10,000
// acts over 10 files, 1,000 pages, a picture), written by `check-bench --write DIR`
// ($CHECK_BENCH_BIN, default target/release/examples/check-bench). Each run spawns
// `docent serve BUNDLE --listen 127.0.0.1:PORT --corpus TMP` (watching the bundle, as by
// default) with the environment the browser tests give it (credentials, a media cache), tries
// to connect to PORT every millisecond until the kernel accepts a connection, then asks
// `GET /healthz` (again every millisecond while refused) until it is answered: the figure.
// The TCP accept alone says little: Docent binds its socket before it starts the server
// (server/main.rs), and the kernel completes connections from then on, which wait unanswered
// until it serves. It also notes when the address line ("websocket: ws://...") is printed,
// and the resident memory once answered. Then SIGTERM, and the next. The floors, spawned and
// polled the same way: a Node process that answers every request with "ok"
// (`http.createServer().listen`), and `python3 -m http.server` (/usr/bin/python3; a 404 for
// /healthz is an answer). The five alternate, in a
// rotating order, `--runs` times; times are this process's performance.now() in ms.

import { execFileSync, spawn } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';

import {
  copyBundle,
  DM_TOKEN,
  docentBin,
  freePort,
  OPERATOR_TOKEN,
  REPO,
  removeTemp,
  tempDir,
  withDeadline,
} from '../tests/e2e/lib/docent.mjs';
import { environment, environmentLine, parseArgs, ratio, save, summary, tableRows } from './lib/report.mjs';

const USAGE = 'usage: node bench/startup.mjs [--runs N (10)]';
const DEADLINE_MS = 30_000;
/** Python for the second floor: the system's, not a version manager's shim (a shell script). */
const PYTHON = process.env.PYTHON_BIN ?? (fs.existsSync('/usr/bin/python3') ? '/usr/bin/python3' : 'python3');

/** Resolves once a TCP connection to `port` is accepted; tries every millisecond. */
function acceptedAt(port, child) {
  return new Promise((resolve, reject) => {
    const attempt = () => {
      if (child.exitCode !== null || child.signalCode !== null) {
        reject(new Error(`the process exited (${child.exitCode ?? child.signalCode}) before it accepted`));
        return;
      }
      const socket = net.connect({ port, host: '127.0.0.1' });
      socket.once('connect', () => {
        const at = performance.now();
        socket.destroy();
        resolve(at);
      });
      socket.once('error', () => {
        socket.destroy();
        setTimeout(attempt, 1);
      });
    };
    attempt();
  });
}

/**
 * Resolves once `GET /healthz` on `port` is answered (any status); a refused or reset
 * connection is tried again after a millisecond. A connection the kernel accepted before the
 * server serves waits for the answer: that wait is part of the start.
 */
function answeredAt(port, child) {
  return new Promise((resolve, reject) => {
    const attempt = () => {
      if (child.exitCode !== null || child.signalCode !== null) {
        reject(new Error(`the process exited (${child.exitCode ?? child.signalCode}) before it answered`));
        return;
      }
      const req = http.get({ host: '127.0.0.1', port, path: '/healthz', agent: false }, (res) => {
        const at = performance.now();
        res.resume();
        resolve({ at, status: res.statusCode });
      });
      req.once('error', () => setTimeout(attempt, 1));
    };
    attempt();
  });
}

/** Resident memory of `pid` in MiB (VmRSS), or null. */
function rssMiB(pid) {
  try {
    const kb = /VmRSS:\s+(\d+)/.exec(fs.readFileSync(`/proc/${pid}/status`, 'utf8'))?.[1];
    return kb ? Math.round((Number(kb) / 1024) * 10) / 10 : null;
  } catch {
    return null;
  }
}

/** One start: spawn → accepted (and → address printed, for Docent). Stops the process after. */
async function startOnce(kind, bundle, cache) {
  const port = await freePort();
  const corpus = tempDir('docent-bench-corpus-');
  const [cmd, args] = {
    'floor-node': [process.execPath, ['-e', `require('http').createServer((q, s) => s.end('ok')).listen(${port}, '127.0.0.1')`]],
    'floor-python': [PYTHON, ['-m', 'http.server', String(port), '--bind', '127.0.0.1', '--directory', corpus]],
  }[kind] ?? [docentBin(), ['serve', bundle, '--listen', `127.0.0.1:${port}`, '--corpus', corpus]];
  const t0 = performance.now();
  const child = spawn(cmd, args, {
    stdio: ['ignore', 'pipe', 'pipe'],
    env: {
      ...process.env,
      RUST_LOG: 'docent=warn',
      XDG_CACHE_HOME: cache,
      DOCENT_OPERATOR_TOKEN: OPERATOR_TOKEN,
      DOCENT_DM_TOKEN: DM_TOKEN,
    },
  });
  let output = '';
  let printed;
  child.stdout.setEncoding('utf8');
  child.stderr.setEncoding('utf8');
  child.stdout.on('data', (chunk) => {
    output += chunk;
    if (printed === undefined && /^\s*websocket:\s+ws:\/\//m.test(output)) printed = performance.now();
  });
  child.stderr.on('data', (chunk) => (output += chunk));
  const exited = new Promise((resolve) => child.once('exit', resolve));
  try {
    const accepted = await withDeadline(acceptedAt(port, child), DEADLINE_MS, `${kind} did not accept within ${DEADLINE_MS} ms`);
    const answer = await withDeadline(answeredAt(port, child), DEADLINE_MS, `${kind} did not answer within ${DEADLINE_MS} ms`);
    if (!kind.startsWith('floor') && answer.status !== 200) throw new Error(`GET /healthz answered ${answer.status}`);
    const rss = rssMiB(child.pid);
    return {
      ms: answer.at - t0,
      tcp_ms: accepted - t0,
      printed_ms: printed === undefined ? undefined : printed - t0,
      rss,
    };
  } catch (e) {
    throw new Error(`${kind}: ${e.message}\n${output}`);
  } finally {
    child.kill('SIGTERM');
    await withDeadline(exited, DEADLINE_MS, `${kind} did not stop`).catch(() => child.kill('SIGKILL'));
    removeTemp(corpus);
  }
}

async function main() {
  const opts = parseArgs(process.argv.slice(2), { runs: 10 }, USAGE);
  const checkBench = process.env.CHECK_BENCH_BIN ?? path.join(REPO, 'target/release/examples/check-bench');
  if (!fs.existsSync(checkBench)) throw new Error(`no ${checkBench}: run \`cargo build --release --example check-bench\``);
  const big = tempDir('docent-bench-10k-');
  execFileSync(checkBench, ['--write', big], { stdio: 'ignore' });
  const cache = tempDir('docent-bench-cache-');
  // The tour again with `speech: {adapter: log}`: what the espeak-ng probes at start-up cost
  // (server/serve.rs runs `espeak-ng --version`, `--voices` and a silent utterance in turn).
  const tourYaml = fs.readFileSync(path.join(REPO, 'dialogs/museum-tour/docent.yaml'), 'utf8');
  if (!/^speech: \{/m.test(tourYaml)) throw new Error('dialogs/museum-tour/docent.yaml has no one-line speech: {...} to replace');
  const tourLog = copyBundle('museum-tour', {
    'docent.yaml': tourYaml.replace(/^speech: \{/m, 'speech: { adapter: log,'),
  });
  const bundles = {
    'museum-tour': path.join(REPO, 'dialogs/museum-tour'),
    'museum-tour-log': tourLog,
    '10k-acts': big,
    'floor-node': null,
    'floor-python': null,
  };
  const kinds = Object.keys(bundles);
  const samples = Object.fromEntries(kinds.map((k) => [k, []]));
  try {
    // One untimed start each first: files in the page cache, as on a kiosk that ran before.
    for (const kind of kinds) await startOnce(kind, bundles[kind], cache);
    const loadBefore = os.loadavg()[0];
    for (let i = 0; i < opts.runs; i++) {
      for (let k = 0; k < kinds.length; k++) {
        const kind = kinds[(i + k) % kinds.length];
        samples[kind].push(await startOnce(kind, bundles[kind], cache));
      }
    }
    const env = environment(loadBefore);
    const s = (kind, key) => summary(samples[kind].map((t) => t[key]).filter((v) => v !== undefined && v !== null));
    const tour = s('museum-tour', 'ms');
    const tenK = s('10k-acts', 'ms');
    const floor = s('floor-node', 'ms');
    const python = s('floor-python', 'ms');
    const rows = [
      ['docent serve dialogs/museum-tour: spawn → GET /healthz answered', tour],
      ['docent serve 10,000-act bundle: spawn → GET /healthz answered', tenK],
      ['floor: node http.createServer().listen: spawn → GET answered', floor],
      ['floor: python3 -m http.server: spawn → GET answered', python],
      ['  museum-tour with speech: {adapter: log}: spawn → GET /healthz answered', s('museum-tour-log', 'ms')],
      ['  museum-tour: spawn → TCP connect accepted (listening socket bound)', s('museum-tour', 'tcp_ms')],
      ['  10,000 acts: spawn → TCP connect accepted', s('10k-acts', 'tcp_ms')],
      ['  node floor: spawn → TCP connect accepted', s('floor-node', 'tcp_ms')],
      ['  museum-tour: spawn → address line printed', s('museum-tour', 'printed_ms')],
      ['  10,000 acts: spawn → address line printed', s('10k-acts', 'printed_ms')],
      ['  RSS when answered, MiB: museum-tour', s('museum-tour', 'rss')],
      ['  RSS when answered, MiB: 10,000 acts', s('10k-acts', 'rss')],
      ['  RSS when answered, MiB: node floor', s('floor-node', 'rss')],
      ['  RSS when answered, MiB: python floor', s('floor-python', 'rss')],
    ];
    const lines = [
      `startup: ${opts.runs} starts each (after one untimed), interleaved; spawn → first HTTP answer, ` +
        `connect tried every 1 ms`,
      environmentLine(env),
      '',
      ...tableRows(rows),
      '',
      `at p50, museum-tour / node floor: ${ratio(tour.p50, floor.p50)}x, / python floor: ${ratio(tour.p50, python.p50)}x; ` +
        `10,000 acts / node floor: ${ratio(tenK.p50, floor.p50)}x, / python floor: ${ratio(tenK.p50, python.p50)}x`,
    ];
    save('startup', lines, {
      bench: 'startup',
      runs: opts.runs,
      museum_tour_ms: tour,
      acts_10k_ms: tenK,
      floor_node_ms: floor,
      floor_python_ms: python,
      ratio_tour_node_p50: ratio(tour.p50, floor.p50),
      ratio_10k_node_p50: ratio(tenK.p50, floor.p50),
      ratio_tour_python_p50: ratio(tour.p50, python.p50),
      ratio_10k_python_p50: ratio(tenK.p50, python.p50),
      rss_mib: Object.fromEntries(rows.slice(-4).map(([name, v]) => [name.split(': ')[1], v.p50])),
      ...env,
    });
  } finally {
    removeTemp(big);
    removeTemp(tourLog);
    removeTemp(cache);
  }
}

main().catch((error) => {
  console.error(`startup: ${error.stack ?? error}`);
  process.exitCode = 1;
});
