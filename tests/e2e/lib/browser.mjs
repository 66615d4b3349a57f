// Headless Debian Chromium through playwright-core: one browser per test file, touch contexts of
// the kiosk's size, and a record of what went wrong in a page (console errors, uncaught
// exceptions, failed requests and HTTP errors).
//
// Playwright never downloads a browser here: it drives /usr/bin/chromium (or $CHROMIUM_BIN),
// installed from Debian by scripts/install-test-deps.sh. Flags as measured in the project notes;
// `--disable-features` may be given only once (a second one replaces Playwright's own list), so
// none is passed here.

import { chromium } from 'playwright-core';

/** The kiosk touchscreen's size. */
export const VIEWPORT = { width: 1280, height: 800 };

const ARGS = [
  '--no-sandbox',
  '--disable-gpu',
  '--disable-background-networking',
  '--disable-component-update',
  '--no-first-run',
  '--disable-sync',
  '--autoplay-policy=no-user-gesture-required',
];

/** Launches one headless Chromium, with `extraArgs` if any. Close it with `browser.close()`. */
export function launchBrowser(extraArgs = []) {
  return chromium.launch({
    executablePath: process.env.CHROMIUM_BIN ?? '/usr/bin/chromium',
    headless: true,
    args: [...ARGS, ...extraArgs],
  });
}

/** A new touch context of the kiosk's size. */
export function newTouchContext(browser) {
  return browser.newContext({ viewport: VIEWPORT, hasTouch: true });
}

/**
 * Records the problems of `page` and its frames: console errors, uncaught exceptions, failed
 * requests and HTTP answers of 400 or more (Docent answers the browser's own favicon request). The
 * returned array lists them as sentences.
 */
export function watchProblems(page) {
  const problems = [];
  page.on('console', (msg) => {
    if (msg.type() === 'error') {
      problems.push(`console error: ${msg.text()} (${msg.location().url})`);
    }
  });
  page.on('pageerror', (err) => problems.push(`uncaught exception: ${err.message}`));
  page.on('requestfailed', (req) => problems.push(`request failed: ${req.url()} (${req.failure()?.errorText})`));
  page.on('response', (res) => {
    if (res.status() >= 400) problems.push(`HTTP ${res.status()}: ${res.url()}`);
  });
  return problems;
}

/** Uncaught exceptions only (a kiosk losing its server logs console errors on purpose). */
export function watchExceptions(page) {
  const errors = [];
  page.on('pageerror', (err) => errors.push(`uncaught exception: ${err.message}`));
  return errors;
}
