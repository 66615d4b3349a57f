// preview.js: the chosen act before it is fired: its label, group and key, every text it may
// say in the current context (the server picks one at random, never the same twice in a row;
// a context the act has no variant for falls back to Text) in the visitor's language (marked
// when the act has no text in it and says another language's), and its commands in order.

import { commandText, languageNote, textsFor } from "./acts.js";
import { h } from "./dom.js";

/** Shows `act` (or a hint when null) in `element` for `context` and the visitor's `language`. */
export function showPreview(element, act, context, language = null) {
  if (!act) {
    element.replaceChildren(h("p", { class: "muted" }, "Type a word, or press ↑ ↓ to choose an act."));
    return;
  }
  const said = textsFor(act, context, language);
  const note = languageNote(said);
  const variantNote = !said.variant
    ? "says nothing"
    : said.fallback
      ? `no ${context} text: says Text`
      : said.variant;
  element.replaceChildren(
    h(
      "div",
      { class: "preview-head" },
      h("strong", { class: "preview-label" }, act.label),
      act.key ? h("kbd", {}, `Alt+${act.key}`) : null,
      h("span", { class: "muted small" }, ` ${act.group} · ${act.file}`),
    ),
    h(
      "p",
      { class: "preview-variant small" },
      variantNote,
      said.texts.length > 1 ? ` · one of ${said.texts.length}` : "",
      // The language said, where the bundle has several.
      said.language && act.languages.get(said.variant)?.size > 1 ? ` · ${said.language}` : "",
    ),
    ...(note ? [h("p", { class: "preview-language small" }, `(${note})`)] : []),
    // replaceChildren writes a null as "null": leave absent parts out.
    ...(said.texts.length ? [h("ul", { class: "preview-texts" }, said.texts.map((t) => h("li", {}, t)))] : []),
    act.commands.length
      ? h("ol", { class: "preview-commands" }, act.commands.map((c) => h("li", {}, h("code", {}, commandText(c)))))
      : h("p", { class: "muted small" }, "no commands"),
    h("p", { class: "muted small" }, "Enter fires · Shift+Enter interrupts current speech"),
  );
}
