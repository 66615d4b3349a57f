// language.js: the visitor's language as the console shows it (docs/AUTHORING.md, "Several
// languages"). One button per language, shown only when the bundle has more than one (GET
// /api/state `languages`, the default first); the pressed one is the server's language (from
// `welcome`, the snapshot and `language.changed`). Another one asks with a `language` frame:
// the pressed button changes only once the server says so, and the note beside the buttons says
// who set it when that was not this console (a visitor's button, a dialog manager, a session's
// end). Buttons, not a selector: Tab and Enter or Space choose, and the console's keys (arrows
// and letters go to the act search) leave them alone.

import { h } from "./dom.js";

/** The language's name in English for the button's tooltip (`de` → German), else the tag. */
function languageName(tag) {
  try {
    return new Intl.DisplayNames(["en"], { type: "language" }).of(tag) ?? tag;
  } catch {
    return tag;
  }
}

/**
 * @param {{group: HTMLElement, buttons: HTMLElement, note: HTMLElement,
 *          ask: (language: string) => void, onChange?: (language: string) => void}} options
 *          `group`: the labelled group, hidden with one language; `buttons`: where the buttons
 *          go; `ask`: sends the request; `onChange`: the server's language is now this one
 */
export function createLanguage({ group, buttons, note, ask, onChange = () => {} }) {
  let language = null;
  let asked = null; // the language this console asked for last, until the server confirms

  function set(tag) {
    if (!tag) return;
    language = tag;
    for (const button of buttons.children) button.setAttribute("aria-pressed", String(button.dataset.language === tag));
    onChange(tag);
  }

  return {
    /** The server's language (from `welcome`). */
    set,
    /** GET /api/state: the bundle's languages and the one in force. */
    snapshot(state) {
      const all = Array.isArray(state?.languages) ? state.languages.map(String) : [];
      group.hidden = all.length < 2;
      buttons.replaceChildren(...all.map((tag, i) => h(
        "button",
        {
          type: "button",
          class: "language",
          title: `${languageName(tag)}${i === 0 ? ", the default" : ""}`,
          dataset: { language: tag },
          "aria-pressed": "false",
          onclick: () => {
            asked = tag;
            ask(tag);
          },
        },
        tag,
      )));
      set(state?.language ?? language);
    },
    /** A `language.changed` event. */
    changed(e) {
      set(e.language);
      const mine = e.source === "operator" && e.language === asked;
      asked = null;
      note.textContent = mine ? "" : `set by ${e.source === "operator" ? "another console" : e.source}`;
    },
  };
}
