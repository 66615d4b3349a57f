// annotate.js: coding a session with the codebook. A code's key (or its button) starts an
// annotation at the playhead and the same key again ends it there (ended where it began, it is a
// point); Shift with the key (or button) marks a point at once; Escape drops what is not yet
// ended. Several codes may be open at once. Every annotation is saved through the API as soon as
// it is complete, and changed or deleted from the list below; a save that fails is shown at once
// with Docent's reason and a button to try it again, so nothing is lost without a word.

import { seconds } from "./timeline.js";

function el(tag, className, text) {
  const node = document.createElement(tag);
  if (className) node.className = className;
  if (text !== undefined) node.textContent = text;
  return node;
}

/**
 * @param {{codebook: HTMLElement, pending: HTMLElement, status: HTMLElement, error: HTMLElement,
 *          list: HTMLElement, count: HTMLElement, position: () => number,
 *          onSeek: (us: number) => void, save: (edit: object) => Promise<object>,
 *          onChange: (annotations: object[]) => void}} options `save`: POSTs an edit, resolves to
 *          the line saved or rejects with an ApiError
 */
export function createAnnotator({ codebook, pending, status, error, list, count, position, onSeek, save, onChange }) {
  let book = { tiers: [] };
  let annotations = [];
  /** Codes begun and not yet ended: "tier\0code" → start µs. */
  const open = new Map();

  function showPending() {
    const parts = [...open].map(([key, start]) => `${key.replace("\0", ": ")} from ${seconds(start)}`);
    pending.textContent = parts.length ? `Open (press the key again to end): ${parts.join("; ")}` : "";
    for (const button of codebook.querySelectorAll("button[data-code]")) {
      button.setAttribute("aria-pressed", String(open.has(`${button.dataset.tier}\0${button.dataset.code}`)));
    }
  }

  function replace(line) {
    annotations = annotations.filter((a) => a.id !== line.id);
    if (!line.deleted) annotations.push(line);
    annotations.sort((a, b) => a.start_us - b.start_us || a.tier.localeCompare(b.tier));
    renderList();
    onChange(annotations);
  }

  /** Sends `edit`; on failure says why and offers to try again. */
  async function send(edit, what) {
    error.hidden = true;
    status.textContent = `Saving ${what}…`;
    try {
      const line = await save(edit);
      replace(line);
      status.textContent = `Saved: ${what}.`;
    } catch (e) {
      status.textContent = "";
      error.replaceChildren(el("span", "", `Not saved: ${what}. ${e.message} (${e.code}) `));
      const retry = el("button", "", "Try again");
      retry.type = "button";
      retry.addEventListener("click", () => send(edit, what));
      error.append(retry);
      error.hidden = false;
    }
  }

  function add(tier, code, startUs, endUs) {
    const [start, end] = [Math.round(Math.min(startUs, endUs)), Math.round(Math.max(startUs, endUs))];
    const what = start === end ? `${tier}: ${code} at ${seconds(start)}` : `${tier}: ${code} ${seconds(start)} to ${seconds(end)}`;
    send({ action: "add", tier, code, start_us: start, end_us: end }, what);
  }

  /** A code pressed (key or button): begins, ends, or (as a point) marks at once. */
  function press(tier, code, point) {
    const now = position();
    const key = `${tier}\0${code}`;
    if (point) {
      add(tier, code, now, now);
    } else if (open.has(key)) {
      const start = open.get(key);
      open.delete(key);
      add(tier, code, start, now);
    } else {
      open.set(key, now);
    }
    showPending();
  }

  function renderCodebook() {
    codebook.replaceChildren();
    if (!book.tiers.length) {
      codebook.append(el("p", "hint", "The bundle has no codebook: add `codebook:` (or `operator: situations`) to its docent.yaml to annotate."));
    }
    for (const tier of book.tiers) {
      const group = el("div", "code-tier");
      group.setAttribute("role", "group");
      group.setAttribute("aria-label", `Tier ${tier.name}`);
      group.append(el("span", "tier-label", tier.name));
      for (const c of tier.codes) {
        const button = el("button", "code", c.key ? `${c.code} (${c.key})` : c.code);
        button.type = "button";
        button.dataset.tier = tier.name;
        button.dataset.code = c.code;
        button.setAttribute("aria-pressed", "false");
        if (c.key) button.setAttribute("aria-keyshortcuts", c.key);
        button.addEventListener("click", (event) => press(tier.name, c.code, event.shiftKey));
        group.append(button);
      }
      codebook.append(group);
    }
  }

  function renderList() {
    count.textContent = `(${annotations.length})`;
    list.replaceChildren();
    for (const a of annotations) {
      const tr = el("tr");
      tr.dataset.id = a.id;
      tr.append(el("td", "", a.tier));
      const codeCell = el("td");
      const select = el("select");
      select.setAttribute("aria-label", `Code of ${a.id}`);
      const codes = book.tiers.find((t) => t.name === a.tier)?.codes.map((c) => c.code) ?? [a.code];
      for (const code of codes.includes(a.code) ? codes : [a.code, ...codes]) {
        const option = el("option", "", code);
        option.value = code;
        option.selected = code === a.code;
        select.append(option);
      }
      select.addEventListener("change", () => change(a, { code: select.value }));
      codeCell.append(select);
      tr.append(codeCell);
      const at = el("button", "link", seconds(a.start_us));
      at.type = "button";
      at.setAttribute("aria-label", `Play from ${seconds(a.start_us)}`);
      at.addEventListener("click", () => onSeek(a.start_us));
      const startCell = el("td");
      startCell.append(at);
      tr.append(startCell, el("td", "", a.end_us === a.start_us ? "(point)" : seconds(a.end_us)), el("td", "", a.annotator ?? ""));
      const actions = el("td", "actions");
      const button = (text, label, onClick) => {
        const b = el("button", "", text);
        b.type = "button";
        b.setAttribute("aria-label", label);
        b.addEventListener("click", onClick);
        actions.append(b);
      };
      button("Start here", `Start ${a.id} at the playhead`, () => change(a, { start_us: Math.round(position()) }));
      button("End here", `End ${a.id} at the playhead`, () => change(a, { end_us: Math.round(position()) }));
      button("Delete", `Delete ${a.id}`, () => send({ action: "delete", id: a.id }, `deleting ${a.tier}: ${a.code}`));
      tr.append(actions);
      list.append(tr);
    }
  }

  function change(a, fields) {
    const next = { tier: a.tier, code: a.code, start_us: a.start_us, end_us: a.end_us, ...fields };
    if (next.end_us < next.start_us) [next.start_us, next.end_us] = [next.end_us, next.start_us];
    send({ action: "change", id: a.id, ...next }, `${a.tier}: ${next.code} ${seconds(next.start_us)}`);
  }

  function onKey(event) {
    if (event.ctrlKey || event.altKey || event.metaKey || document.querySelector("dialog[open]")) return;
    if (event.target.closest("input, select, textarea")) return;
    if (event.key === "Escape") {
      open.clear();
      showPending();
      return;
    }
    // Shift+1 is `!` on most layouts: a digit is read from the key's place.
    const digit = /^Digit(\d)$/.exec(event.code)?.[1];
    const key = digit ?? event.key.toLowerCase();
    for (const tier of book.tiers) {
      const c = tier.codes.find((code) => code.key === key);
      if (c) {
        event.preventDefault();
        press(tier.name, c.code, event.shiftKey);
        return;
      }
    }
  }
  document.addEventListener("keydown", onKey);

  return {
    /** Shows a session's codebook and annotations. */
    load(detail) {
      book = detail.codebook;
      annotations = [...detail.annotations];
      open.clear();
      error.hidden = true;
      status.textContent = "";
      renderCodebook();
      renderList();
      showPending();
    },
  };
}
