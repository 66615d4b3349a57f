// history.js: what happened, newest first: every act triggered by anyone (time, source, act,
// variant and the exact text chosen), stops, refused triggers, proposals accepted, dismissed or
// withdrawn (their dialog manager left), context and language changes, corpus marks (consent
// changes too, and the recordings a refused consent deleted), recording failures (the alarm
// above shows only those still current: recording.js), robot events and
// reactions to them that could not run, the fleet broker's link going down and up, a kiosk or
// projector back after a lost connection (kioskbanner.js). An act whose
// command was cancelled or failed says so on its line, with the reason: a text that was never
// said must not read as said. Several consoles see each other's acts here live.

import { clock, describeBytes, h } from "./dom.js";

const KEEP = 300;

/** @param {HTMLElement} list the <ol> to fill, newest first */
export function createHistory(list) {
  let me = null;

  const who = (e) => {
    const source = e.source ?? "";
    if (e.client === undefined || e.client === null) return source;
    return e.client === me ? `${source} (you)` : `${source} #${e.client}`;
  };

  function line(e) {
    switch (e.type) {
      case "act.triggered":
        return [
          "act",
          [
            h("strong", { class: "history-label" }, e.label),
            e.variant && e.variant !== "Text" ? h("span", { class: "muted small" }, ` ${e.variant}`) : null,
            e.interrupt ? h("span", { class: "muted small" }, " interrupting") : null,
            e.text ? h("span", { class: "history-text" }, ` “${e.text}”`) : null,
          ],
        ];
      case "stop":
        return ["stop", [h("strong", {}, "STOP"), ` ${e.reason ?? ""}`]];
      case "trigger.refused":
        return ["refused", [`refused ${e.label}: `, e.message ?? e.code]];
      case "client.refused":
        return ["refused", [`sign-in refused (${e.code}) for a ${e.role}`, e.address ? ` from ${e.address}` : ""]];
      case "proposal.accepted":
        return ["proposal", [`accepted proposal ${e.proposal}: `, h("strong", {}, e.label)]];
      case "proposal.dismissed":
        return ["proposal", [`dismissed proposal ${e.proposal}: `, h("strong", {}, e.label)]];
      case "proposal.withdrawn":
        return ["proposal", [`withdrawn proposal ${e.proposal}: `, h("strong", {}, e.label ?? "?"), e.reason ? ` (${e.reason})` : ""]];
      case "context.changed":
        return ["mark", [`context → ${e.context}`]];
      case "language.changed":
        return ["mark", [`language → ${e.language}`]];
      case "session.started":
        return ["mark", [`session ${e.session} started`]];
      case "session.ended":
        return ["mark", [`session ${e.session} ended`]];
      case "visitor.group":
        return ["mark", [`visitor group: ${e.group}`, e.context ? ` (context ${e.context})` : ""]];
      case "consent.changed":
        return ["mark", [`consent of session ${e.session}: `, h("strong", {}, e.consent)]];
      case "recording.deleted":
        return ["refused", [`recording of session ${e.session} deleted (consent ${e.consent}): ${deletedFiles(e)}`]];
      case "recording.failed":
        return ["refused", [`recording failed${e.client ? ` on kiosk #${e.client}` : ""} (${e.code}): `, e.message ?? ""]];
      case "situation.marked":
        return ["mark", [`situation: ${e.situation}`]];
      case "note.written":
        return ["mark", [`note: ${e.text}`]];
      case "robot":
        return ["mark", [`robot noticed: ${e.event}`, e.topic ? h("span", { class: "muted small" }, ` (${e.topic})`) : null]];
      case "topic.refused":
        return ["refused", [`robot message on ${e.topic} not used: `, e.reason]];
      case "reaction.failed":
        return ["refused", [`reaction ${e.reaction} (${e.event} → ${e.act}) did not run: `, e.reason]];
      case "fleet.link":
        return e.state === "up"
          ? ["mark", [`fleet broker ${e.broker}: connected`]]
          : ["refused", [`fleet broker ${e.broker}: link down (the fleet view cannot see or stop this robot): `, e.reason ?? ""]];
      default:
        return null;
    }
  }

  /** What a `recording.deleted` removed: "2 files, 1.4 MB" (the `.chunks` indexes not counted). */
  function deletedFiles(e) {
    const media = (e.files ?? []).filter((f) => !f.endsWith(".chunks"));
    if (media.length === 0) return "nothing had been stored";
    return `${media.length === 1 ? "1 file" : `${media.length} files`}, ${describeBytes(e.bytes ?? 0)} (${media.join(", ")})`;
  }

  /** Notes on an act's line that one of its commands was not carried out. */
  function notCarriedOut(e) {
    const act = list.querySelector(`li[data-type="act.triggered"][data-trigger="${Number(e.trigger)}"]`);
    if (!act) return; // scrolled out of the kept history
    const what = e.verb === "SAY" ? "not said" : `${e.verb} ${e.type === "command.failed" ? "failed" : "cancelled"}`;
    act.classList.add("not-carried-out");
    act.querySelector(".history-body").append(h("span", { class: "history-outcome" }, ` — ${what}: ${e.reason ?? ""}`));
  }

  return {
    welcome(id) {
      me = id;
      list.replaceChildren();
    },
    event(e) {
      if (e.type === "command.cancelled" || e.type === "command.failed") return notCarriedOut(e);
      const made = line(e);
      if (made) insert(e, e.type, ...made);
    },
    /** A line this console wrote about event `e` (a kiosk back after a lost connection). */
    note(e, type, text) {
      insert(e, type, "mark", [text]);
    },
  };

  /** One line for event `e`, in `seq` order. */
  function insert(e, type, kind, body) {
    const item = h(
      "li",
      { class: `history-item ${kind}`, dataset: { seq: String(e.seq), type, trigger: String(e.trigger ?? "") } },
      h("time", { datetime: e.time }, clock(e.time)),
      h("span", { class: "history-source" }, who(e)),
      h("span", { class: "history-body" }, body),
    );
    // Newest first by seq: a replayed event may arrive after a newer live one.
    let before = list.firstElementChild;
    while (before && Number(before.dataset.seq) > e.seq) before = before.nextElementSibling;
    list.insertBefore(item, before);
    while (list.childElementCount > KEEP) list.lastElementChild.remove();
  }
}
