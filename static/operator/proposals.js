// proposals.js: acts a dialog manager proposes (proposal.made events; pending ones also in
// GET /api/state `proposals`), newest first and hard to miss, each with its age ("12 s ago",
// kept up to date). F9 accepts the newest (the one that just arrived fits the moment best),
// Shift+F9 dismisses it, each has its own buttons too. A proposal leaves the list when any
// console accepts or dismisses it (proposal.accepted, proposal.dismissed) or when the server
// withdraws it because its dialog manager left (proposal.withdrawn).

import { clock, h, wrappableLabel } from "./dom.js";

const SETTLED = new Set(["proposal.accepted", "proposal.dismissed", "proposal.withdrawn"]);

/** How long ago, in words: "just now", "12 s ago", "3 min ago". */
export function age(ms) {
  const s = Math.max(0, Math.floor(ms / 1000));
  if (s < 1) return "just now";
  if (s < 60) return `${s} s ago`;
  const m = Math.floor(s / 60);
  return m < 60 ? `${m} min ago` : `${Math.floor(m / 60)} h ${m % 60} min ago`;
}

/**
 * @param {{panel: HTMLElement, list: HTMLElement,
 *          accept: (id: number) => void, dismiss: (id: number) => void,
 *          says: (label: string, context: string|null) => string|null,
 *          who: (client: number) => string, now?: () => number}} options `says`: the text the
 *          act would say, to show beside the proposal; `who`: a client's name; `now`: the
 *          server's clock in ms (events' `time` is the server's), by default this computer's.
 */
export function createProposals({ panel, list, accept, dismiss, says, who, now = () => Date.now() }) {
  const pending = new Map(); // id -> proposal (with `since`: when it was made, server ms)
  const settled = new Set(); // ids accepted, dismissed or withdrawn: a late snapshot must not revive them
  let ticker = null;

  const newestFirst = () => [...pending.values()].sort((a, b) => b.proposal - a.proposal);

  function render() {
    const items = newestFirst();
    panel.hidden = items.length === 0;
    list.replaceChildren(
      ...items.map((p, i) =>
        h(
          "li",
          { class: "proposal", dataset: { proposal: String(p.proposal), label: p.label } },
          h(
            "div",
            { class: "proposal-what" },
            h("strong", { class: "proposal-label" }, wrappableLabel(p.label)),
            p.context ? h("span", { class: "muted small" }, ` ${p.context}`) : null,
            p.reason ? h("span", { class: "proposal-reason" }, ` — ${p.reason}`) : null,
            h("div", { class: "proposal-text small" }, says(p.label, p.context) ?? ""),
            h(
              "div",
              { class: "muted small" },
              h("span", { class: "proposal-age", dataset: { since: String(p.since) } }, age(now() - p.since)),
              `${p.time ? ` (${clock(p.time)})` : ""} from ${who(p.client)}`,
            ),
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
    // The ages count on while proposals wait (only their text changes: a focused button stays).
    if (items.length && ticker === null) ticker = setInterval(tick, 1000);
    else if (!items.length && ticker !== null) {
      clearInterval(ticker);
      ticker = null;
    }
  }

  function tick() {
    for (const el of list.querySelectorAll(".proposal-age")) {
      const text = age(now() - Number(el.dataset.since));
      if (el.textContent !== text) el.textContent = text;
    }
  }

  function add(p) {
    if (typeof p?.proposal !== "number" || settled.has(p.proposal)) return;
    const old = pending.get(p.proposal);
    const made = Date.parse(p.time ?? "");
    const since = old?.since ?? (Number.isFinite(made) ? made : now());
    pending.set(p.proposal, { ...old, ...p, since });
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
      } else if (SETTLED.has(e.type)) {
        settled.add(e.proposal);
        pending.delete(e.proposal);
        render();
      }
    },
    /** Redraws (the acts arrived, so their texts can be shown). */
    refresh: render,
    /** The id of the newest pending proposal, or null. */
    newest() {
      return newestFirst()[0]?.proposal ?? null;
    },
  };
}
