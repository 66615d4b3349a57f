// main.js: the operator console (GET /operator). Signs in, keeps one websocket as an operator,
// and wires the panels together: acts (actlist.js, preview.js), keys (keys.js), live state
// (live.js, map.js, clients.js), history, proposals, marks and the camera (camera.js, when the
// server has it). Events are handed to every panel once: the server replays recent history
// after `welcome`, which may repeat live events, so they are told apart by `seq`.

import { readActs, textsFor } from "./acts.js";
import { createActList } from "./actlist.js";
import { createClients } from "./clients.js";
import { connect } from "./connection.js";
import { byId, h } from "./dom.js";
import { createHistory } from "./history.js";
import { bindKeys } from "./keys.js";
import { createLive } from "./live.js";
import { createMap, parseWaypoint } from "./map.js";
import { createMarks } from "./marks.js";
import { showPreview } from "./preview.js";
import { createProposals } from "./proposals.js";
import * as signin from "./signin.js";
import * as store from "./store.js";

const NOTICE_MS = 6_000;
const NO_SETTINGS = { map: null, camera: { kind: "none" }, situations: [], visitor_groups: {} };

const config = document.body.dataset;
const open = config.credential === "open";

let connection = null;
let signedIn = false;
let me = null;
let token = null;
let name = null;
let context = "Text";
let askedContext = null; // the context this console asked for last, until the server confirms
let lastFired = null;
let refCount = 0;
let camera = null;
let settings = null; // GET /api/operator, once loaded
let seen = new Set();
let noticeTimer = null;

// --- panels ---------------------------------------------------------------------------------

const search = byId("search");
const previewEl = byId("preview");
const contextSelect = byId("context");

const list = createActList({
  element: byId("act-list"),
  count: byId("match-count"),
  onFire: (act, options) => fire(act, options),
  onPreview: (act) => showPreview(previewEl, act, context),
});
const live = createLive({
  kiosk: byId("kiosk-page"),
  projector: byId("projector-content"),
  speaking: byId("speaking"),
  queue: byId("queue"),
});
const map = createMap({ panel: byId("map-panel"), view: byId("map"), text: byId("pose-text") });
const clients = createClients(byId("clients"), (all) => camera?.onClients(clientList(all)));
const history = createHistory(byId("history"));
const proposals = createProposals({
  panel: byId("proposals"),
  list: byId("proposal-list"),
  accept: (id) => answerProposal("accept", id),
  dismiss: (id) => answerProposal("dismiss", id),
  says: (label, ctx) => {
    const act = list.act(label);
    return act ? textsFor(act, ctx ?? context).texts[0] ?? null : null;
  },
  who: (client) => {
    const c = clients.get().get(client);
    return c?.name ? `${c.name} (#${client})` : `dialog manager #${client ?? "?"}`;
  },
});
const marks = createMarks({
  session: byId("session"),
  start: byId("session-start"),
  end: byId("session-end"),
  groups: byId("visitor-groups"),
  situations: byId("situation-buttons"),
  mark: (mark, value) => {
    if (mark === "group") askedContext = settings?.visitor_groups?.[value] ?? askedContext;
    send({ type: "mark", mark, ...(value ? { value } : {}), ref: ref("mark") }, `mark ${mark}`);
  },
});
const dialog = signin.createSignIn({
  dialog: byId("signin"),
  form: byId("signin-form"),
  token: byId("signin-token"),
  name: byId("signin-name"),
  error: byId("signin-error"),
  onSubmit: (credentials) => start(credentials.token, credentials.name),
});

/** The connected clients as the camera wants them: `[{client, role, name}]`. */
function clientList(all) {
  return [...all].map(([client, c]) => ({ client, role: c.role, name: c.name }));
}

// --- actions --------------------------------------------------------------------------------

const ref = (kind) => `console-${kind}-${++refCount}`;

/** Sends a frame; says so when the console is offline. */
function send(frame, what) {
  if (connection?.send(frame)) return true;
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

function stop() {
  // Without the websocket, Stop still tries the HTTP route: stopping must not wait for a reconnect.
  if (!connection?.send({ type: "stop", ref: ref("stop") })) {
    fetch("/api/stop", { method: "POST", headers: authHeaders() })
      .then((res) => notice(res.ok ? "Stopped (over HTTP: the console is not connected)." : `Stop failed: HTTP ${res.status}`))
      .catch(() => notice("Not connected: Stop could not reach Docent."));
  }
  const button = byId("stop");
  button.classList.remove("pressed");
  void button.offsetWidth;
  button.classList.add("pressed");
}

function answerProposal(kind, id) {
  if (id === null || id === undefined) return;
  send({ type: kind, proposal: id, ref: ref(kind) }, `${kind} proposal ${id}`);
}

function notice(message) {
  const el = byId("notice");
  el.textContent = message;
  el.hidden = false;
  clearTimeout(noticeTimer);
  noticeTimer = setTimeout(() => (el.hidden = true), NOTICE_MS);
}

function setContext(name) {
  if (!name || name === context) return;
  context = name;
  if (![...contextSelect.options].some((o) => o.value === name)) contextSelect.append(h("option", { value: name }, name));
  contextSelect.value = name;
  list.setContext(name);
}

contextSelect.addEventListener("change", () => {
  const wanted = contextSelect.value;
  contextSelect.value = context; // shown once the server says it changed
  askedContext = wanted;
  send({ type: "context", context: wanted, ref: ref("context") }, `context ${wanted}`);
});
byId("stop").addEventListener("click", stop);
byId("signout").addEventListener("click", signOut);
search.addEventListener("input", () => list.setQuery(search.value));

bindKeys({
  search,
  active: () => signedIn,
  stop,
  fire: ({ interrupt }) => {
    const act = list.chosen();
    return act ? fire(act, { interrupt }) : false;
  },
  move: (delta) => list.move(delta, { focus: document.activeElement?.closest?.("#act-list") != null }),
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
    const id = proposals.oldest();
    if (id === null) notice("No proposal is waiting.");
    else answerProposal("accept", id);
  },
  dismiss: () => {
    const id = proposals.oldest();
    if (id === null) notice("No proposal is waiting.");
    else answerProposal("dismiss", id);
  },
  actKey: (key) => {
    const act = list.byKey(key);
    if (act) fire(act);
    return Boolean(act);
  },
  situation: (n) => {
    const situation = marks.situation(n);
    if (situation) send({ type: "mark", mark: "situation", value: situation, ref: ref("mark") }, `situation ${situation}`);
    return Boolean(situation);
  },
  typed: () => list.setQuery(search.value),
});

// --- the server -----------------------------------------------------------------------------

function handleEvent(e) {
  if (typeof e?.seq === "number") {
    if (seen.has(e.seq)) return;
    seen.add(e.seq);
  }
  live.event(e);
  clients.event(e);
  history.event(e);
  proposals.event(e);
  marks.event(e);
  if (e.type === "pose") map.pose(e);
  else if (e.type === "command.sent" && e.verb === "SET_WAYPOINT") map.waypoint(parseWaypoint(e.arg));
  else if (e.type === "context.changed") {
    setContext(e.context);
    // Events do not say which operator changed it: one this console asked for is its own.
    const mine = e.source === "operator" && e.context === askedContext;
    askedContext = null;
    byId("context-note").textContent = mine ? "" : `set by ${e.source === "operator" ? "another console" : e.source}`;
  }
}

function onFrame(frame) {
  switch (frame.type) {
    case "welcome":
      me = frame.client;
      seen = new Set();
      history.welcome(me);
      proposals.welcome();
      clients.welcome(me);
      live.reset();
      live.welcome(frame.state);
      map.pose(frame.state?.pose);
      setContext(frame.state?.context);
      byId("operator-name").textContent = `${name || "operator"} #${me}`;
      loadState();
      break;
    case "event":
      handleEvent(frame.event);
      break;
    case "signal":
      camera?.onSignal(frame);
      break;
    case "error":
      notice(frame.message ?? frame.code);
      break;
    case "marked":
      if (frame.mark === "session_start") marks.setSession(frame.session);
      break;
    default:
      break;
  }
}

function onStatus(status) {
  const link = byId("link");
  link.dataset.state = status.state;
  if (status.state === "online") {
    link.textContent = "connected";
    signedIn = true;
    if (token) signin.remember(token, name);
    loadSettings();
  } else if (status.state === "connecting") {
    link.textContent = "connecting…";
  } else if (status.state === "offline") {
    link.textContent = "offline: reconnecting…";
  } else if (status.state === "refused") {
    link.textContent = "signed out";
    signedIn = false;
    connection = null;
    camera?.stop();
    camera = null;
    signin.forget();
    dialog.ask(
      status.code === "too-many-attempts"
        ? "Too many failed attempts from this computer: wait a minute, then try again."
        : "That credential was refused. Check it and try again.",
    );
  }
}

/** Signs in with `credential` (null on an open development server). */
function start(credential, operatorName) {
  connection?.close();
  token = credential;
  name = operatorName || name || "operator";
  connection = connect({ path: config.ws || "/ws", token, name, onFrame, onStatus });
}

function signOut() {
  connection?.close();
  connection = null;
  signedIn = false;
  camera?.stop();
  camera = null;
  signin.forget();
  token = null;
  byId("link").textContent = "signed out";
  byId("link").dataset.state = "offline";
  dialog.ask();
}

const authHeaders = () => (token ? { Authorization: `Bearer ${token}` } : {});

async function loadState() {
  try {
    const state = await (await fetch("/api/state")).json();
    live.apiState(state);
    clients.snapshot(state.clients);
    proposals.snapshot(state.proposals);
    marks.setSession(state.session ?? null);
    map.pose(state.pose);
    map.waypoint(state.waypoint);
  } catch (error) {
    console.warn("docent console: no /api/state", error);
  }
}

async function loadSettings() {
  if (settings) {
    await startCamera(settings.camera);
    return;
  }
  try {
    const res = await fetch("/api/operator", { headers: authHeaders() });
    if (res.ok) settings = { ...NO_SETTINGS, ...(await res.json()) };
    else console.warn(`docent console: /api/operator answered ${res.status}`);
  } catch (error) {
    console.warn("docent console: no /api/operator", error);
  }
  settings ??= NO_SETTINGS;
  map.configure(settings.map);
  marks.configure(settings);
  await startCamera(settings.camera ?? { kind: "none" });
}

async function startCamera(settings) {
  const panel = byId("camera-panel");
  const element = byId("camera");
  panel.hidden = settings.kind === "none";
  if (panel.hidden || camera) return;
  if (config.cameraScript) {
    try {
      const module = await import(config.cameraScript);
      camera = module.createCamera({ element, send: (frame) => connection?.send(frame) ?? false, settings });
      camera.onClients(clientList(clients.get()));
      return;
    } catch (error) {
      console.error("docent console: the camera did not start", error);
    }
  }
  if (settings.kind === "url") element.replaceChildren(h("img", { src: settings.url, alt: "robot camera" }));
  else element.replaceChildren(h("p", { class: "muted" }, "camera not available in this server"));
}

async function loadActs() {
  const answer = await (await fetch("/api/acts")).json();
  contextSelect.replaceChildren(...(answer.contexts ?? ["Text"]).map((c) => h("option", { value: c }, c)));
  contextSelect.value = context;
  contextSelect.disabled = false;
  list.setActs(readActs(answer));
  proposals.refresh(); // proposals shown before the acts arrived name their texts now
}

loadActs().catch((error) => notice(`The acts could not be loaded: ${error.message}`));
list.setContext(context);
if (open) {
  byId("signout").hidden = true;
  start(null, signin.stored().name);
} else {
  const saved = signin.stored();
  if (saved.token) start(saved.token, saved.name);
  else dialog.ask();
}
