// main.js: the operator console (GET /operator). Signs in, keeps one websocket as an operator,
// and wires the panels together: acts (actlist.js, preview.js), keys (keys.js), live state
// (live.js, map.js, clients.js), history, proposals, marks and the camera (camera.js, when the
// server has it). Events are handed to every panel once: after `welcome` the server replays
// recent history strictly before the live events, all in `seq` order, so an event whose `seq`
// is not above the highest seen is one already handled. The GET /api/state snapshot fetched
// after `welcome` fills in only what no event has told since. Stop never waits: without a
// connection, or when the websocket does not answer within STOP_ANSWER_MS, it goes over HTTP.

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
/** How long a websocket stop may wait for its `stopped` answer before Stop goes over HTTP. */
const STOP_ANSWER_MS = 500;
const NO_SETTINGS = { map: null, camera: { kind: "none" }, situations: [], visitor_groups: {} };

const config = document.body.dataset;
const open = config.credential === "open";

let connection = null;
let signedIn = false;
let me = null;
let token = null;
let verified = false; // the server accepted `token` before (or it was kept from this tab's sign-in)
let lockouts = 0; // `too-many-attempts` answers in a row
let name = null;
let context = "Text";
let askedContext = null; // the context this console asked for last, until the server confirms
let lastFired = null;
let refCount = 0;
let camera = null;
let settings = null; // GET /api/operator, once loaded
let lastSeq = -Infinity; // the highest event seq handled on this connection
let noticeTimer = null;
let welcomes = 0; // connections welcomed so far: a fetch for an older one is dropped
let streaming = false; // the live stream began (this console's own client.connected arrived)
let clockOffset = null; // this computer's clock minus the server's, from live events
const told = { pose: false, waypoint: false, session: false }; // newer than the snapshot
const pendingStops = new Map(); // ref -> timer: websocket stops not answered yet

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
const liveView = createLive({
  kiosk: byId("kiosk-page"),
  projector: byId("projector-content"),
  speaking: byId("speaking"),
  queue: byId("queue"),
});
const map = createMap({ panel: byId("map-panel"), view: byId("map"), text: byId("pose-text") });
// The camera hears of the kiosks only once the list is whole again after a `welcome` (with the
// snapshot): an empty list in between would look as if its kiosk had left.
let clientsKnown = false;
const clients = createClients(byId("clients"), (all) => clientsKnown && camera?.onClients(clientList(all)));
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
  now: () => Date.now() - (clockOffset ?? 0),
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
  const button = byId("stop");
  // Without the websocket (offline, not welcomed yet), Stop goes over HTTP at once: stopping
  // must not wait for a reconnect. A socket that looks open may be dead (half-open): when its
  // `stopped` answer does not come in time, Stop goes over HTTP too (stopping twice is harmless).
  const id = ref("stop");
  if (connection?.send({ type: "stop", ref: id })) {
    const timer = setTimeout(() => {
      settleStop(id);
      httpStop(`the websocket did not answer within ${STOP_ANSWER_MS} ms`);
    }, STOP_ANSWER_MS);
    pendingStops.set(id, timer);
    button.dataset.pending = String(pendingStops.size);
  } else {
    httpStop("the console is not connected");
  }
  button.classList.remove("pressed");
  void button.offsetWidth;
  button.classList.add("pressed");
}

/** A websocket stop is answered (or given up on): no HTTP stop for it. */
function settleStop(id) {
  clearTimeout(pendingStops.get(id));
  pendingStops.delete(id);
  byId("stop").dataset.pending = String(pendingStops.size); // how many wait for their answer
}

/** POST /api/stop with the credential; says how it went. */
function httpStop(why) {
  if (!token && !open) {
    notice("Not signed in: Stop needs the operator credential.");
    return;
  }
  fetch("/api/stop", { method: "POST", headers: authHeaders() })
    .then((res) => {
      if (res.ok) notice(`Stopped over HTTP (${why}).`);
      else if (res.status === 429) notice(`Stop refused: this computer is locked out for ${retryAfter(res)} s (too many wrong credentials).`);
      else notice(`Stop failed: HTTP ${res.status}`);
    })
    .catch(() => notice(`Stop could not reach Docent (${why}).`));
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
  // Chosen: let go of the focus, so that typing goes to the search and not into the selector.
  contextSelect.blur();
});
byId("stop").addEventListener("click", stop);
byId("signout").addEventListener("click", signOut);
search.addEventListener("input", () => list.setQuery(search.value));

bindKeys({
  search,
  active: () => signedIn && !byId("signin").open,
  stop,
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
  typed: () => list.setQuery(search.value),
});

// --- the server -----------------------------------------------------------------------------

function handleEvent(e) {
  if (typeof e?.seq === "number") {
    if (e.seq <= lastSeq) return;
    lastSeq = e.seq;
  }
  if (e.type === "client.connected" && e.client === me) streaming = true;
  const at = Date.parse(e.time ?? "");
  // The smallest (local - server) time of live events: the clocks' offset plus the least delay.
  if (streaming && Number.isFinite(at)) clockOffset = Math.min(clockOffset ?? Infinity, Date.now() - at);
  if (e.type === "pose") told.pose = true;
  else if (e.type === "command.sent" && e.verb === "SET_WAYPOINT") told.waypoint = true;
  else if (e.type === "session.started" || e.type === "session.ended") told.session = true;
  liveView.event(e);
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
      welcomes += 1;
      lastSeq = -Infinity; // a new connection replays its history (a new server run restarts seq)
      clientsKnown = false;
      streaming = false;
      told.pose = told.waypoint = told.session = false;
      history.welcome(me);
      proposals.welcome();
      clients.welcome(me);
      liveView.reset();
      liveView.welcome(frame.state);
      map.pose(frame.state?.pose);
      setContext(frame.state?.context);
      byId("operator-name").textContent = `${name || "operator"} #${me}`;
      loadState();
      break;
    case "stopped":
      settleStop(frame.ref);
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
      if (frame.mark === "session_start") {
        told.session = true;
        marks.setSession(frame.session);
      }
      break;
    default:
      break;
  }
}

function onStatus(status) {
  const link = byId("link");
  link.dataset.state = status.state;
  if (status.state !== "locked") showLockout(null);
  if (status.state === "online") {
    link.textContent = "connected";
    signedIn = true;
    verified = true;
    lockouts = 0;
    if (token) signin.remember(token, name);
    loadSettings();
  } else if (status.state === "connecting") {
    link.textContent = "connecting…";
  } else if (status.state === "offline") {
    link.textContent = "offline: reconnecting…";
  } else if (status.state === "locked") {
    // Too many wrong or missing credentials from this computer (maybe not this console's): the
    // server refuses every one for a while. The credential is kept and tried again after the
    // wait, with no sign-in form over the console (Stop stays in reach). Only a credential the
    // server never accepted and that is refused again right after the wait is given up: the
    // server then answers a wrong one with `too-many-attempts` as well, and retrying it would
    // keep this computer locked out for good.
    lockouts += 1;
    if (!verified && lockouts >= 2) {
      connection?.close();
      refused("Still refused after the wait: the credential is probably wrong. Check it and try again.");
      return;
    }
    link.textContent = "locked out: waiting";
    showLockout(status.retryAt);
  } else if (status.state === "refused") {
    // A wrong credential: forget it and ask again.
    refused("That credential was refused. Check it and try again.");
  }
}

/** The credential is given up: forget it and ask for one, saying `why`. */
function refused(why) {
  const link = byId("link");
  link.textContent = "signed out";
  link.dataset.state = "refused";
  showLockout(null);
  signedIn = false;
  connection = null;
  camera?.stop();
  camera = null;
  signin.forget();
  token = null;
  verified = false;
  dialog.ask(why);
}

let lockoutTimer = null;

/** The lockout banner counting down to `retryAt` (ms, this computer's clock); null hides it. */
function showLockout(retryAt) {
  const banner = byId("lockout");
  clearInterval(lockoutTimer);
  lockoutTimer = null;
  if (retryAt === null || retryAt === undefined) {
    banner.hidden = true;
    return;
  }
  const show = () => {
    const left = Math.max(0, Math.ceil((retryAt - Date.now()) / 1000));
    banner.dataset.seconds = String(left);
    banner.textContent =
      left > 0
        ? `Too many wrong or missing credentials from this computer: Docent refuses every sign-in from it for ${left} s more. The console keeps its credential and signs in again by itself then. Stop tries the server all the same.`
        : "Signing in again…";
  };
  show();
  banner.hidden = false;
  lockoutTimer = setInterval(show, 1000);
}

/** Signs in with `credential` (null on an open development server). */
function start(credential, operatorName, { kept = false } = {}) {
  connection?.close();
  token = credential;
  verified = kept; // a kept credential was accepted in this tab before
  lockouts = 0;
  name = operatorName || name || "operator";
  connection = connect({ path: config.ws || "/ws", token, name, onFrame, onStatus });
}

function signOut() {
  connection?.close();
  connection = null;
  signedIn = false;
  showLockout(null);
  camera?.stop();
  camera = null;
  signin.forget();
  token = null;
  byId("link").textContent = "signed out";
  byId("link").dataset.state = "offline";
  dialog.ask();
}

const authHeaders = () => (token ? { Authorization: `Bearer ${token}` } : {});

/** The seconds of a 429 answer's `Retry-After` (10 when it has none: asking early is harmless). */
function retryAfter(res) {
  const seconds = Number(res.headers.get("Retry-After"));
  return Number.isFinite(seconds) && seconds > 0 ? seconds : 10;
}

/**
 * GET `path` with the credential while `wanted()`: JSON, or null when it failed or is no longer
 * wanted (signed out, a newer connection). A lockout (429) is waited out and the request made
 * again.
 */
async function getJson(path, wanted) {
  while (wanted()) {
    let res;
    try {
      res = await fetch(path, { headers: authHeaders() });
    } catch (error) {
      console.warn(`docent console: no ${path}`, error);
      return null;
    }
    if (res.status === 429) {
      const seconds = retryAfter(res);
      showLockout(Date.now() + seconds * 1000);
      await new Promise((resolve) => setTimeout(resolve, (seconds + 1) * 1000));
      showLockout(null);
      continue;
    }
    if (!res.ok) {
      console.warn(`docent console: ${path} answered ${res.status}`);
      return null;
    }
    return wanted() ? res.json() : null;
  }
  return null;
}

async function loadState() {
  const welcome = welcomes;
  const state = await getJson("/api/state", () => welcome === welcomes && connection !== null);
  if (welcome !== welcomes) return;
  clientsKnown = true;
  if (!state) {
    camera?.onClients(clientList(clients.get())); // as far as the events told
    return;
  }
  liveView.apiState(state);
  clients.snapshot(state.clients);
  proposals.snapshot(state.proposals);
  // Only what no event told since `welcome`: an event is newer than this answer.
  if (!told.session) marks.setSession(state.session ?? null);
  if (!told.pose) map.pose(state.pose);
  if (!told.waypoint) map.waypoint(state.waypoint);
  document.body.dataset.snapshots = String(Number(document.body.dataset.snapshots ?? 0) + 1);
}

async function loadSettings() {
  if (settings) {
    await startCamera(settings.camera);
    return;
  }
  const mine = connection;
  const answer = await getJson("/api/operator", () => connection === mine && mine !== null);
  if (connection !== mine || !mine) return; // signed out meanwhile
  if (settings) return; // an earlier call got them
  settings = answer ? { ...NO_SETTINGS, ...answer } : NO_SETTINGS;
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
      if (clientsKnown) camera.onClients(clientList(clients.get()));
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
  if (saved.token) start(saved.token, saved.name, { kept: true });
  else dialog.ask();
}
