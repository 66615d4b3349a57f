#!/usr/bin/env node
// key-paint: an operator's key in the console to the kiosk's new page painted (issue 27).
//
//   cargo build --release && DOCENT_BIN=target/release/docent node bench/key-paint.mjs \
//     [--switches 100] [--warmup 10] [--gap 150]
//
// One Docent (with the test credentials, as the browser tests), one headless Chromium with two
// contexts: the operator console (`/operator` at 1440x900, signed in with the operator
// credential through its form, lib/operator.mjs) and the kiosk shell (`/` at 1280x800). Two
// contexts, not two tabs of one window: a tab behind another gets no animation frames, and
// the console and the kiosk are two screens. The acts SHOW_A and SHOW_B (`Key: A`, `Key: B`)
// show the two pages of lib/pages.mjs. Two keyboard paths the console offers
// (static/operator/keys.js), alternating:
//   alt     Alt+B (the act's `Key`): one key fires the act;
//   search  the label typed into the search (untimed), then Enter fires the chosen act.
// From the key's `keydown` (event.timeStamp in the console) to the new page painted in the
// kiosk (the first requestAnimationFrame after its frame is shown: lib/shell-probe.mjs).
// Both are epoch ms (performance.timeOrigin + each document's own clock); the run checks how
// far the two documents' readings disagree and prints it. The floor, in a third context and
// interleaved: a tap on a plain link between the same two pages opened directly, to the new
// page painted (as in tap-paint.mjs).

import os from 'node:os';

import { newTouchContext, watchExceptions } from '../tests/e2e/lib/browser.mjs';
import { newConsoleContext, signIn } from '../tests/e2e/lib/operator.mjs';
import { floorSwitch, twoPageBundle } from './lib/pages.mjs';
import { DEADLINE_MS, intervals as ms, openFloor, openProbedShell, runPaintBench, tapSeen } from './lib/paint-run.mjs';
import {
  clockAgreement,
  clockLine,
  environment,
  environmentLine,
  pause,
  ratio,
  save,
  summary,
  tableRows,
} from './lib/report.mjs';

// Runs in the console: keeps the time of the last keydown of `key` (epoch ms).
function installKeyProbe() {
  window.__keyAt = {};
  addEventListener('keydown', (e) => {
    window.__keyAt[e.key.toLowerCase()] = performance.timeOrigin + e.timeStamp;
  }, { capture: true });
}

async function keySwitch(console_, kiosk, target, path) {
  const letter = target[0]; // 'a' or 'b'
  if (path === 'search') await console_.keyboard.type(`SHOW_${letter.toUpperCase()}`);
  await kiosk.evaluate((p) => window.__shellProbe.arm(p), target);
  const key = path === 'alt' ? letter : 'enter';
  await console_.keyboard.press(path === 'alt' ? `Alt+Key${letter.toUpperCase()}` : 'Enter');
  const t = await kiosk.evaluate((ms) => window.__shellProbe.result(ms), DEADLINE_MS);
  t.keyAt = await console_.evaluate((k) => window.__keyAt[k], key);
  return t;
}

const ACTS =
  '- Label: SHOW_A\n  Key: A\n  Cmds:\n    - DISPLAY_PAGE a.html\n' +
  '- Label: SHOW_B\n  Key: B\n  Cmds:\n    - DISPLAY_PAGE b.html\n';

// One run: both key paths and the floor, interleaved, and their table.
async function measure({ opts, server, browser }) {
  const kiosk = await (await newTouchContext(browser)).newPage();
  const console_ = await (await newConsoleContext(browser)).newPage();
  const errors = [...watchExceptions(kiosk), ...watchExceptions(console_)];
  await openProbedShell(kiosk, server);
  const floor = await (await newTouchContext(browser)).newPage();
  errors.push(...watchExceptions(floor));
  await openFloor(floor, server);
  await signIn(console_, server, 'bench-console');
  await console_.evaluate(installKeyProbe);
  const clock = await clockAgreement(console_, kiosk);

  const samples = { alt: [], search: [], floor: [] };
  const floorTurn = async (i) => {
    const t = await floorSwitch(floor, i % 2 === 0 ? 'b.html' : 'a.html', DEADLINE_MS);
    if (!tapSeen(t)) throw new Error(`floor: the tap was not seen (${JSON.stringify(t)})`);
    if (i >= opts.warmup) samples.floor.push(t);
    await pause(opts.gap);
  };
  const loadBefore = os.loadavg()[0];
  for (let i = 0; i < opts.warmup + opts.switches; i++) {
    // Each pair goes to b and back to a; which path goes first alternates.
    const order = i % 2 === 0 ? ['alt', 'search'] : ['search', 'alt'];
    if (i % 2 === 1) await floorTurn(i);
    for (const [k, path] of order.entries()) {
      const page = k === 0 ? 'b.html' : 'a.html';
      const t = await keySwitch(console_, kiosk, page, path);
      if (!Number.isFinite(t.keyAt)) throw new Error(`${path}: the console saw no key (${JSON.stringify(t)})`);
      if (i >= opts.warmup) samples[path].push(t);
      await pause(opts.gap);
    }
    if (i % 2 === 0) await floorTurn(i);
  }
  if (errors.length) throw new Error(`a page failed: ${errors.join('; ')}`);
  const env = environment(loadBefore);

  const alt = summary(ms(samples.alt, 'keyAt', 'painted'));
  const search = summary(ms(samples.search, 'keyAt', 'painted'));
  const floorPaint = summary(ms(samples.floor, 'tapAt', 'painted'));
  const rows = [
    ['Alt+key → kiosk page painted (first rAF after shown)', alt],
    ['search + Enter → kiosk page painted', search],
    ['floor: tap on a link → new page painted (first rAF after load)', floorPaint],
    ['  Alt+key → DISPLAY_PAGE at the kiosk', summary(ms(samples.alt, 'keyAt', 'cmd'))],
    ['  Enter (after the search) → DISPLAY_PAGE at the kiosk', summary(ms(samples.search, 'keyAt', 'cmd'))],
    ['  DISPLAY_PAGE → shown (frame load)', summary(ms([...samples.alt, ...samples.search], 'cmd', 'shown'))],
    ['  shown → first rAF', summary(ms([...samples.alt, ...samples.search], 'shown', 'painted'))],
  ];
  const lines = [
    `key-paint: ${opts.switches} switches per key path and as many floor switches (after ${opts.warmup} warm-up), interleaved, ` +
      `${opts.gap} ms apart; console 1440x900 and kiosk 1280x800 in one headless Chromium, epoch ms`,
    environmentLine(env) + `; ${env.chromium}`,
    clockLine("the console's and the kiosk's", clock),
    '',
    ...tableRows(rows),
    '',
    `key / floor at p50: Alt+key ${ratio(alt.p50, floorPaint.p50)}x, search + Enter ${ratio(search.p50, floorPaint.p50)}x; ` +
      `at p90: ${ratio(alt.p90, floorPaint.p90)}x, ${ratio(search.p90, floorPaint.p90)}x`,
  ];
  save('key-paint', lines, {
    bench: 'key-paint',
    switches: opts.switches,
    warmup: opts.warmup,
    gap_ms: opts.gap,
    alt_key_paint_ms: alt,
    search_enter_paint_ms: search,
    floor_paint_ms: floorPaint,
    ratio_alt_p50: ratio(alt.p50, floorPaint.p50),
    ratio_search_p50: ratio(search.p50, floorPaint.p50),
    alt_key_to_command_ms: rows[3][1],
    enter_to_command_ms: rows[4][1],
    clock,
    ...env,
  });
}

runPaintBench('key-paint', { files: { ...twoPageBundle(), 'acts.yaml': ACTS }, args: ['--no-watch'] }, measure);
