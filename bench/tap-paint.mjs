#!/usr/bin/env node
// tap-paint: a visitor's tap to the new page painted, in the kiosk shell against its floor, a
// plain link between the same two pages in the same browser (issue 27).
//
//   cargo build --release && DOCENT_BIN=target/release/docent node bench/tap-paint.mjs \
//     [--switches 100] [--warmup 10] [--gap 150]
//
// One Docent (`--open`), one headless Chromium, one touch context at 1280x800 with two tabs:
//  - kiosk: the shell `/` showing a.html; a real tap (page.touchscreen.tap: CDP touch events,
//    so pointerdown, pointerup and click as on a touchscreen) on the page's `data-act` button,
//    whose act does DISPLAY_PAGE of the other page, until the new page is painted in the shell
//    (the first requestAnimationFrame after its frame is shown: lib/shell-probe.mjs);
//  - floor: the same page opened directly (`/pages/a.html`, same server, same bytes); a tap on
//    its `<a href>` to the other page, until that page is painted (its `load`, then the first
//    requestAnimationFrame: the same point as the shell's, which shows a frame at its `load`).
//    Its first contentful paint (the 'paint' PerformanceObserver entry) is given too.
// Both start at the tap's `pointerdown` (event.timeStamp in the tapped page). Times are epoch
// ms (performance.timeOrigin + the document's own clock), the only clock two documents share;
// the run checks how far two documents' readings of it disagree and prints the figure.
// Switches alternate kiosk and floor (which goes first alternates too), `--gap` ms apart.

import os from 'node:os';

import { newTouchContext, VIEWPORT, watchExceptions } from '../tests/e2e/lib/browser.mjs';
import { BUTTON, floorSwitch, middle, twoPageBundle } from './lib/pages.mjs';
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

// Each tab is brought to the front before its switch: Chromium throttles a background tab's
// timers and animation frames (a kiosk's tab is always in front), and the two tabs share one
// window.
async function kioskSwitch(shell, target) {
  await shell.bringToFront();
  await shell.evaluate((p) => window.__shellProbe.arm(p), target);
  const at = middle(BUTTON);
  await shell.touchscreen.tap(at.x, at.y);
  return shell.evaluate((ms) => window.__shellProbe.result(ms), DEADLINE_MS);
}

// One run: the kiosk and the floor, interleaved, and their table.
async function measure({ opts, server, browser }) {
  const context = await newTouchContext(browser);
  const shell = await context.newPage();
  const floor = await context.newPage();
  const errors = [...watchExceptions(shell), ...watchExceptions(floor)];
  await openProbedShell(shell, server);
  await openFloor(floor, server);
  const clock = await clockAgreement(shell, floor);

  const kiosk = [];
  const plain = [];
  const loadBefore = os.loadavg()[0];
  for (let i = 0; i < opts.warmup + opts.switches; i++) {
    const target = i % 2 === 0 ? 'b.html' : 'a.html';
    const order = i % 4 < 2 ? ['kiosk', 'floor'] : ['floor', 'kiosk'];
    for (const which of order) {
      const t = which === 'kiosk' ? await kioskSwitch(shell, target) : await floorSwitch(floor, target, DEADLINE_MS);
      if (!tapSeen(t)) {
        throw new Error(`${which}: the tap was not seen by the page (${JSON.stringify(t)})`);
      }
      if (i >= opts.warmup) (which === 'kiosk' ? kiosk : plain).push(t);
      await pause(opts.gap);
    }
  }
  if (errors.length) throw new Error(`a page failed: ${errors.join('; ')}`);
  const env = environment(loadBefore);

  const kioskPaint = summary(ms(kiosk, 'tapAt', 'painted'));
  const floorPaint = summary(ms(plain, 'tapAt', 'painted'));
  const rows = [
    ['kiosk: tap → new page painted (first rAF after shown)', kioskPaint],
    ['floor: tap on a link → new page painted (first rAF after load)', floorPaint],
    ['floor: tap on a link → first contentful paint', summary(ms(plain, 'tapAt', 'fcp'))],
    ['  kiosk: tap → click (pointerdown to click, timeStamps)', summary(ms(kiosk, 'tapAt', 'clickAt'))],
    ['  kiosk: click timeStamp → its listeners run', summary(ms(kiosk, 'clickAt', 'clickRun'))],
    ['  kiosk: click listeners → DISPLAY_PAGE at the shell', summary(ms(kiosk, 'clickRun', 'cmd'))],
    ['  kiosk: DISPLAY_PAGE → shown (frame load)', summary(ms(kiosk, 'cmd', 'shown'))],
    ['  kiosk: shown → first rAF', summary(ms(kiosk, 'shown', 'painted'))],
    ['  kiosk: tap → after paint (rAF + message)', summary(ms(kiosk, 'tapAt', 'post'))],
    ['  floor: tap → navigation start of the new page', summary(ms(plain, 'tapAt', 'navStart'))],
  ];
  const lines = [
    `tap-paint: ${opts.switches} switches each (after ${opts.warmup} warm-up), kiosk and floor interleaved, ` +
      `${opts.gap} ms apart, headless Chromium ${VIEWPORT.width}x${VIEWPORT.height} with touch, epoch ms`,
    environmentLine(env) + `; ${env.chromium}`,
    clockLine("the shell's and the floor tab's", clock),
    '',
    ...tableRows(rows),
    '',
    `kiosk / floor at p50: ${ratio(kioskPaint.p50, floorPaint.p50)}x, at p90: ${ratio(kioskPaint.p90, floorPaint.p90)}x`,
  ];
  save('tap-paint', lines, {
    bench: 'tap-paint',
    switches: opts.switches,
    warmup: opts.warmup,
    gap_ms: opts.gap,
    kiosk_paint_ms: kioskPaint,
    floor_paint_ms: floorPaint,
    floor_fcp_ms: rows[2][1],
    ratio_p50: ratio(kioskPaint.p50, floorPaint.p50),
    ratio_p90: ratio(kioskPaint.p90, floorPaint.p90),
    clock,
    ...env,
  });
}

runPaintBench('tap-paint', { files: twoPageBundle(), args: ['--open', '--no-watch'] }, measure);
