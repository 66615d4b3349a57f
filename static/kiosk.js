// kiosk.js: the touchscreen shell. Shows the page Docent says (welcome, DISPLAY_PAGE commands,
// state frames) in two stacked iframes: the next page loads in the hidden one and is revealed
// once loaded, so a swap never flashes white; the old page is then unloaded, which ends its
// timers. Returns home after the configured idle time without touch (and may trigger the idle
// act), and offers `window.docentShell` to the page script (docent-page.js). With
// `data-camera="webrtc"` it also answers the operator console's camera calls (camera-kiosk.js).
// When a saved bundle goes live (`changed`), it reloads its page if that page, or a file other
// than a page (a stylesheet, script or picture it may use), changed; and reloads itself when
// its own settings changed.
// Speech (speech-state.js's job, wired here): while the robot speaks, the shell's body and the
// shown page's <html> carry `data-docent-speaking` (who asked: kiosk, operator, dm, http), and
// a "Stop" button ends speech visitors started, never anyone else's. A tap on an act already
// speaking is answered with a short notice. Every word the shell shows visitors comes from the
// server's table (`data-strings`, shell-text.js), in the language of the page on show.
// Recording (recorder.js): on the server's `record` frame the shell records the microphone (and
// camera) and uploads the chunks into the session's folder.
// Attract loop (attract.js) and opening hours (schedule.js): after `after_ms` without a touch
// the loop runs until the first touch; the schedule, as the server evaluated it for the kiosk's
// own clock, picks the home page and attract loop, or shows the closed page (and then neither
// idles nor attracts).
// Captions (caption.js): what the robot says, in the page while it is said. While Docent is
// away (outage.js) a calm notice shows and taps answer "one moment"; the hello of a new
// connection says which page is shown, so a restarted server keeps the visitor there. The
// hello's name comes from the shell's address (`/?kiosk=entrance`, client-name.js).

import { createAttract } from "./attract.js";
import { answerCameraCalls } from "./camera-kiosk.js";
import { captions } from "./caption.js";
import { outage } from "./outage.js";
import { answerRecordRequests } from "./recorder.js";
import { kioskLanguage } from "./language.js";
import { clientName } from "./client-name.js";
import { encodePath, keepConnected } from "./socket.js";
import { startBrowserSpeech } from "./speech.js";
import { askSchedule, followSchedule } from "./schedule.js";
import { shellWords } from "./shell-text.js";
import { speechState } from "./speech-state.js";

const TRIGGER_ANSWER_TIMEOUT_MS = 10_000;
const IDLE_CHECK_MS = 1_000;
const LINK_TOUCH_MS = 10_000; // a link's page reported later was not that touch's doing

const config = document.body.dataset;
const pagesPath = config.pages || "/pages/";
const defaultHome = config.home || "index.html";
let home = defaultHome; // the schedule's range may have its own
let closed = false; // outside opening hours: the closed page, no idle return, no attract loop
const parsed = (text) => (text ? JSON.parse(text) : null);
const defaultAttract = parsed(config.attract);
let attractLoop = defaultAttract;
// With opening hours, what they say now is asked for before the connection opens, so the
// server's first state frame already meets the closed page or the range's home.
const firstSchedule = config.schedule ? await askSchedule() : null;
const idleMs = Number(config.idleMs) || 0;
const idleAct = config.idleAct || null;

const frames = [...document.querySelectorAll("iframe.docent-frame")];
let front = 0; // index of the frame on show
let wanted = null; // the page shown or being loaded
let serverPage = null; // the page the server's display state names
let lastActivity = performance.now();
let idle = false;
let shownBy = null; // {page, via}: a page the shell showed by itself (idle, attract, schedule)
let linkTouch = null; // {element, at}: the link a visitor touched, until its page is reported

const listeners = new Map(); // frame or event type -> Set of functions
const pending = new Map(); // trigger ref -> resolve function
let refCount = 0;

function emit(type, value) {
  for (const fn of listeners.get(type) ?? []) {
    try {
      fn(value);
    } catch (error) {
      console.error(`docent: a "${type}" listener failed`, error);
    }
  }
}

function activity() {
  lastActivity = performance.now();
  idle = false;
}

/** Shows `page` (relative to pages/), unless it is already shown or on its way. */
function show(page) {
  if (!page || page === wanted) return;
  wanted = page;
  const old = frames[front];
  const next = frames[1 - front];
  next.onload = () => {
    if (wanted !== page) return; // overtaken by a later page
    if (!reachable(next)) return; // the friendly page takes its place and loads next
    next.onload = null;
    watchActivity(next);
    next.classList.add("shown");
    next.removeAttribute("aria-hidden");
    old.classList.remove("shown");
    old.setAttribute("aria-hidden", "true");
    old.onload = null;
    old.src = "about:blank"; // unloads the old page: its timers and listeners end with it
    front = 1 - front;
    speech.markPage(next);
    outages.watch(next.contentWindow);
    caption.page();
    emit("page", { page });
  };
  next.removeAttribute("srcdoc"); // it would win over src
  next.src = pagesPath + encodePath(language.path(page));
}

/** Loads the page on show again (its file changed), through the same flash-free swap. */
function reloadPage() {
  const page = wanted;
  wanted = null;
  show(page);
}

/** A saved bundle went live: reload what it changed (docs/PROTOCOL.md, `changed`). */
function bundleChanged(frame) {
  if (frame.shell) {
    location.reload();
    return;
  }
  const pages = Array.isArray(frame.pages) ? frame.pages : [];
  const mine = wanted && (pages.includes(wanted) || pages.includes(language.path(wanted)));
  const asset = pages.some((file) => !/\.html?$/i.test(file));
  if (wanted && (mine || asset)) reloadPage();
}

/** Touches inside a page do not reach the shell's document: listen in the frame too. */
function watchActivity(frame) {
  try {
    for (const type of ["pointerdown", "keydown", "wheel"]) {
      frame.contentWindow.addEventListener(type, activity, { capture: true, passive: true });
    }
  } catch (error) {
    console.warn("docent: cannot watch touches in the page", error);
  }
}

function showState(state) {
  const page = state?.display?.page;
  serverPage = page ?? null;
  // Closed, or a schedule's own home where the server still has the bundle's: the schedule
  // wins, and the server is told.
  const scheduled = closed || (page === defaultHome && home !== defaultHome && !attract.running());
  if (scheduled && wanted) {
    if (wanted !== serverPage && socket) socket.send({ type: "page", page: wanted, via: "schedule" });
    serverPage = wanted;
    return;
  }
  if (scheduled) return showBy(closed ? wanted : home, "schedule");
  if (page) show(page);
}

/** Shows `page` by the shell's own doing, reported to the server as `via`. */
function showBy(page, via) {
  if (!page) return;
  if (page !== serverPage) shownBy = { page, via };
  show(page);
}

/**
 * A page reached here without the server (a link, the idle return home) is reported, so the
 * server's display state, its log and a reconnecting kiosk agree with the screen.
 */
function reportShown(frame) {
  let page;
  try {
    const path = decodeURIComponent(frame.contentWindow.location.pathname);
    if (!path.startsWith(pagesPath)) return;
    page = language.page(path.slice(pagesPath.length));
  } catch {
    return;
  }
  if (!frame.classList.contains("shown") && page !== wanted) return;
  if (frame.contentDocument?.querySelector('meta[name="docent-page"][content="missing"]')) return;
  // The frame on show went there itself (a link): that is the page shown now, so the idle
  // return home and a later DISPLAY_PAGE of the page left behind both work.
  if (frame.classList.contains("shown")) wanted = page;
  if (page === serverPage) return;
  serverPage = page;
  const frameOut = { type: "page", page, via: "script" };
  if (linkTouch && performance.now() - linkTouch.at < LINK_TOUCH_MS) {
    frameOut.via = "touch";
    if (linkTouch.element) frameOut.element = linkTouch.element;
  } else if (page === shownBy?.page) {
    frameOut.via = shownBy.via;
  }
  linkTouch = null;
  shownBy = null;
  socket.send(frameOut);
}

/** The documents overlays go into: the shown page's (null if unreachable) and the shell's. */
function overlayDocuments() {
  let page = null;
  try {
    page = frames[front].classList.contains("shown") ? frames[front].contentDocument : null;
  } catch {
    page = null;
  }
  return { page, shell: document };
}
/** The shell's own controls on screen, which overlays must not hide either. */
function shellControls() {
  return [...document.querySelectorAll("#docent-stop-speech, #docent-notice")]
    .filter((element) => !element.hidden)
    .map((element) => element.getBoundingClientRect());
}

const language = kioskLanguage({
  languages: config.languages,
  pageFolders: parsed(config.pageFolders),
  send: (frame) => socket.send(frame),
  say: (key) => speech.say(key),
  onChange: () => reloadPage(), // the page on show, in the new language
});
// Every word the shell shows visitors, in the shown page's language (shell-text.js).
const words = shellWords({ table: parsed(config.strings), languages: config.languages, current: () => language.current() });

const caption = captions({ documents: overlayDocuments, avoid: shellControls });
const outages = outage({ documents: overlayDocuments, avoid: shellControls, words });
outages.start();

/** What a new connection's hello adds: the page on show, unless it is the "not available" copy. */
function helloExtra() {
  // The visitor's language too, so that a restarted server goes on in it.
  const shown = language.chosen() ? { language: language.chosen() } : {};
  if (!wanted || frames[front].hasAttribute("srcdoc")) {
    wanted = null; // the server's page is loaded again
    return shown;
  }
  return { page: wanted, ...shown };
}

const speech = speechState({
  button: document.getElementById("docent-stop-speech"),
  notice: document.getElementById("docent-notice"),
  stop: () => window.docentShell.stopSpeech(),
  words,
});

const socket = keepConnected({
  path: config.ws || "/ws",
  role: "kiosk",
  name: clientName("kiosk"),
  hello: helloExtra,
  onOnline: (online) => {
    outages.online(online);
    if (!online) {
      caption.forget();
      speech.forget(frames[front]);
      for (const [ref, resolve] of pending) {
        resolve({ type: "error", code: "disconnected", message: "the connection to Docent was lost", ref });
      }
      pending.clear();
    }
    if (online) attract.flush();
    emit("connection", { online });
  },
  onFrame: (frame) => {
    language.onFrame(frame); // before the page: it is shown in the language in force
    if (frame.type === "welcome" || frame.type === "state") {
      showState(frame.state);
    } else if (frame.type === "command" && frame.verb === "DISPLAY_PAGE") {
      // A page change by the robot counts as activity: a tour is not an idle kiosk.
      activity();
      attract.stop("robot");
      serverPage = frame.args.page;
      reportPageShown(frame.id, frame.args.page);
      show(frame.args.page);
    } else if (frame.type === "changed") {
      bundleChanged(frame);
    } else if (frame.type === "caption") {
      caption.onFrame(frame);
    } else if (frame.type === "speaking" || frame.type === "outcome" || frame.type === "error") {
      speech.onFrame(frame, frames[front]);
    }
    if ((frame.type === "triggered" || frame.type === "error") && pending.has(frame.ref)) {
      pending.get(frame.ref)(frame);
      pending.delete(frame.ref);
    }
    emit(frame.type, frame);
  },
});

/**
 * The shell's API for the page script.
 * trigger(label, {context, interrupt}) resolves with the `triggered` or `error` frame.
 * on(type, fn) listens to server frames by type (`command`, `triggered`, `state`, ...) and to
 * `page` ({page}) and `connection` ({online}); it returns a function that stops listening.
 */
window.docentShell = {
  trigger(label, { context = null, interrupt = false, via = "script", element } = {}) {
    activity(); // timers and scripts too: a page that moves on by itself is not idle
    const ref = `kiosk-${Date.now().toString(36)}-${++refCount}`;
    const frame = { type: "trigger", label: String(label), ref, via };
    if (context) frame.context = String(context);
    if (interrupt) frame.interrupt = true;
    if (element) frame.element = String(element);
    return new Promise((resolve) => {
      if (!socket.send(frame)) {
        resolve({ type: "error", code: "offline", message: "not connected to Docent", ref });
        return;
      }
      pending.set(ref, resolve);
      setTimeout(() => {
        if (!pending.delete(ref)) return;
        resolve({ type: "error", code: "timeout", message: "Docent did not answer", ref });
      }, TRIGGER_ANSWER_TIMEOUT_MS);
    });
  },
  /** Asks Docent to end the speech visitors started (never the operator's); resolves with
   * whether the request went out (the answer is a `stopped` frame, then `speaking`). */
  stopSpeech() {
    return Promise.resolve(socket.send({ type: "stop", ref: `kiosk-stop-${++refCount}` }));
  },
  /** A `data-language` button: asks Docent for that language (language.js). */
  setLanguage(tag) {
    activity();
    return language.ask(tag);
  },
  /** A page's link was touched: the page it leads to is reported as that touch's. */
  linkTouched(element) {
    linkTouch = { element: element ? String(element) : undefined, at: performance.now() };
  },
  on(type, fn) {
    if (!listeners.has(type)) listeners.set(type, new Set());
    listeners.get(type).add(fn);
    return () => listeners.get(type)?.delete(fn);
  },
};

/**
 * Answers the DISPLAY_PAGE command `id` once `page` is on screen (docs/PROTOCOL.md): `done`
 * when revealed, `failed` when the "not available" page took its place. A page revealed first
 * overtook it, and a lost connection voids the id: the server settled those already.
 */
function reportPageShown(id, page) {
  if (id == null) return;
  const front = () => frames.find((frame) => frame.classList.contains("shown"));
  const report = () => {
    let missing = false;
    try {
      missing = Boolean(front()?.contentDocument?.querySelector('meta[name="docent-page"][content="missing"]'));
    } catch {
      missing = true; // a document of another origin: the browser's own error screen
    }
    socket.send(missing ? { type: "failed", id, reason: `the touchscreen could not show ${page}: it is not available` } : { type: "done", id });
  };
  if (wanted === page && front()?.src.endsWith(pagesPath + encodePath(language.path(page)))) return report();
  const stopPage = window.docentShell.on("page", (shown) => {
    stop();
    if (shown.page === page) report();
  });
  const stopOffline = window.docentShell.on("connection", ({ online }) => online || stop());
  const stop = () => (stopPage(), stopOffline());
}

// Idle: back home after `idleMs` without touch; then the idle act, if one is configured.
// After the attract loop's `after_ms` without touch, the loop (attract.js).
setInterval(() => {
  // Not while Docent is away: the home page and the loop's pages could not be loaded.
  if (closed || !outages.isOnline()) return;
  const quiet = performance.now() - lastActivity;
  if (attractLoop && !attract.running() && quiet >= attractLoop.after_ms) {
    attract.start(attractLoop);
    idle = true; // its act counted as activity
    return;
  }
  if (idleMs <= 0 || idle || quiet < idleMs) return;
  idle = true;
  if (wanted === home || attract.running()) return; // nothing to do, nothing to send
  showBy(home, "idle");
  if (idleAct) triggerOnArrival(home, idleAct);
  idle = true; // the trigger above counted as activity
}, IDLE_CHECK_MS);

/**
 * Triggers `label` once `page` is shown (and reported): its speech belongs to the new page, so
 * the report of arriving there (which ends the old page's speech) must not end it.
 */
function triggerOnArrival(page, label) {
  const stop = window.docentShell.on("page", (shown) => {
    if (shown.page !== page) return;
    stop();
    window.docentShell.trigger(label, { via: "idle" });
  });
}

for (const type of ["pointerdown", "keydown", "wheel"]) {
  addEventListener(type, activity, { capture: true, passive: true });
}

// The attract loop's pages and act are the shell's own doing: not a visitor's, not a session.
const attract = createAttract({
  show: (page) => showBy(page, "attract"),
  trigger: (label) => window.docentShell.trigger(label, { via: "attract" }),
  send: (frame) => socket.send(frame),
  onTouchEnd: () => showBy(home, "attract"),
});

if (config.schedule) followSchedule(firstSchedule, (showing) => {
  if (showing.state === "closed") {
    closed = true;
    attract.stop("schedule");
    showBy(showing.page, "schedule");
    return;
  }
  const before = { closed, home, attractLoop };
  closed = false;
  home = showing.home;
  attractLoop = showing.attract;
  if (attract.running() && JSON.stringify(before.attractLoop) !== JSON.stringify(attractLoop)) {
    attract.stop("schedule");
  }
  // Opening, or a new home while the old one is on show (no visitor busy elsewhere).
  if (before.closed || wanted === before.home || wanted === null) showBy(home, "schedule");
});
for (const type of ["contextmenu", "selectstart", "dragstart", "gesturestart"]) {
  addEventListener(type, (event) => event.preventDefault(), { capture: true });
}

// A page the browser could not load at all (Docent unreachable: no answer, not even a 404)
// shows the shell's own copy of the friendly "not available" page, with its way home, instead
// of the browser's error screen. An error screen is a document of another origin.
function reachable(frame) {
  try {
    return frame.contentDocument !== null;
  } catch {
    return false;
  }
}
function coverFailure(frame) {
  if (reachable(frame) || !config.unavailable) return false;
  frame.srcdoc = config.unavailable;
  return true;
}

for (const frame of frames) frame.addEventListener("load", () => coverFailure(frame) || reportShown(frame));

if (config.speech === "browser") {
  startBrowserSpeech({ path: config.ws || "/ws", voice: config.voice, wpm: Number(config.rate) });
}
if (config.camera === "webrtc") answerCameraCalls({ send: socket.send, on: window.docentShell.on });
answerRecordRequests({ send: socket.send, on: window.docentShell.on });
