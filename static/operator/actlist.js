// actlist.js: the act buttons. Without a search: favourites, recently used, then every act by
// group. With a search: the matches, best first, the first one chosen, each showing the text
// that matched with the query's words marked. Up/Down move the choice, and so does the focus
// (Tab, a click): the chosen act is the one the preview shows and the one Enter fires; hovering
// chooses nothing. A redraw (the context, a star, recently used) keeps the choice on the same
// act while it is still listed; a changed search chooses its best match. A click fires (Shift
// interrupts current speech); the star keeps an act among the favourites. Texts are shown in
// the visitor's language (`setLanguage`); an act without a text in it shows what the robot
// says instead, marked (`English: no German text`).

import { groupActs, languageNote, textsFor } from "./acts.js";
import { h, shorten, wrappableLabel } from "./dom.js";
import { highlight, indexActs, search } from "./search.js";
import * as store from "./store.js";

/**
 * @param {{element: HTMLElement, count: HTMLElement,
 *          onFire: (act: object, options: {interrupt: boolean}) => void,
 *          onPreview: (act: object|null) => void}} options `onPreview` gets the chosen act
 *          (or null) whenever the choice or its text may have changed.
 */
export function createActList({ element, count, onFire, onPreview }) {
  let acts = [];
  let byLabel = new Map();
  let index = [];
  let context = "Text";
  let language = null; // the visitor's language; null: the bundle's default
  let query = "";
  let rows = []; // [{act, button}] in screen order
  let chosen = -1;

  const tellPreview = () => onPreview(rows[chosen]?.act ?? null);

  /** Makes row `i` the choice. */
  function choose(i) {
    if (i === chosen) return;
    chosen = i;
    mark();
  }

  function button(act, match) {
    const said = textsFor(act, context, language);
    // The mark goes with the texts the robot says, not with another text a search matched.
    const note = !match?.text || said.texts.includes(match.text) ? languageNote(said) : null;
    const text = match?.text ?? said.texts[0] ?? (act.commands[0] ? act.commands.map((c) => c.verb).join(" ") : "");
    const pieces = match ? highlight(text, query) : [{ text: shorten(text, 90), hit: false }];
    const fav = store.isFavourite(act.label);
    const fire = h(
      "button",
      {
        type: "button",
        class: "act",
        dataset: { label: act.label },
        title: [note, ...said.texts].filter(Boolean).join("\n") || undefined,
        "aria-keyshortcuts": act.key ? `Alt+${act.key}` : null,
        onclick: (event) => onFire(act, { interrupt: event.shiftKey }),
        // Tab (or a click) to a button chooses it: Enter then fires what the preview shows.
        onfocus: () => choose(rows.findIndex((r) => r.button === fire)),
      },
      h("span", { class: "act-label" }, wrappableLabel(act.label)),
      act.key ? h("kbd", { class: "act-key" }, `Alt+${act.key}`) : null,
      h(
        "span",
        { class: "act-text" },
        note ? h("span", { class: "act-language muted" }, `(${note}) `) : null,
        pieces.map((p) => (p.hit ? h("mark", {}, p.text) : p.text)),
      ),
    );
    const star = h(
      "button",
      {
        type: "button",
        class: "star",
        "aria-pressed": String(fav),
        "aria-label": `Favourite ${act.label}`,
        title: "Favourite (F4 for the chosen act)",
        onclick: () => {
          store.toggleFavourite(act.label);
          render();
        },
      },
      fav ? "★" : "☆",
    );
    const row = h("li", { class: "act-row" }, fire, star);
    rows.push({ act, button: fire });
    return row;
  }

  function section(title, items, extra = {}) {
    return h(
      "section",
      { class: `act-group ${extra.class ?? ""}` },
      h("h3", {}, title, h("span", { class: "muted small" }, ` ${items.length}`)),
      h("ul", { class: "act-grid" }, items.map((item) => button(item.act ?? item, item.act ? item : null))),
    );
  }

  /**
   * Redraws. `newQuery`: the search text changed, so its best match is chosen (none without a
   * search); otherwise the same act stays chosen while it is listed, on the same row when it is
   * listed twice (a favourite is also in its group).
   */
  function render({ newQuery = false } = {}) {
    const keep = newQuery ? null : rows[chosen]?.act?.label ?? null;
    const keepAt = chosen;
    rows = [];
    const parts = [];
    const searching = Boolean(query.trim());
    if (searching) {
      const matches = search(index, query, context, language);
      count.textContent = matches.length === 1 ? "1 match" : `${matches.length} matches`;
      if (matches.length) parts.push(section("Matches", matches, { class: "matches" }));
      else parts.push(h("p", { class: "muted empty" }, "No act matches. Esc still stops."));
    } else {
      count.textContent = `${acts.length} acts`;
      const favs = store.favourites().map((l) => byLabel.get(l)).filter(Boolean);
      const recent = store.recent().map((l) => byLabel.get(l)).filter(Boolean);
      if (favs.length) parts.push(section("★ Favourites", favs, { class: "favourites" }));
      if (recent.length) parts.push(section("Recently used", recent, { class: "recent" }));
      for (const [group, members] of groupActs(acts)) parts.push(section(group, members));
    }
    const kept = keep === null ? -1 : rows[keepAt]?.act.label === keep ? keepAt : rows.findIndex((r) => r.act.label === keep);
    // Else a search chooses its best match; the plain list chooses nothing until Up/Down.
    chosen = kept !== -1 ? kept : searching && rows.length ? 0 : -1;
    element.replaceChildren(...parts);
    mark();
  }

  function mark() {
    for (const [i, row] of rows.entries()) {
      row.button.classList.toggle("chosen", i === chosen);
      if (i === chosen) row.button.setAttribute("aria-current", "true");
      else row.button.removeAttribute("aria-current");
    }
    rows[chosen]?.button.scrollIntoView({ block: "nearest" });
    tellPreview();
  }

  return {
    setActs(list) {
      acts = list;
      byLabel = new Map(acts.map((a) => [a.label, a]));
      index = indexActs(acts);
      render();
    },
    setContext(name) {
      context = name;
      render();
    },
    /** The visitor's language changed: texts (and the search's ranking) follow it. */
    setLanguage(tag) {
      if (tag === language) return;
      language = tag;
      render();
    },
    /** The visitor's language, as the list shows it (null: the default). */
    language: () => language,
    setQuery(text) {
      if (text === query) return;
      query = text;
      render({ newQuery: true });
    },
    /** Redraws (favourites or recently used changed), keeping the choice. */
    refresh: () => render(),
    /** Moves the choice by `delta` rows; focuses the chosen button when `focus`. */
    move(delta, { focus = false } = {}) {
      if (!rows.length) return;
      choose(chosen === -1 ? (delta > 0 ? 0 : rows.length - 1) : (chosen + delta + rows.length) % rows.length);
      if (focus) rows[chosen].button.focus();
    },
    /** The chosen act, or null. */
    chosen: () => rows[chosen]?.act ?? null,
    /** The act with this label. */
    act: (label) => byLabel.get(label) ?? null,
    /** The act bound to `key` (A-Z, 0-9). */
    byKey: (key) => acts.find((a) => a.key === key) ?? null,
    /** Briefly marks the buttons of `label` as fired. */
    flash(label) {
      for (const row of rows) {
        if (row.act.label !== label) continue;
        row.button.classList.remove("fired");
        void row.button.offsetWidth; // restart the animation
        row.button.classList.add("fired");
      }
    },
  };
}
