// context.js: the shared context (which variant of the texts the robot says: Text, TextChild...)
// as the console shows it. The selector shows the server's context and asks for another one: it
// changes only once the server says so (`context.changed`), and the note beside it says who set
// it when that was not this console.

import { h } from "./dom.js";

/**
 * @param {{select: HTMLSelectElement, note: HTMLElement, list: {setContext: (name: string) => void},
 *          ask: (context: string) => void}} options `list`: the act list, which shows the
 *          context's texts; `ask`: sends the request for another context
 */
export function createContext({ select, note, list, ask }) {
  let context = "Text";
  let asked = null; // the context this console asked for last, until the server confirms

  function set(name) {
    if (!name || name === context) return;
    context = name;
    if (![...select.options].some((o) => o.value === name)) select.append(h("option", { value: name }, name));
    select.value = name;
    list.setContext(name);
  }

  select.addEventListener("change", () => {
    const wanted = select.value;
    select.value = context; // shown once the server says it changed
    asked = wanted;
    ask(wanted);
    // Chosen: let go of the focus, so that typing goes to the search and not into the selector.
    select.blur();
  });

  return {
    /** The context of the moment. */
    current: () => context,
    /** The server's context (from `welcome`). */
    set,
    /** This console asked for `name` another way (a visitor group); null or undefined: it did not. */
    expect(name) {
      asked = name ?? asked;
    },
    /** A `context.changed` event. */
    changed(e) {
      set(e.context);
      // Events do not say which operator changed it: one this console asked for is its own.
      const mine = e.source === "operator" && e.context === asked;
      asked = null;
      note.textContent = mine ? "" : `set by ${e.source === "operator" ? "another console" : e.source}`;
    },
    /** The bundle's contexts (GET /api/acts) to choose from, the current one chosen. */
    options(contexts) {
      select.replaceChildren(...contexts.map((c) => h("option", { value: c }, c)));
      select.value = context;
      select.disabled = false;
    },
  };
}
