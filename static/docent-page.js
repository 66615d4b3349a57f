// docent-page.js: added by the server to every HTML page under /pages/, as the first thing in
// its <head> and as a classic (not module) script, so `window.docent` exists before any script
// of the page runs: an inline script may call `docent.trigger("X")` or `docent.on(...)` at once.
// Makes elements with `data-act="LABEL"` trigger their act when tapped (with press feedback),
// fires the acts of `data-act-after="20s"` elements after their delay while the page is shown,
// and hardens the page for public touch use (no context menu, selection, drag, zoom or
// navigation out of the bundle). It talks to Docent through the kiosk shell
// (`parent.docentShell`, static/kiosk.js); calls made before the shell is reachable wait for
// it until the page has loaded, and opened on its own the page only warns.
// The API: docent.trigger(label, {context, interrupt}) -> Promise of the `triggered` or
// `error` frame (the shell tells Docent whether a visitor's touch, a timer or a script asked); docent.on(type, fn) -> stop function; docent.ready(fn): fn runs once the
// page's document is parsed (its elements exist), at once if it already is;
// docent.stopSpeech() ends the speech visitors started (never the operator's), and so does a
// tap on an element with `data-docent-stop` (a page's own stop control). While the robot
// speaks, the shell sets `data-docent-speaking` on this page's <html> (style it as you like);
// a tapped element whose act is already speaking gets `docent-already-speaking` briefly.
// An element with `data-language="de"` switches the visitor's language when tapped (with press
// feedback; Docent then shows the page in that language); a refused switch (the language is
// not one of the bundle's, or this page offers no button for it) is told on screen by the
// shell, logged here, and marks the element `docent-refused` briefly.

(() => {
"use strict";
if (window.docent) return; // a page that also includes this script itself

const PRESS_MS = 150;
const REPEAT_GUARD_MS = 400;
const ALREADY_SPEAKING_MS = 1_500;
const REFUSED_MS = 1_500;
const PAGES_PREFIX = "/pages/";

/** The kiosk shell's API, or undefined (not framed yet, or opened on its own). */
function findShell() {
  try {
    return window.parent !== window ? window.parent.docentShell : undefined;
  } catch {
    return undefined; // a parent from elsewhere
  }
}

const cleanups = [];
addEventListener("pagehide", () => cleanups.splice(0).forEach((stop) => stop()));

// Calls made while no shell is reachable: run as soon as one is, or answered "no shell" once
// the page has loaded without one. Never dropped without a word.
const waiting = [];
let settled = false; // the page has loaded: a missing shell will not come any more

function withShell(use, without) {
  const shell = findShell();
  if (shell) return use(shell);
  if (settled || window.parent === window) return without();
  return new Promise((resolve) => waiting.push({ use, without, resolve }));
}

function flush() {
  const shell = findShell();
  if (!shell && !settled) return;
  for (const call of waiting.splice(0)) call.resolve(shell ? call.use(shell) : call.without());
}

function noShell(what) {
  console.warn(`docent: not inside the kiosk shell; ${what}`);
}

const readyCallbacks = [];
let parsed = document.readyState !== "loading";
function runReady() {
  parsed = true;
  flush();
  for (const fn of readyCallbacks.splice(0)) {
    try {
      fn(window.docent);
    } catch (error) {
      console.error("docent: a docent.ready function failed", error);
    }
  }
}

/**
 * An element as the corpus names a touch on it: tag, id, act or link, and its words, e.g.
 * `button#start[data-act=GREETING] "Start the tour"`. The server keeps at most 160 characters.
 */
function describe(element) {
  if (!element?.tagName) return undefined;
  let said = element.tagName.toLowerCase();
  if (element.id) said += `#${element.id}`;
  if (element.dataset?.act) said += `[data-act=${element.dataset.act}]`;
  else if (element.getAttribute("href")) said += `[href=${element.getAttribute("href")}]`;
  const words = (element.getAttribute("aria-label") || element.textContent || element.getAttribute("alt") || "")
    .replace(/\s+/g, " ").trim();
  return words ? `${said} "${words.slice(0, 80)}"` : said;
}

// The element the visitor last pressed: a page's own script that triggers from its click
// handler is a touch on it (docs/PROTOCOL.md, `via`).
let lastPressed = null;
addEventListener("pointerdown", (event) => { lastPressed = event.target; }, { capture: true, passive: true });

/** Asks the shell for `label`; `via` says why (touch, timer, script) for the corpus. */
function ask(label, { context = null, interrupt = false, via = "script", element } = {}) {
  return Promise.resolve(withShell(
    (shell) => shell.trigger(label, { context, interrupt, via, element }),
    () => {
      noShell(`act ${label} not triggered`);
      return { type: "error", code: "no-shell", message: "not in the kiosk shell" };
    },
  ));
}

window.docent = Object.freeze({
  /** Triggers an act; resolves with Docent's `triggered` or `error` frame. Called from a
   * visitor's tap or key press (the browser's user activation), it counts as their touch. */
  trigger(label, { context = null, interrupt = false } = {}) {
    const touched = navigator.userActivation?.isActive === true;
    const target = lastPressed?.closest?.("[data-act], a, button, [role=button]") ?? lastPressed;
    return ask(label, { context, interrupt, via: touched ? "touch" : "script", element: touched ? describe(target) : undefined });
  },
  /** Calls `fn` for each frame or shell event of this type while the page is shown. */
  on(event, fn) {
    let stop = null;
    let stopped = false;
    const listen = (shell) => {
      if (stopped) return;
      stop = shell.on(event, fn);
      cleanups.push(stop);
    };
    const result = withShell(listen, () => noShell(`"${event}" will never happen`));
    if (result instanceof Promise) result.catch(() => {});
    return () => {
      stopped = true;
      stop?.();
    };
  },
  /** Ends the speech visitors started; resolves with whether the request went out. */
  stopSpeech() {
    return Promise.resolve(withShell(
      (shell) => shell.stopSpeech(),
      () => {
        noShell("speech not stopped");
        return false;
      },
    ));
  },
  /** Runs `fn(docent)` once the page's elements exist (at once, later, if they already do). */
  ready(fn) {
    if (typeof fn !== "function") throw new TypeError("docent.ready needs a function");
    if (parsed) queueMicrotask(() => fn(window.docent));
    else readyCallbacks.push(fn);
  },
});

if (parsed) queueMicrotask(runReady);
else document.addEventListener("DOMContentLoaded", runReady, { once: true });
addEventListener("load", () => {
  settled = true;
  flush();
}, { once: true });

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
  const target = event.target.closest?.("[data-act], [data-language]");
  if (target) release = press(target);
});
for (const type of ["pointerup", "pointercancel"]) {
  document.addEventListener(type, () => {
    release?.();
    release = null;
  });
}

// A page's own "stop speaking" control: `data-docent-stop` (the shell then hides its own
// button while this page is shown; style it with html[data-docent-speaking="kiosk"]).
document.addEventListener("click", (event) => {
  if (!event.target.closest?.("[data-docent-stop]")) return;
  event.preventDefault();
  window.docent.stopSpeech();
}, { capture: true });

document.addEventListener("click", (event) => {
  const target = event.target.closest?.("[data-act]");
  if (!target) return;
  event.preventDefault(); // a data-act link does not navigate
  if (target.matches(":disabled, [aria-disabled='true']")) return;
  const now = performance.now();
  if (now - (lastFired.get(target) ?? -Infinity) < REPEAT_GUARD_MS) return;
  lastFired.set(target, now);
  if (!target.classList.contains("docent-pressed")) press(target)();
  ask(target.dataset.act, { via: "touch", element: describe(target) }).then((answer) => {
    if (answer?.code !== "already-speaking") return;
    target.classList.add("docent-already-speaking");
    setTimeout(() => target.classList.remove("docent-already-speaking"), ALREADY_SPEAKING_MS);
  });
}, { capture: true });

// Language buttons: the shell asks Docent for the language; a refusal is never silent.
document.addEventListener("click", (event) => {
  const target = event.target.closest?.("[data-language]:not([data-act])");
  if (!target) return;
  event.preventDefault();
  if (target.matches(":disabled, [aria-disabled='true']")) return;
  const now = performance.now();
  if (now - (lastFired.get(target) ?? -Infinity) < REPEAT_GUARD_MS) return;
  lastFired.set(target, now);
  if (!target.classList.contains("docent-pressed")) press(target)();
  const language = target.dataset.language;
  Promise.resolve(withShell(
    (shell) => shell.setLanguage(language),
    () => {
      noShell(`language ${language} not chosen`);
      return { type: "error", code: "no-shell", message: "not in the kiosk shell" };
    },
  )).then((answer) => {
    if (answer?.type !== "error") return;
    console.warn(`docent: language ${language} refused: ${answer.message ?? answer.code}`);
    target.classList.add("docent-refused");
    setTimeout(() => target.classList.remove("docent-refused"), REFUSED_MS);
  });
}, { capture: true });

// A link the visitor follows: the shell names it when it reports the page it leads to.
document.addEventListener("click", (event) => {
  const link = event.target.closest?.("a[href]:not([data-act])");
  if (!link || event.defaultPrevented) return;
  const shell = findShell();
  shell?.linkTouched?.(describe(link));
});

// Timers: each data-act-after element fires its act once, after its delay. Leaving the page
// unloads it, and its timers with it. The elements exist once the document is parsed.
window.docent.ready(() => {
  for (const element of document.querySelectorAll("[data-act-after]")) {
    // The server read the delay once (docent check uses the same rule) and added it in ms.
    const delay = Number.parseInt(element.dataset.actAfterMs ?? "", 10);
    if (!Number.isFinite(delay) || !element.dataset.act) {
      console.warn("docent: data-act-after needs data-act and a delay like 500ms, 20s or 1m", element);
      continue;
    }
    setTimeout(() => ask(element.dataset.act, { via: "timer", element: describe(element) }), delay);
  }
});

// Hardening for public use.
const style = document.createElement("style");
style.textContent = `
html { touch-action: manipulation; -webkit-user-select: none; user-select: none;
  -webkit-touch-callout: none; -webkit-tap-highlight-color: transparent; }
input, textarea, [contenteditable] { -webkit-user-select: text; user-select: text; }
img, a { -webkit-user-drag: none; }
[data-act], [data-language] { cursor: pointer; transition: transform 80ms ease-out, filter 80ms ease-out; }
.docent-pressed { transform: scale(0.97); filter: brightness(0.85); }
`;
// First, so the page's own styles win. This script runs inside <head> while it is parsed.
(document.head ?? document.documentElement).prepend(style);

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
})();
