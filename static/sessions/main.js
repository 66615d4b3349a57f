// main.js: the replay and annotation page (GET /sessions). Signs in with the operator console's
// sign-in module (../operator/signin.js: the credential kept for this tab only, never in a URL;
// the name given there is written with each annotation), lists the corpus's sessions
// (GET /api/sessions) and opens one (GET /api/sessions/NAME): its timeline (timeline.js), its
// recordings under a media ticket (player.js keeps them in step with the session clock), what
// the touchscreen showed and the robot said at the playhead, and the codebook to annotate with
// (annotate.js). Space plays and pauses. `body[data-state]` says where the page is: signed-out,
// loading, ready (the list), open (a session shown).

import * as signin from "../operator/signin.js";
import { createAnnotator } from "./annotate.js";
import { getSession, listSessions, mediaTicket, saveAnnotation } from "./api.js";
import { createPlayer } from "./player.js";
import { createTimeline, seconds } from "./timeline.js";

const byId = (id) => document.getElementById(id);
const body = document.body;
const open = body.dataset.credential === "open";

let token = null;
let annotator = null;
let player = null;
let timeline = null;
let current = null; // the session shown

const dialog = signin.createSignIn({
  dialog: byId("signin"),
  form: byId("signin-form"),
  token: byId("signin-token"),
  name: byId("signin-name"),
  error: byId("signin-error"),
  onSubmit: (credentials) => start(credentials.token, credentials.name),
});

function setState(state, summary) {
  body.dataset.state = state;
  if (summary !== undefined) byId("summary").textContent = summary;
}

/** Says what a refused request means, and asks again for a refused credential. */
function refused(error) {
  if (error.status === 401) {
    signin.forget();
    setState("signed-out", "Not signed in.");
    dialog.ask("That credential was refused. Check it and try again.");
  } else if (error.status === 429) {
    const lockout = byId("lockout");
    lockout.textContent = `Too many wrong or missing credentials from this computer: Docent refuses wrong ones from it (the right credential is always taken) for ${error.retryAfterS} s. Try again then.`;
    lockout.hidden = false;
    setState("signed-out", "Locked out for now.");
    setTimeout(() => {
      lockout.hidden = true;
      dialog.ask();
    }, error.retryAfterS * 1000);
  } else {
    byId("summary").textContent = `${error.message} (${error.code})`;
  }
}

async function start(credential, name) {
  token = credential;
  if (name) signin.remember(null, name);
  annotator = name || signin.stored().name;
  setState("loading", "Loading the sessions…");
  let listed;
  try {
    listed = await listSessions(token);
  } catch (error) {
    refused(error);
    return;
  }
  if (token) signin.remember(token, annotator);
  showList(listed.sessions);
}

function showList(sessions) {
  const rows = sessions.map((s) => {
    const tr = document.createElement("tr");
    const cell = document.createElement("td");
    const button = document.createElement("button");
    button.type = "button";
    button.className = "link";
    button.textContent = s.name;
    button.dataset.session = s.name;
    button.addEventListener("click", () => openSession(s.name));
    cell.append(button);
    tr.append(cell);
    const length = s.length_us === null ? "" : seconds(s.length_us);
    for (const text of [s.state, length, s.events, s.media, s.annotations]) {
      const td = document.createElement("td");
      td.textContent = String(text);
      tr.append(td);
    }
    return tr;
  });
  byId("session-list").replaceChildren(...rows);
  setState("ready", sessions.length ? `${sessions.length} session${sessions.length === 1 ? "" : "s"}.` : "The corpus has no sessions yet.");
}

/** What the touchscreen showed and the robot said at `us`. */
function showNow(us) {
  const t = current.timeline;
  const within = (item) => item.start_us <= us && us < item.end_us;
  const page = t.pages.find(within) ?? null;
  const nowPage = byId("now-page");
  const name = page?.page ?? "none";
  if (nowPage.textContent !== name) {
    nowPage.textContent = name;
    const frame = byId("now-page-frame");
    frame.hidden = !page?.url;
    if (page?.url && frame.getAttribute("src") !== page.url) frame.setAttribute("src", page.url);
  }
  const said = t.utterances.find(within);
  const text = said?.text ?? "";
  if (byId("now-utterance").textContent !== text) byId("now-utterance").textContent = text;
}

function onTick(us, playing) {
  timeline.setPlayhead(us);
  byId("clock").textContent = `${seconds(us)} / ${seconds(current.timeline.length_us)}`;
  byId("play").textContent = playing ? "Pause" : "Play";
  showNow(us);
}

/** The session's recordings, as media elements under a fresh ticket. */
async function mediaElements(detail) {
  const holder = byId("media");
  holder.replaceChildren();
  if (!detail.media.length) {
    holder.append(Object.assign(document.createElement("p"), { className: "hint", textContent: "No recordings: the session plays on its own clock." }));
    return [];
  }
  const { base } = await mediaTicket(token, detail.name);
  return detail.media.map((m) => {
    const el = document.createElement(m.track === "video" ? "video" : "audio");
    el.src = base + m.file;
    el.preload = "auto";
    el.dataset.file = m.file;
    el.setAttribute("aria-label", `Recording ${m.file} (${m.track}, from ${seconds(m.start_us)})`);
    holder.append(el);
    return { el, startUs: m.start_us };
  });
}

async function openSession(name) {
  setState("loading", `Opening ${name}…`);
  let detail;
  let media;
  try {
    detail = await getSession(token, name);
    media = await mediaElements(detail);
  } catch (error) {
    refused(error);
    if (error.status !== 401) setState("ready");
    return;
  }
  player?.stop();
  current = detail;
  byId("session-title").textContent = `Session ${detail.name}`;
  const warnings = [...detail.warnings, ...detail.annotation_problems.map((p) => `annotations.jsonl line ${p.line}: ${p.problem}`)];
  byId("session-warnings").textContent = warnings.join(" ");
  const lengthUs = detail.timeline.length_us;
  timeline = createTimeline({
    timeline: byId("timeline"),
    tiers: byId("tiers"),
    playhead: byId("playhead"),
    lengthUs,
    onSeek: (us) => player.seek(us),
  });
  timeline.render(detail);
  player = createPlayer({
    lengthUs,
    media,
    onTick,
    onProblem: (message) => {
      byId("session-warnings").textContent = message;
    },
  });
  player.setRate(Number(byId("speed").value));
  annotations.load(detail);
  byId("replay").hidden = false;
  setState("open", `Session ${detail.name}: ${seconds(lengthUs)}.`);
  player.seek(0);
}

const annotations = createAnnotator({
  codebook: byId("codebook"),
  pending: byId("pending"),
  status: byId("save-status"),
  error: byId("save-error"),
  list: byId("annotations"),
  count: byId("annotation-count"),
  position: () => player?.position() ?? 0,
  onSeek: (us) => player?.seek(us),
  save: (edit) => saveAnnotation(token, current.name, annotator ? { ...edit, ...(edit.action === "delete" ? {} : { annotator }) } : edit),
  onChange: (list) => {
    current.annotations = list;
    timeline.showAnnotations(list);
  },
});

byId("play").addEventListener("click", () => player?.toggle());
byId("speed").addEventListener("change", (event) => player?.setRate(Number(event.target.value)));
document.addEventListener("keydown", (event) => {
  if (event.key !== " " || !player || document.querySelector("dialog[open]")) return;
  if (event.target.closest("button, input, select, textarea, a")) return;
  event.preventDefault();
  player.toggle();
});

byId("signout").addEventListener("click", () => {
  signin.forget();
  player?.stop();
  byId("replay").hidden = true;
  byId("session-list").replaceChildren();
  setState("signed-out", "Signed out.");
  dialog.ask();
});

if (open) {
  byId("signout").hidden = true;
  start(null, null);
} else {
  const saved = signin.stored().token;
  if (saved) start(saved, null);
  else dialog.ask();
}
