// What the two paint benchmarks (tap-paint, key-paint) share around their measurement: their
// flags, one Docent serving a bundle of the two pages (lib/pages.mjs) and one headless
// Chromium, both stopped and their folders removed however the run ends, an error printed
// under the benchmark's name; the kiosk shell with its paint probe and the floor's page opened
// directly; and the intervals their tables give.

import { makeBundle, removeTemp, startDocent } from '../../tests/e2e/lib/docent.mjs';
import { launchBrowser } from '../../tests/e2e/lib/browser.mjs';
import { openShell } from '../../tests/e2e/lib/kiosk.mjs';
import { parseArgs } from './report.mjs';
import { installShellProbe } from './shell-probe.mjs';

/** How long one page switch may take before the run fails. */
export const DEADLINE_MS = 10_000;

const DEFAULTS = { switches: 100, warmup: 10, gap: 150 };

/**
 * Runs the benchmark `name`: `measure({ opts, server, browser })` with its flags (`--switches`,
 * `--warmup`, `--gap`), a Docent serving `files` (a bundle for makeBundle) started with `args`,
 * and a headless Chromium. A failure is printed as `name: ...` and sets the exit code.
 */
export function runPaintBench(name, { files, args }, measure) {
  paintRun(name, files, args, measure).catch((error) => {
    console.error(`${name}: ${error.stack ?? error}`);
    process.exitCode = 1;
  });
}

async function paintRun(name, files, args, measure) {
  const usage = `usage: node bench/${name}.mjs [--switches N (100)] [--warmup N (10)] [--gap MS (150)]`;
  const opts = parseArgs(process.argv.slice(2), DEFAULTS, usage);
  const bundle = makeBundle(files);
  let server;
  let browser;
  try {
    server = await startDocent(bundle, { args });
    browser = await launchBrowser();
    await measure({ opts, server, browser });
  } finally {
    await browser?.close().catch(() => {});
    await server?.stop().catch(() => {});
    removeTemp(bundle);
    if (server) removeTemp(server.corpusDir);
  }
}

/** Opens the kiosk shell in `page`, showing a.html, with the paint probe (lib/shell-probe.mjs). */
export async function openProbedShell(page, server) {
  await openShell(page, server, 'a.html');
  await page.evaluate(installShellProbe);
}

/** Opens the floor's a.html directly (not in the shell) in `page`; resolves once it painted. */
export async function openFloor(page, server) {
  await page.goto(`${server.base}/pages/a.html`);
  await page.evaluate(() => window.__painted);
}

/** Whether a switch's page saw its tap (its `tapAt` is an epoch time). */
export function tapSeen(t) {
  return Number.isFinite(t.tapAt) && t.tapAt !== 0;
}

/** The intervals from time `a` to time `b` (ms) of the samples that have both. */
export function intervals(samples, a, b) {
  return samples.filter((t) => t[a] !== undefined && t[b] !== undefined).map((t) => t[b] - t[a]);
}
