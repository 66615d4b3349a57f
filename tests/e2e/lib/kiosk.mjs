// Reading the kiosk shell (`GET /`) from the outside, as a visitor sees it: which content page
// its frame shows. The shell may keep more than one <iframe> (to swap pages without a flash of
// white), so "shown" means the visible frame on top at the middle of the screen, whose document
// has finished loading.

import { DEADLINE_MS } from './docent.mjs';

// Runs in the shell's document: the <iframe> a visitor sees, or null. Self-contained, because
// Playwright sends its source text to the page.
function shownFrame() {
  const visible = [...document.querySelectorAll('iframe')].filter((f) => {
    const style = getComputedStyle(f);
    const box = f.getBoundingClientRect();
    return style.display !== 'none' && style.visibility !== 'hidden' && Number(style.opacity) > 0.5 &&
      box.width > 0 && box.height > 0;
  });
  const middle = document.elementFromPoint(innerWidth / 2, innerHeight / 2);
  if (visible.includes(middle)) return middle;
  return visible.at(-1) ?? null;
}

// Runs in the shell's document: the path of the shown page (`/pages/index.html`) once loaded,
// or with `wanted`, whether that is the path shown.
function shownPath(wanted) {
  // Repeated from shownFrame: each function must stand alone in the page.
  const visible = [...document.querySelectorAll('iframe')].filter((f) => {
    const style = getComputedStyle(f);
    const box = f.getBoundingClientRect();
    return style.display !== 'none' && style.visibility !== 'hidden' && Number(style.opacity) > 0.5 &&
      box.width > 0 && box.height > 0;
  });
  const middle = document.elementFromPoint(innerWidth / 2, innerHeight / 2);
  const frame = visible.includes(middle) ? middle : visible.at(-1);
  try {
    const doc = frame?.contentDocument;
    const path = doc && doc.readyState === 'complete' ? decodeURI(frame.contentWindow.location.pathname) : null;
    return wanted === undefined ? path : path === wanted;
  } catch {
    return wanted === undefined ? null : false;
  }
}

/** The path of the content page the shell shows now (`/pages/map.html`), or null. */
export function shownPage(page) {
  return page.evaluate(shownPath);
}

/**
 * Waits until the shell shows `/pages/<name>`, loaded; returns its Playwright Frame. The
 * deadline's error says what was shown instead.
 */
export async function waitForShownPage(page, name, { timeout = DEADLINE_MS } = {}) {
  const want = `/pages/${name}`;
  try {
    await page.waitForFunction(shownPath, want, { timeout, polling: 'raf' });
  } catch (e) {
    const now = await shownPage(page).catch(() => '(unknown)');
    throw new Error(`the kiosk shell did not show ${want} within ${timeout} ms (it shows ${now}): ${e.message}`);
  }
  return shownContentFrame(page);
}

/** The Playwright Frame of the shown content page. */
export async function shownContentFrame(page) {
  const handle = await page.evaluateHandle(shownFrame);
  const element = handle.asElement();
  if (!element) throw new Error('the kiosk shell shows no frame');
  const frame = await element.contentFrame();
  if (!frame) throw new Error('the shown frame has no document');
  return frame;
}

/** Opens the kiosk shell of `server` in `page` and waits until it shows `/pages/<home>`. */
export async function openShell(page, server, home) {
  const res = await page.goto(`${server.base}/`);
  if (res.status() !== 200) throw new Error(`no kiosk shell at ${server.base}/: HTTP ${res.status()}`);
  return waitForShownPage(page, home);
}
