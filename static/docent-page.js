// docent-page.js: added by the server to every HTML page under /pages/. Makes elements with
// `data-act="LABEL"` trigger their act when tapped (with press feedback), fires the acts of
// `data-act-after="20s"` elements after their delay while the page is shown, defines the
// `window.docent` API for page scripts, and hardens the page for public touch use (no context
// menu, selection, drag, zoom or navigation out of the bundle). It talks to Docent through the
// kiosk shell (`parent.docentShell`, static/kiosk.js); opened on its own it only warns.

const PRESS_MS = 150;
const REPEAT_GUARD_MS = 400;
const PAGES_PREFIX = "/pages/";

const shell = (() => {
  try {
    return window.parent !== window ? window.parent.docentShell : undefined;
  } catch {
    return undefined; // a parent from elsewhere
  }
})();

/** Parses `500ms`, `20s`, `1.5s` or `1m` into milliseconds; `null` when it is none of these. */
function parseDelay(text) {
  const match = /^\s*(\d+(?:\.\d+)?)\s*(ms|s|m)\s*$/.exec(text ?? "");
  if (!match) return null;
  return Number(match[1]) * { ms: 1, s: 1000, m: 60_000 }[match[2]];
}

const cleanups = [];
addEventListener("pagehide", () => cleanups.splice(0).forEach((stop) => stop()));

window.docent = Object.freeze({
  /** Triggers an act; resolves with Docent's `triggered` or `error` frame. */
  trigger(label, { context = null, interrupt = false } = {}) {
    if (!shell) {
      console.warn(`docent: not inside the kiosk shell; act ${label} not triggered`);
      return Promise.resolve({ type: "error", code: "no-shell", message: "not in the kiosk shell" });
    }
    return shell.trigger(label, { context, interrupt });
  },
  /** Calls `fn` for each frame or shell event of this type while the page is shown. */
  on(event, fn) {
    if (!shell) {
      console.warn(`docent: not inside the kiosk shell; "${event}" will never happen`);
      return () => {};
    }
    const stop = shell.on(event, fn);
    cleanups.push(stop);
    return stop;
  },
});

// Taps on data-act elements: feedback while pressed (at least PRESS_MS), one trigger per tap.
const lastFired = new WeakMap();

function press(element) {
  element.classList.add("docent-pressed");
  const since = performance.now();
  return () => {
    const left = Math.max(0, PRESS_MS - (performance.now() - since));
    setTimeout(() => element.classList.remove("docent-pressed"), left);
  };
}

let release = null;
document.addEventListener("pointerdown", (event) => {
  const target = event.target.closest?.("[data-act]");
  if (target) release = press(target);
});
for (const type of ["pointerup", "pointercancel"]) {
  document.addEventListener(type, () => {
    release?.();
    release = null;
  });
}

document.addEventListener("click", (event) => {
  const target = event.target.closest?.("[data-act]");
  if (!target) return;
  event.preventDefault(); // a data-act link does not navigate
  if (target.matches(":disabled, [aria-disabled='true']")) return;
  const now = performance.now();
  if (now - (lastFired.get(target) ?? -Infinity) < REPEAT_GUARD_MS) return;
  lastFired.set(target, now);
  if (!target.classList.contains("docent-pressed")) press(target)();
  window.docent.trigger(target.dataset.act);
}, { capture: true });

// Timers: each data-act-after element fires its act once, after its delay. Leaving the page
// unloads it, and its timers with it.
for (const element of document.querySelectorAll("[data-act-after]")) {
  const delay = parseDelay(element.dataset.actAfter);
  if (delay === null || !element.dataset.act) {
    console.warn("docent: data-act-after needs data-act and a delay like 500ms, 20s or 1m", element);
    continue;
  }
  setTimeout(() => window.docent.trigger(element.dataset.act), delay);
}

// Hardening for public use.
const style = document.createElement("style");
style.textContent = `
html { touch-action: manipulation; -webkit-user-select: none; user-select: none;
  -webkit-touch-callout: none; -webkit-tap-highlight-color: transparent; }
input, textarea, [contenteditable] { -webkit-user-select: text; user-select: text; }
img, a { -webkit-user-drag: none; }
[data-act] { cursor: pointer; transition: transform 80ms ease-out, filter 80ms ease-out; }
.docent-pressed { transform: scale(0.97); filter: brightness(0.85); }
`;
document.head.prepend(style); // first, so the page's own styles win

const editable = (target) => target.closest?.("input, textarea, [contenteditable]");
const block = (event) => event.preventDefault();
document.addEventListener("contextmenu", block, { capture: true });
document.addEventListener("dragstart", block, { capture: true });
document.addEventListener("gesturestart", block, { capture: true });
document.addEventListener("selectstart", (event) => editable(event.target) || block(event), {
  capture: true,
});
document.addEventListener("touchmove", (event) => event.touches.length > 1 && block(event), {
  capture: true,
  passive: false,
});
document.addEventListener("wheel", (event) => event.ctrlKey && block(event), {
  capture: true,
  passive: false,
});
document.addEventListener("keydown", (event) => {
  if ((event.ctrlKey || event.metaKey) && ["+", "-", "=", "0"].includes(event.key)) block(event);
}, { capture: true });

// No way out of the bundle: links and forms may only lead to other pages under /pages/.
const insideBundle = (url) => url.origin === location.origin && url.pathname.startsWith(PAGES_PREFIX);
document.addEventListener("click", (event) => {
  const link = event.target.closest?.("a[href]");
  if (!link) return;
  const leaves = !insideBundle(new URL(link.href, location.href));
  if (leaves || (link.target && link.target !== "_self")) block(event);
});
document.addEventListener("submit", (event) => {
  if (!insideBundle(new URL(event.target.action, location.href))) block(event);
}, { capture: true });
window.open = () => null;
