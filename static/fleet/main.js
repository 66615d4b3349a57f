// main.js: the fleet view (GET /fleet). Signs in with the operator console's sign-in module
// (../operator/signin.js: the credential kept for this tab only, never in a URL), then reads
// GET /api/fleet/updates, a text/event-stream of the robots heard on the MQTT broker, with the
// credential in a header (so `fetch`, not EventSource). The first message is a snapshot; each
// later one changes one robot or the broker link. A lost stream or broker link is shown at
// once, never hidden: the page says so and reconnects. Stop asks the server to publish a stop
// on that robot's `cmd` and shows the robot's own answer, or why there was none.
// `body[data-state]`: signed-out, connecting, live, lost.

import * as signin from "../operator/signin.js";
import { authHeaders, retryAfter } from "../operator/api.js";

const byId = (id) => document.getElementById(id);
const body = document.body;
const open = body.dataset.credential === "open";
const robots = new Map(); // id -> {robot, online, state}
let token = null;
let retryMs = 500;

const dialog = signin.createSignIn({
  dialog: byId("signin"),
  form: byId("signin-form"),
  token: byId("signin-token"),
  name: byId("signin-name"),
  error: byId("signin-error"),
  onSubmit: (credentials) => start(credentials.token),
});

function problem(text) {
  const p = byId("problem");
  p.textContent = text ?? "";
  p.hidden = !text;
}

function showLink(link, lost = null) {
  const el = byId("link");
  if (lost) {
    el.dataset.link = "lost";
    el.textContent = lost;
    return;
  }
  el.dataset.link = link.state;
  el.textContent =
    link.state === "up"
      ? `Broker ${link.broker}: connected.`
      : link.state === "down"
        ? `Broker ${link.broker}: link down (${link.reason ?? "no reason given"}). The robots' states below may be out of date; Stop cannot reach them.`
        : `Broker ${link.broker}: connecting…`;
}

const text = (value) => (value === null || value === undefined || value === "" ? "—" : String(value));

function pose(p) {
  if (!p) return "—";
  return `x ${p.x.toFixed(2)} m, y ${p.y.toFixed(2)} m, ${Math.round(p.heading)}°${p.moving ? ", moving" : ""}`;
}

function row(entry) {
  const s = entry.state ?? {};
  const tr = document.createElement("tr");
  tr.dataset.robot = entry.robot;
  tr.dataset.online = String(entry.online);
  const cells = [
    entry.robot,
    entry.online ? "online" : "offline",
    text(s.page),
    text(s.speaking),
    pose(s.pose),
    s.battery ? `${Math.round(s.battery.percent)} %` : "unknown",
    s.link ? s.link.state : "—",
  ];
  for (const [i, value] of cells.entries()) {
    const cell = document.createElement(i === 0 ? "th" : "td");
    if (i === 0) cell.scope = "row";
    cell.textContent = value;
    cell.dataset.field = ["robot", "online", "page", "speaking", "pose", "battery", "link"][i];
    tr.append(cell);
  }
  const actions = document.createElement("td");
  actions.className = "actions";
  if (s.console && /^https?:\/\//.test(s.console)) {
    const a = document.createElement("a");
    a.className = "console";
    a.href = s.console;
    a.target = "_blank";
    a.rel = "noopener";
    a.textContent = "Console";
    a.setAttribute("aria-label", `Open ${entry.robot}'s console`);
    actions.append(a);
  }
  const stop = document.createElement("button");
  stop.type = "button";
  stop.className = "stop";
  stop.textContent = "Stop";
  stop.setAttribute("aria-label", `Stop ${entry.robot}`);
  stop.addEventListener("click", () => stopRobot(entry.robot, stop, outcome));
  const outcome = document.createElement("span");
  outcome.className = "outcome";
  outcome.setAttribute("role", "status");
  actions.append(stop, outcome);
  tr.append(actions);
  return tr;
}

function render() {
  const list = byId("robots");
  // Keep the row that has focus (a Stop button) where it is: replace the others only.
  const focused = document.activeElement?.closest("tr")?.dataset.robot;
  const ids = [...robots.keys()].sort();
  const rows = ids.map((id) => {
    const old = list.querySelector(`tr[data-robot="${CSS.escape(id)}"]`);
    if (old && id === focused) {
      const fresh = row(robots.get(id));
      for (const field of ["online", "page", "speaking", "pose", "battery", "link"]) {
        old.querySelector(`[data-field="${field}"]`).textContent = fresh.querySelector(`[data-field="${field}"]`).textContent;
      }
      old.dataset.online = fresh.dataset.online;
      return old;
    }
    return row(robots.get(id));
  });
  list.replaceChildren(...rows);
  byId("empty").hidden = ids.length > 0;
}

function apply(kind, data) {
  if (kind === "snapshot") {
    robots.clear();
    for (const entry of data.robots) robots.set(entry.robot, entry);
    showLink(data.link);
  } else if (data.link) {
    showLink(data.link);
  } else if (data.robot) {
    robots.set(data.robot.robot, data.robot);
  } else if (data.gone) {
    robots.delete(data.gone);
  }
  render();
}

async function stopRobot(id, button, outcome) {
  button.disabled = true;
  outcome.className = "outcome";
  outcome.textContent = "Stopping…";
  try {
    const res = await fetch(`/api/fleet/robots/${encodeURIComponent(id)}/stop`, {
      method: "POST",
      headers: authHeaders(token),
    });
    const json = await res.json().catch(() => null);
    if (res.ok) {
      outcome.textContent = `Stopped (${id} confirmed).`;
    } else {
      outcome.className = "outcome failed";
      outcome.textContent = `Not stopped: ${json?.error ?? `the fleet server answered ${res.status}`}`;
    }
  } catch {
    outcome.className = "outcome failed";
    outcome.textContent = "Not stopped: the fleet server did not answer.";
  } finally {
    button.disabled = false;
  }
}

/** Reads the update stream until it ends; resolves with why it ended. */
async function follow() {
  let res;
  try {
    res = await fetch("/api/fleet/updates", { headers: { ...authHeaders(token), Accept: "text/event-stream" } });
  } catch {
    return "the fleet server did not answer";
  }
  if (!res.ok) {
    const json = await res.json().catch(() => null);
    if (res.status === 401) return { refused: true };
    if (res.status === 429) return { locked: retryAfter(res) };
    // This Docent follows no fleet: trying again would not change that.
    if (res.status === 404) return { final: json?.error ?? "this server has no fleet view" };
    return json?.error ?? `the fleet server answered ${res.status}`;
  }
  if (token) signin.remember(token, null);
  body.dataset.state = "live";
  problem(null);
  retryMs = 500;
  const reader = res.body.pipeThrough(new TextDecoderStream()).getReader();
  let buffer = "";
  for (;;) {
    let chunk;
    try {
      chunk = await reader.read();
    } catch {
      return "the connection to the fleet server was lost";
    }
    if (chunk.done) return "the fleet server ended the stream";
    buffer += chunk.value;
    let end;
    while ((end = buffer.indexOf("\n\n")) >= 0) {
      const message = buffer.slice(0, end);
      buffer = buffer.slice(end + 2);
      let kind = "message";
      const data = [];
      for (const line of message.split("\n")) {
        if (line.startsWith("event:")) kind = line.slice(6).trim();
        else if (line.startsWith("data:")) data.push(line.slice(5).replace(/^ /, ""));
      }
      if (data.length) apply(kind, JSON.parse(data.join("\n")));
    }
  }
}

async function start(credential) {
  token = credential || null;
  body.dataset.state = "connecting";
  for (;;) {
    const ended = await follow();
    if (ended?.refused) {
      signin.forget();
      body.dataset.state = "signed-out";
      showLink(null, "Not signed in.");
      dialog.ask("That credential was refused. Check it and try again.");
      return;
    }
    if (ended?.final) {
      body.dataset.state = "lost";
      showLink(null, ended.final);
      return;
    }
    if (ended?.locked) {
      body.dataset.state = "signed-out";
      problem(`Too many wrong or missing credentials from this computer: try again in ${ended.locked} s.`);
      setTimeout(() => dialog.ask(), ended.locked * 1000);
      return;
    }
    body.dataset.state = "lost";
    showLink(null, `Not live: ${ended}. Reconnecting…`);
    await new Promise((resolve) => setTimeout(resolve, retryMs));
    retryMs = Math.min(retryMs * 2, 5000);
  }
}

if (open) {
  start(null);
} else {
  const { token: kept } = signin.stored();
  if (kept) start(kept);
  else dialog.ask();
}
