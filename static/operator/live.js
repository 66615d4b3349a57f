// live.js: what the robot does now: the kiosk's page and the projector's content with what
// the projector reported about it (display.changed, welcome state), the text being spoken (a SAY between command.started and
// its end) and the queue of commands sent to adapters and not yet ended (command.* events;
// before those, the per-adapter snapshot of GET /api/state `queues`). The snapshot is fetched
// after `welcome` while events already arrive: a part of it is used only as long as no event
// about that part came first (an event is newer than any snapshot still on its way).
// The kiosk's attract loop (attract.started / attract.ended events) is shown beside its page.

import { h, shorten } from "./dom.js";

const PROJECTOR_STATES = { loading: "not shown yet", shown: "shown", playing: "playing", held: "ended, last frame held" };
const ENDED = new Set(["command.done", "command.failed", "command.cancelled"]);

/** @param {{kiosk: HTMLElement, projector: HTMLElement, speaking: HTMLElement, queue: HTMLElement}} els */
export function createLive(els) {
  const commands = new Map(); // id -> {id, verb, arg, label, adapter, started}
  let snapshot = []; // [{adapter, verb, current, queued}] from /api/state until events take over
  let speakingId = null;
  let speakingText = null;
  // Which parts events have told since the connection's `welcome`: the snapshot leaves them be.
  // `verbs`: the verbs of command events seen (the snapshot's queue entries of those verbs are
  // older); `queue`: a stop emptied every queue.
  const told = { display: false, speech: false, queue: false, verbs: new Set() };
  let kioskPage = null;
  let attracting = false;

  function showKiosk() {
    const loop = attracting ? h("span", { class: "muted small", dataset: { attract: "" } }, " · attract loop") : "";
    els.kiosk.replaceChildren(kioskPage ?? "–", loop);
  }

  function showDisplay(display) {
    if (!display) return;
    kioskPage = display.page ?? null;
    showKiosk();
    // What the projector reported (docs/PROTOCOL.md `projector_state`), not what was asked.
    const state = display.projector_state ?? "black";
    const shown = display.highlight ? `highlight ${display.highlight}` : display.projector;
    els.projector.dataset.state = state;
    els.projector.replaceChildren(
      shown && state !== "black" ? shown : "black",
      PROJECTOR_STATES[state] ? h("span", { class: "muted small" }, ` · ${PROJECTOR_STATES[state]}`) : "",
    );
  }

  function showSpeaking() {
    if (speakingText) els.speaking.replaceChildren(h("span", { class: "said" }, `“${speakingText}”`));
    else els.speaking.replaceChildren(h("span", { class: "muted" }, "silent"));
  }

  function showQueue() {
    const items = [
      ...snapshot.map((s) =>
        h("li", { class: "queue-item started" }, h("code", {}, shorten(s.current, 70)), h("span", { class: "muted small" }, ` ${s.adapter}${s.queued ? `, ${s.queued} waiting` : ""}`)),
      ),
      ...[...commands.values()].map((c) =>
        h(
          "li",
          { class: `queue-item ${c.started ? "started" : "waiting"}`, dataset: { command: String(c.id) } },
          h("code", {}, shorten(c.arg ? `${c.verb} ${c.arg}` : c.verb, 70)),
          h("span", { class: "muted small" }, ` ${c.label} · ${c.adapter ?? ""} · ${c.started ? "running" : "queued"}`),
        ),
      ),
    ];
    els.queue.replaceChildren(...(items.length ? items : [h("li", { class: "muted" }, "nothing running")]));
  }

  return {
    /** The `state` of a welcome frame. */
    welcome(state) {
      showDisplay(state?.display);
    },
    /** A GET /api/state answer. */
    apiState(state) {
      if (!told.display) showDisplay(state.display);
      if (!told.queue) {
        snapshot = Object.entries(state.queues ?? {})
          .filter(([, q]) => q.current && !told.verbs.has(q.current_verb))
          .map(([adapter, q]) => ({ adapter, verb: q.current_verb, current: q.current, queued: q.queued ?? 0 }));
      }
      if (!told.speech) speakingText = state.speaking ?? null;
      showSpeaking();
      showQueue();
    },
    /** One event. */
    event(e) {
      if (e.type === "display.changed") told.display = true;
      else if (e.type.startsWith("command.") && e.verb) told.verbs.add(e.verb);
      if (e.verb === "SAY" && (e.type === "command.started" || ENDED.has(e.type))) told.speech = true;
      if (e.type === "stop") told.queue = told.speech = true;
      if (e.type === "display.changed") {
        showDisplay(e);
      } else if (e.type === "attract.started" || e.type === "attract.ended") {
        attracting = e.type === "attract.started";
        showKiosk();
      } else if (e.type === "command.sent") {
        commands.set(e.command, { id: e.command, verb: e.verb, arg: e.arg ?? null, label: e.label, adapter: e.adapter, started: false });
        showQueue();
      } else if (e.type === "command.started") {
        const c = commands.get(e.command);
        if (c) c.started = true;
        if (e.verb === "SAY") {
          speakingId = e.command;
          speakingText = c?.arg ?? speakingText;
          showSpeaking();
        }
        showQueue();
      } else if (ENDED.has(e.type)) {
        if (!commands.delete(e.command)) snapshot = snapshot.filter((s) => s.verb !== e.verb);
        if (e.command === speakingId || (speakingId === null && e.verb === "SAY")) {
          speakingId = null;
          speakingText = null;
          showSpeaking();
        }
        showQueue();
      } else if (e.type === "stop") {
        snapshot = [];
        speakingId = null;
        speakingText = null;
        showSpeaking();
        showQueue();
      }
    },
    /** Forgets everything before a new connection's snapshot. */
    reset() {
      told.display = told.speech = told.queue = false;
      told.verbs.clear();
      attracting = false;
      commands.clear();
      snapshot = [];
      speakingId = null;
      speakingText = null;
      showSpeaking();
      showQueue();
    },
  };
}
