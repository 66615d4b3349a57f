// main.js: the operator console (GET /operator), wiring its modules together. The panels: acts
// (actlist.js, preview.js), live state (live.js, map.js, clients.js), the caption line beside
// Stop (caption.js), history, proposals, marks,
// the shared context (context.js), the visitor's language (language.js) and the camera (camerapanel.js, which loads camera.js when
// the server has it). Signing in, the one websocket as an operator and lockouts are access.js;
// the server's frames and events reach the panels through events.js; Stop, which never waits
// (over HTTP when the websocket cannot or does not answer), is stop.js; keys.js the keyboard.
// The corpus banner (the log cannot be written, in the server's words) is corpusbanner.js.
// The kiosk banner (a kiosk or projector whose connection was lost) is kioskbanner.js.
// A consent change that deletes a session's recordings waits for the operator's confirmation
// (consentconfirm.js). The live-reload banner (a refused save, a folder gone) is reloadbanner.js; after a good save
// the act list is loaded again. What is left here: firing acts, answering proposals, marks, the notice line, and loading the
// acts and the console's settings.

import { readActs, textsFor } from "./acts.js";
import { accessElements, createAccess } from "./access.js";
import { createActList } from "./actlist.js";
import * as api from "./api.js";
import { createCameraPanel } from "./camerapanel.js";
import { createClients } from "./clients.js";
import { createCaptionLine } from "./caption.js";
import { createConsentConfirm } from "./consentconfirm.js";
import { createContext } from "./context.js";
import { createCorpusBanner } from "./corpusbanner.js";
import { byId, clock, createNotice } from "./dom.js";
import { createEvents } from "./events.js";
import { createHistory } from "./history.js";
import { createKioskBanner } from "./kioskbanner.js";
import { createLanguage } from "./language.js";
import { bindKeys } from "./keys.js";
import { createLive } from "./live.js";
import { createMap } from "./map.js";
import { createMarks } from "./marks.js";
import { showPreview } from "./preview.js";
import { createProposals } from "./proposals.js";
import { createRecording } from "./recording.js";
import { createReloadBanner } from "./reloadbanner.js";
import { createRobotLink } from "./robotlink.js";
import { createStop } from "./stop.js";
import * as store from "./store.js";

const NOTICE_MS = 6_000;
const notice = createNotice(byId("notice"), NOTICE_MS);
const NO_SETTINGS = { map: null, camera: { kind: "none" }, situations: [], visitor_groups: {} };

const config = document.body.dataset;
const open = config.credential === "open";

let lastFired = null;
let refCount = 0;
let settings = null; // GET /api/operator, once loaded

// --- panels ---------------------------------------------------------------------------------

const search = byId("search");
const previewEl = byId("preview");

const list = createActList({
  element: byId("act-list"),
  count: byId("match-count"),
  onFire: (act, options) => fire(act, options),
  onPreview: (act) => showPreview(previewEl, act, context.current(), list.language()),
});
const context = createContext({
  select: byId("context"),
  note: byId("context-note"),
  list,
  ask: (wanted) => send({ type: "context", context: wanted, ref: ref("context") }, `context ${wanted}`),
});
const language = createLanguage({
  group: byId("language-pick"),
  buttons: byId("language-buttons"),
  note: byId("language-note"),
  ask: (wanted) => send({ type: "language", language: wanted, ref: ref("language") }, `language ${wanted}`),
  onChange: (tag) => {
    list.setLanguage(tag);
    proposals.refresh(); // proposals name the texts in the visitor's language
  },
});
const liveView = createLive({
  kiosk: byId("kiosk-page"),
  projector: byId("projector-content"),
  speaking: byId("speaking"),
  queue: byId("queue"),
});
const map = createMap({ panel: byId("map-panel"), view: byId("map"), text: byId("pose-text") });
const camera = createCameraPanel({
  panel: byId("camera-panel"),
  element: byId("camera"),
  script: config.cameraScript,
  send: (frame) => access.connection()?.send(frame) ?? false,
  clients: () => clients.get(),
});
const clients = createClients(byId("clients"), (all) => camera.clients(all));
const history = createHistory(byId("history"));
const proposals = createProposals({
  panel: byId("proposals"),
  list: byId("proposal-list"),
  accept: (id) => answerProposal("accept", id),
  dismiss: (id) => answerProposal("dismiss", id),
  says: (label, ctx) => {
    const act = list.act(label);
    return act ? textsFor(act, ctx ?? context.current(), list.language()).texts[0] ?? null : null;
  },
  who: (client) => {
    const c = clients.get().get(client);
    return c?.name ? `${c.name} (#${client})` : `dialog manager #${client ?? "?"}`;
  },
  now: () => events.now(),
});
const marks = createMarks({
  session: byId("session"),
  start: byId("session-start"),
  end: byId("session-end"),
  consent: byId("consent"),
  groups: byId("visitor-groups"),
  situations: byId("situation-buttons"),
  note: { form: byId("note-form"), input: byId("note") },
  mark: (mark, value, extra = {}) => {
    if (mark === "group") context.expect(settings?.visitor_groups?.[value]);
    send({ type: "mark", mark, ...(value ? { value } : {}), ...extra, ref: ref("mark") }, `mark ${mark}`);
  },
  confirmDeletion: (session, consent) => consentConfirm.ask(session, consent),
});
const consentConfirm = createConsentConfirm({
  dialog: byId("consent-confirm"),
  title: byId("consent-confirm-title"),
  text: byId("consent-confirm-text"),
  cancel: byId("consent-confirm-cancel"),
  confirm: byId("consent-confirm-delete"),
  recording: async () => (await getJson("/api/state", () => access.connection() !== null))?.recording ?? null,
});

const robotLink = createRobotLink(byId("robot-link"));
const captionLine = createCaptionLine(byId("caption-line"));
const recording = createRecording({ status: byId("recording-status"), alert: byId("recording-alert") });

const corpusBanner = createCorpusBanner(byId("corpus-banner"));
const kioskBanner = createKioskBanner({
  element: byId("kiosk-banner"),
  clock,
  // Said by the kiosk: its line's source is its role and client id.
  onBack: (e, text) => history.note({ ...e, source: e.role }, "client.back", text),
});
const reloadBanner = createReloadBanner({
  element: byId("reload-banner"),
  onReloaded: () => loadActs().catch((error) => notice(`The acts could not be loaded: ${error.message}`)),
});

// --- the server -----------------------------------------------------------------------------

const access = createAccess({
  path: config.ws || "/ws",
  open,
  ...accessElements(byId),
  onFrame: (frame) => {
    corpusBanner.onFrame(frame);
    reloadBanner.onFrame(frame);
    captionLine.onFrame(frame);
    events.onFrame(frame);
  },
  onOnline: () => loadSettings(),
  onClosed: (reason) =>
    notice(`Docent closed this console's connection (${reason}); reconnecting. Events in between are in the corpus, not in this list.`),
  onSignedOut: () => camera.stop(),
});
const stopper = createStop({
  button: byId("stop"),
  send: (frame) => access.connection()?.send(frame),
  ref,
  token: access.token,
  open,
  notice,
});
const events = createEvents({
  panels: { live: liveView, clients, history, proposals, marks, map, recording, robotLink, kiosks: kioskBanner },
  context,
  language,
  camera,
  operatorName: byId("operator-name"),
  name: access.name,
  stopped: stopper.settle,
  notice,
  getJson,
  connected: () => access.connection() !== null,
});

/** GET `path` with the credential while `wanted()`, waiting out a lockout (api.js). */
function getJson(path, wanted) {
  return api.getJson(path, { wanted, token: access.token, lockout: access.showLockout });
}

// --- actions --------------------------------------------------------------------------------

function ref(kind) {
  return `console-${kind}-${++refCount}`;
}

/** Sends a frame; says so when the console is offline. */
function send(frame, what) {
  if (access.connection()?.send(frame)) return true;
  notice(`Not connected: ${what} was not sent.`);
  return false;
}

function fire(act, { interrupt = false } = {}) {
  const frame = { type: "trigger", label: act.label, ref: ref("act") };
  if (interrupt) frame.interrupt = true;
  if (!send(frame, act.label)) return false;
  lastFired = act.label;
  byId("repeat-label").textContent = `F2 repeats ${act.label}`;
  store.noteFired(act.label);
  if (search.value) {
    search.value = "";
    list.setQuery("");
  } else {
    list.refresh();
  }
  list.flash(act.label);
  return true;
}

function answerProposal(kind, id) {
  if (id === null || id === undefined) return;
  send({ type: kind, proposal: id, ref: ref(kind) }, `${kind} proposal ${id}`);
}


search.addEventListener("input", () => list.setQuery(search.value));

bindKeys({
  search,
  active: () => access.signedIn() && !document.querySelector("dialog[open]"),
  stop: () => {
    consentConfirm.cancel(); // Esc answers an open question no, and stops as always
    stopper.stop();
  },
  fire: ({ interrupt }) => {
    const act = list.chosen();
    return act ? fire(act, { interrupt }) : false;
  },
  move: (delta) => {
    // In the act list the focus follows the choice; from anywhere else it goes to the search,
    // so that no other control (a button, a selector) keeps it for the next Enter.
    const inList = document.activeElement?.closest?.("#act-list") != null;
    list.move(delta, { focus: inList });
    if (!inList) search.focus();
  },
  repeat: () => {
    const act = lastFired && list.act(lastFired);
    if (act) fire(act);
    else notice("Nothing to repeat yet.");
  },
  favourite: () => {
    const act = list.chosen();
    if (!act) return notice("Choose an act first (↑ ↓) to star it.");
    store.toggleFavourite(act.label);
    list.refresh();
  },
  accept: () => {
    const id = proposals.newest();
    if (id === null) notice("No proposal is waiting.");
    else answerProposal("accept", id);
  },
  dismiss: () => {
    const id = proposals.newest();
    if (id === null) notice("No proposal is waiting.");
    else answerProposal("dismiss", id);
  },
  actKey: (key, { repeat }) => {
    const act = list.byKey(key);
    if (act && !repeat) fire(act);
    return Boolean(act);
  },
  situation: (n, { repeat }) => {
    const situation = marks.situation(n);
    if (situation && !repeat) send({ type: "mark", mark: "situation", value: situation, ref: ref("mark") }, `situation ${situation}`);
    return Boolean(situation);
  },
  note: () => marks.focusNote(),
  typed: () => list.setQuery(search.value),
});

// --- loading --------------------------------------------------------------------------------

async function loadSettings() {
  if (settings) {
    await camera.start(settings.camera);
    return;
  }
  const mine = access.connection();
  const answer = await getJson("/api/operator", () => access.connection() === mine && mine !== null);
  if (access.connection() !== mine || !mine) return; // signed out meanwhile
  if (settings) return; // an earlier call got them
  settings = answer ? { ...NO_SETTINGS, ...answer } : NO_SETTINGS;
  map.configure(settings.map);
  marks.configure(settings);
  await camera.start(settings.camera ?? { kind: "none" });
}

async function loadActs() {
  const answer = await (await fetch("/api/acts")).json();
  context.options(answer.contexts ?? ["Text"]);
  list.setActs(readActs(answer));
  proposals.refresh(); // proposals shown before the acts arrived name their texts now
}

loadActs().catch((error) => notice(`The acts could not be loaded: ${error.message}`));
list.setContext(context.current());
access.begin();
