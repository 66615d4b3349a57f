// preview.js: the author's preview (GET /preview, opened by `docent serve --preview`). Fits the
// two screens (the kiosk shell and the projector, each at its real pixel size in a frame) side
// by side right of the act list, scaling them down as needed to leave room for the caption. The act
// list is the operator console's (actlist.js: grouped like the console, searchable by label and
// text; a click or Enter fires), and so is signing in (access.js): the preview fires acts as an
// operator, with the operator credential, or none on an `--open` server. Below the screens it
// shows the words being spoken now (a SAY from its `command.started` to its end, from the
// events every operator gets), marked with its language (`args.language`, so that a screen
// reader reads a German text as German; the kiosk frame's browser speech speaks it in that
// language, speech.js), and it says so when this browser has no voice (speech.js).
// The author sees every refusal and every change here: a save with errors shows at once above
// the act list (the operator console's banner, reloadbanner.js: each problem at its file, line
// and column with its hint, and that the last good bundle still runs), and goes when a good
// save is live; the act list follows every good save (`bundle.reloaded`) without a reload.

import { accessElements, createAccess } from "./operator/access.js";
import { createActList } from "./operator/actlist.js";
import { readActs } from "./operator/acts.js";
import { byId, createNotice, h } from "./operator/dom.js";
import { createReloadBanner } from "./operator/reloadbanner.js";
import { detectVoice } from "./speech.js";

const NOTICE_MS = 6_000;
const notice = createNotice(byId("notice"), NOTICE_MS);
const ENDED = new Set(["command.done", "command.failed", "command.cancelled"]);

const config = document.body.dataset;
let refCount = 0;

// --- screens ------------------------------------------------------------------------------

function fit() {
  const area = byId("screens");
  const stage = area.parentElement;
  const screens = [...area.querySelectorAll(".screen")];
  const gap = 16;
  const width = (area.clientWidth - gap * (screens.length - 1)) / screens.length;
  // The screens' headings and the caption below them keep their room.
  const height = stage.clientHeight - byId("speaking").parentElement.offsetHeight - gap - 32;
  for (const screen of screens) {
    const w = Number(screen.dataset.width);
    const h = Number(screen.dataset.height);
    const scale = Math.max(0.05, Math.min(1, width / w, height / h));
    screen.querySelector("iframe").style.transform = `scale(${scale})`;
    const viewport = screen.querySelector(".viewport");
    viewport.style.width = `${w * scale}px`;
    viewport.style.height = `${h * scale}px`;
  }
}

new ResizeObserver(fit).observe(byId("screens").parentElement);
fit();

// --- what is being said -------------------------------------------------------------------

const said = new Map(); // SAY command id -> {text, language}, from command.sent
let speakingId = null;

function showSpeaking(saying) {
  const el = byId("speaking");
  if (saying === null) el.replaceChildren(h("span", { class: "muted" }, "silent"));
  else {
    const words = h("span", { class: "said" }, `“${saying.text}”`);
    if (saying.language) words.lang = saying.language;
    el.replaceChildren(words);
  }
}

function onEvent(e) {
  if (e.type === "stop") {
    said.clear();
    speakingId = null;
    showSpeaking(null);
    return;
  }
  if (e.verb !== "SAY") return;
  if (e.type === "command.sent") {
    said.set(e.command, { text: e.arg ?? "", language: e.args?.language ?? null });
  } else if (e.type === "command.started") {
    speakingId = e.command;
    showSpeaking(said.get(e.command) ?? { text: "…", language: null });
  } else if (ENDED.has(e.type)) {
    said.delete(e.command);
    if (e.command === speakingId) {
      speakingId = null;
      showSpeaking(null);
    }
  }
}

detectVoice().then((found) => {
  byId("no-voice").hidden = found;
});

// --- acts ---------------------------------------------------------------------------------


const list = createActList({
  element: byId("act-list"),
  count: byId("match-count"),
  onFire: (act, options) => fire(act, options),
  onPreview: () => {},
});

function fire(act, { interrupt = false } = {}) {
  const frame = { type: "trigger", label: act.label, ref: `preview-${++refCount}` };
  if (interrupt) frame.interrupt = true;
  if (!access.connection()?.send(frame)) {
    notice(`Not connected: ${act.label} was not fired.`);
    return;
  }
  list.flash(act.label);
}

const search = byId("search");
search.addEventListener("input", () => list.setQuery(search.value));
search.addEventListener("keydown", (event) => {
  if (event.key === "ArrowDown" || event.key === "ArrowUp") {
    event.preventDefault();
    list.move(event.key === "ArrowDown" ? 1 : -1);
  } else if (event.key === "Enter") {
    event.preventDefault();
    const act = list.chosen();
    if (act) fire(act, { interrupt: event.shiftKey });
    else notice("No act is chosen: type a word, or press ↓ to choose one.");
  }
});

async function loadActs() {
  const answer = await (await fetch("/api/acts")).json();
  list.setActs(readActs(answer));
}

// --- live reload --------------------------------------------------------------------------

const banner = createReloadBanner({
  element: byId("reload-banner"),
  onReloaded: () => loadActs().catch((error) => notice(`The acts could not be loaded: ${error.message}`)),
});

// --- the server ---------------------------------------------------------------------------

const access = createAccess({
  path: config.ws || "/ws",
  open: config.credential === "open",
  ...accessElements(byId),
  onFrame: (frame) => {
    banner.onFrame(frame);
    if (frame.type === "event") onEvent(frame.event);
    else if (frame.type === "error" && String(frame.ref ?? "").startsWith("preview-")) {
      notice(`Not fired: ${frame.message ?? frame.code}`);
    } else if (frame.type === "welcome") {
      said.clear();
      speakingId = null;
      showSpeaking(null);
    }
  },
  onOnline: () => {},
  onSignedOut: () => {},
});

loadActs().catch((error) => notice(`The acts could not be loaded: ${error.message}`));
access.begin();
