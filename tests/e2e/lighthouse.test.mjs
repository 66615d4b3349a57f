// Lighthouse (the npm package, pinned) on the kiosk shell (`GET /`) of each shipped bundle, as
// the kiosk shows it: a 1280x800 desktop-class screen, Debian's Chromium headless
// (CHROME_PATH or /usr/bin/chromium, launched by chrome-launcher; nothing is downloaded).
// Lighthouse counts only what the shell paints itself, never a page inside its frames, so the
// shell paints its own "Starting…" until a page covers it: first and largest contentful paint
// must both be measured, and every accessibility audit must pass but one: the touchscreen
// forbids zooming on purpose (Lighthouse's meta-viewport; the score is 0.84 for it). The performance,
// accessibility and best-practices figures are printed (TAP diagnostics) and each report is kept
// in target/e2e/lighthouse/<bundle>.json (not committed).

import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';

import * as chromeLauncher from 'chrome-launcher';
import lighthouse from 'lighthouse';
import desktopConfig from 'lighthouse/core/config/desktop-config.js';

import { REPO, startDocent } from './lib/docent.mjs';

const OUT = path.join(REPO, 'target/e2e/lighthouse');
const KIOSK = { mobile: false, width: 1280, height: 800, deviceScaleFactor: 1, disabled: false };
const FLAGS = ['--headless=new', '--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update', '--no-first-run', '--disable-sync'];

const bundles = fs
  .readdirSync(path.join(REPO, 'dialogs'), { withFileTypes: true })
  .filter((d) => d.isDirectory() && fs.existsSync(path.join(REPO, 'dialogs', d.name, 'docent.yaml')))
  .map((d) => d.name)
  .sort();

for (const name of bundles) {
  test(`Lighthouse measures the kiosk shell of ${name}: contentful paints, accessibility audits pass but the deliberate no-zoom`, { timeout: 180_000 }, async (t) => {
    const server = await startDocent(path.join(REPO, 'dialogs', name));
    const chrome = await chromeLauncher.launch({
      chromePath: process.env.CHROME_PATH ?? process.env.CHROMIUM_BIN ?? '/usr/bin/chromium',
      chromeFlags: FLAGS,
      logLevel: 'error',
    });
    try {
      const config = { ...desktopConfig, settings: { ...desktopConfig.settings, screenEmulation: KIOSK } };
      const result = await lighthouse(
        `${server.base}/`,
        { port: chrome.port, output: 'json', logLevel: 'error', onlyCategories: ['performance', 'accessibility', 'best-practices'] },
        config,
      );
      const { lhr } = result;
      fs.mkdirSync(OUT, { recursive: true });
      fs.writeFileSync(path.join(OUT, `${name}.json`), result.report);

      assert.equal(lhr.runtimeError, undefined, `Lighthouse failed: ${JSON.stringify(lhr.runtimeError)}`);
      const score = (id) => lhr.categories[id].score;
      const ms = (id) => lhr.audits[id].numericValue;
      const figures = {
        performance: score('performance'),
        accessibility: score('accessibility'),
        'best-practices': score('best-practices'),
        'first-contentful-paint ms': Math.round(ms('first-contentful-paint')),
        'largest-contentful-paint ms': Math.round(ms('largest-contentful-paint')),
      };
      t.diagnostic(`${name}: ${JSON.stringify(figures)}`);
      for (const id of ['first-contentful-paint', 'largest-contentful-paint']) {
        const audit = lhr.audits[id];
        assert.ok(Number.isFinite(audit.numericValue) && audit.numericValue > 0, `${id} not measured: ${audit.errorMessage ?? audit.explanation ?? 'no value'}`);
      }
      const failing = lhr.categories.accessibility.auditRefs
        .map((ref) => lhr.audits[ref.id])
        .filter((a) => a.score !== null && a.score < 1)
        .map((a) => `${a.id}: ${a.title}`);
      // The one audit the touchscreen fails on purpose: its shell forbids zooming, since a
      // pinch on a public kiosk strands the next visitor in a zoomed page (accessibility.test.mjs
      // holds both the shell to that and Docent's desktop pages to zooming).
      assert.deepEqual(failing, [`meta-viewport: ${lhr.audits['meta-viewport'].title}`], 'accessibility audits that failed');
    } finally {
      await chrome.kill();
      await server.stop();
    }
  });
}
