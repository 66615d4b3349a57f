// proposals.js: acts a dialog manager proposes (proposal.made events; pending ones also in
// GET /api/state `proposals`), oldest first and hard to miss. F9 accepts the oldest, Shift+F9
// dismisses it, each has its own buttons too. A proposal leaves the list when any console
// accepts or dismisses it (proposal.accepted, proposal.dismissed).

import { clock, h } from "./dom.js";

/**
 * @param {{panel: HTMLElement, list: HTMLElement,
 *          accept: (id: number) => void, dismiss: (id: number) => void,
 *          says: (label: string, context: string|null) => string|null,
 *          who: (client: number) => string}} options `says`: the text the act would say, to
 *          show beside the proposal; `who`: a client's name.
 */
export function createProposals({ panel, list, accept, dismiss, says, who }) {
  const pending = new Map(); // id -> proposal
  const settled = new Set(); // ids accepted or dismissed: a late snapshot must not revive them

  function render() {
    const items = [...pending.values()].sort((a, b) => a.proposal - b.proposal);
    panel.hidden = items.length === 0;
    list.replaceChildren(
      ...items.map((p, i) =>
        h(
          "li",
          { class: "proposal", dataset: { proposal: String(p.proposal), label: p.label } },
          h(
            "div",
            { class: "proposal-what" },
            h("strong", { class: "proposal-label" }, p.label),
            p.context ? h("span", { class: "muted small" }, ` ${p.context}`) : null,
            p.reason ? h("span", { class: "proposal-reason" }, ` — ${p.reason}`) : null,
            h("div", { class: "proposal-text small" }, says(p.label, p.context) ?? ""),
            h("div", { class: "muted small" }, `${p.time ? clock(p.time) : ""} from ${who(p.client)}`),
          ),
          h(
            "div",
            { class: "proposal-actions" },
            h("button", { type: "button", class: "accept", onclick: () => accept(p.proposal) }, "Accept", i === 0 ? h("kbd", {}, "F9") : null),
            h("button", { type: "button", class: "dismiss", onclick: () => dismiss(p.proposal) }, "Dismiss", i === 0 ? h("kbd", {}, "Shift+F9") : null),
          ),
        ),
      ),
    );
  }

  function add(p) {
    if (typeof p?.proposal !== "number" || settled.has(p.proposal)) return;
    pending.set(p.proposal, { ...pending.get(p.proposal), ...p });
  }

  return {
    welcome() {
      pending.clear();
      settled.clear();
      render();
    },
    /** GET /api/state `proposals`: an array (or an object by id) of pending proposals. */
    snapshot(proposals) {
      const items = Array.isArray(proposals) ? proposals : Object.entries(proposals ?? {}).map(([id, p]) => ({ proposal: Number(id), ...p }));
      for (const p of items) add(p);
      render();
    },
    event(e) {
      if (e.type === "proposal.made") {
        add({ proposal: e.proposal, client: e.client, label: e.label, context: e.context ?? null, reason: e.reason ?? null, time: e.time });
        render();
      } else if (e.type === "proposal.accepted" || e.type === "proposal.dismissed") {
        settled.add(e.proposal);
        pending.delete(e.proposal);
        render();
      }
    },
    /** Redraws (the acts arrived, so their texts can be shown). */
    refresh: render,
    /** The id of the oldest pending proposal, or null. */
    oldest() {
      const ids = [...pending.keys()];
      return ids.length ? Math.min(...ids) : null;
    },
  };
}
