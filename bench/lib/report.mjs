// What the "speed where people feel it" benchmarks share (bench/README.md): percentiles, the
// machine's state during a run, and saving a run's table and JSON line to
// bench/results/NAME-latest.txt. Each benchmark measures its floor in the same run, so a busy
// machine slows both and the ratio stays meaningful.

import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

import { docentBin, REPO } from '../../tests/e2e/lib/docent.mjs';

/** The `q` quantile of sorted values (nearest rank: a value that was measured). */
export function quantile(sorted, q) {
  if (sorted.length === 0) return NaN;
  const i = Math.min(sorted.length - 1, Math.max(0, Math.ceil(q * sorted.length) - 1));
  return sorted[i];
}

/** p50, p90, p99, min, max and mean of `values`, rounded to 0.1. */
export function summary(values) {
  const s = [...values].sort((a, b) => a - b);
  const r = (x) => Math.round(x * 10) / 10;
  return {
    n: s.length,
    p50: r(quantile(s, 0.5)),
    p90: r(quantile(s, 0.9)),
    p99: r(quantile(s, 0.99)),
    min: r(s[0]),
    max: r(s.at(-1)),
    mean: r(s.reduce((a, b) => a + b, 0) / s.length),
  };
}

/** `a / b` rounded to 0.01 (the "times the floor" column). */
export function ratio(a, b) {
  return Math.round((a / b) * 100) / 100;
}

/** Output of a command, or null when it cannot run. */
export function sh(cmd, args) {
  try {
    return execFileSync(cmd, args, { cwd: REPO, encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] }).trim();
  } catch {
    return null;
  }
}

/** What a reader needs to weigh the figures: versions, the machine and its load. */
export function environment(loadBefore) {
  const chromium = sh(process.env.CHROMIUM_BIN ?? '/usr/bin/chromium', ['--version']);
  const r = (x) => Math.round(x * 100) / 100;
  return {
    commit: sh('git', ['rev-parse', '--short', 'HEAD']),
    dirty: Boolean(sh('git', ['status', '--porcelain', '--', 'server', 'static', 'Cargo.lock'])),
    docent: path.relative(REPO, docentBin()) || docentBin(),
    chromium: chromium?.split('\n').at(-1) ?? null,
    espeak: sh('espeak-ng', ['--version'])?.split('\n')[0] ?? null,
    cpus: os.cpus().length,
    loadavg_1m: [r(loadBefore), r(os.loadavg()[0])],
    date: new Date().toISOString(),
  };
}

/** The line under a table's title: the binary, commit and load. */
export function environmentLine(env) {
  return (
    `docent ${env.docent} at ${env.commit}${env.dirty ? ' (server/ or static/ changed)' : ''}; ` +
    `${env.cpus} CPUs, load average ${env.loadavg_1m[0]} before, ${env.loadavg_1m[1]} after`
  );
}

/** A markdown table row per `[name, summary]`, with p50/p90/p99/max/mean. */
export function tableRows(rows) {
  const lines = ['| interval | n | p50 | p90 | p99 | max | mean |', '|---|---|---|---|---|---|---|'];
  for (const [name, s] of rows) lines.push(`| ${name} | ${s.n} | ${s.p50} | ${s.p90} | ${s.p99} | ${s.max} | ${s.mean} |`);
  return lines;
}

/** Prints `lines` and the JSON line, and saves both to bench/results/NAME-latest.txt. */
export function save(name, lines, json) {
  const text = [...lines, '', JSON.stringify(json)].join('\n') + '\n';
  process.stdout.write(text);
  const out = path.join(REPO, `bench/results/${name}-latest.txt`);
  fs.mkdirSync(path.dirname(out), { recursive: true });
  fs.writeFileSync(out, text);
  console.error(`saved to ${path.relative(process.cwd(), out) || out}`);
}

/** Parses `--name value` / `--name=value` whole numbers into a copy of `defaults`. */
export function parseArgs(argv, defaults, usage) {
  const opts = { ...defaults };
  for (let i = 0; i < argv.length; i++) {
    const arg = argv[i];
    if (arg === '--help' || arg === '-h') {
      console.log(usage);
      process.exit(0);
    }
    const m = /^--([a-z-]+)(?:=(.*))?$/.exec(arg);
    if (!m || !(m[1] in defaults)) throw new Error(`unknown argument ${arg} (see --help)`);
    const value = Number(m[2] ?? argv[++i]);
    if (!Number.isInteger(value) || value < 0) throw new Error(`--${m[1]} wants a whole number`);
    opts[m[1]] = value;
  }
  return opts;
}

/** Resolves after `ms` (a pace between measurements, never a wait for a result). */
export function pause(ms) {
  return new Promise((resolve) => setTimeout(resolve, ms));
}

/**
 * How far apart two documents' epoch clocks (performance.timeOrigin + performance.now()) are:
 * reads `a`, then `b`, then `a` again, `rounds` times. `b`'s reading was taken between the two
 * of `a`, so each round bounds b's clock minus a's to (b - a_after, b - a_before); the bounds
 * of all rounds intersect in `offset_ms` [low, high]. A constant offset lies in it; an empty
 * interval (low > high) would mean the clocks do not run together. Also the median bracket
 * (how long one round's a → b → a took), in ms.
 */
export async function clockAgreement(a, b, rounds = 50) {
  const now = () => performance.timeOrigin + performance.now();
  let low = -Infinity;
  let high = Infinity;
  const widths = [];
  for (let i = 0; i < rounds; i++) {
    const before = await a.evaluate(now);
    const mid = await b.evaluate(now);
    const after = await a.evaluate(now);
    low = Math.max(low, mid - after);
    high = Math.min(high, mid - before);
    widths.push(after - before);
  }
  widths.sort((x, y) => x - y);
  const r = (x) => Math.round(x * 1000) / 1000;
  return { offset_ms: [r(low), r(high)], consistent: low <= high, bracket_p50_ms: r(quantile(widths, 0.5)) };
}

/** The clock line of a table: what `clockAgreement` found, in words. */
export function clockLine(what, clock) {
  const [low, high] = clock.offset_ms;
  return clock.consistent
    ? `clock: ${what} epoch clocks (performance.timeOrigin + now()) differ by between ${low} and ${high} ms ` +
        `(${clock.bracket_p50_ms} ms per check, median)`
    : `clock: ${what} epoch clocks do NOT agree (offset bounds ${low} > ${high} ms): read the cross-document rows with care`;
}
