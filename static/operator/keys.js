// keys.js: the console's keyboard, one listener for the whole page. Esc is always Stop, even
// inside a text field, during an IME composition and before the console is connected. Typing
// anywhere goes into the search, also while a button or a selector has the focus (a selector
// would otherwise take the letters and arrows as a choice: the context, a kiosk). Up/Down
// choose among the acts, Enter fires the chosen one (Shift+Enter interrupting speech): with a
// search typed or after Up/Down it always fires the choice, never a button that happens to have
// the focus. Alt+<key> fires the act with that `Key`, F2 repeats the last act, F4 stars the
// chosen act, F9 accepts the newest proposal and Shift+F9 dismisses it, Alt+Shift+1..9 mark a
// situation, Alt+Shift+N goes to the note field. A held key's auto-repeat fires nothing again (Esc excepted: stopping twice is
// harmless).

/**
 * @param {{search: HTMLInputElement, active: () => boolean, stop: () => void,
 *          fire: (options: {interrupt: boolean}) => boolean, move: (delta: number) => void,
 *          repeat: () => void, favourite: () => void, accept: () => void,
 *          dismiss: () => void, actKey: (key: string, options: {repeat: boolean}) => boolean,
 *          situation: (n: number, options: {repeat: boolean}) => boolean,
 *          note: () => void,
 *          typed: () => void}} handlers `active`: whether the console takes keys (signed in,
 *          no dialog open); `actKey` and `situation` say whether the key is bound and act only
 *          when it is not a `repeat`; `typed`: the search text changed.
 */
export function bindKeys(handlers) {
  const { search } = handlers;
  // Whether Enter fires the choice wherever the focus is: set by Up/Down, cleared by a fire, by
  // Tab (the operator moves the focus on purpose) and by the mouse.
  let armed = false;

  /** A field the operator types into that is not the search: its keys are its own. */
  const textField = (el) =>
    el instanceof HTMLTextAreaElement ||
    (el instanceof HTMLElement && el.isContentEditable) ||
    (el instanceof HTMLInputElement && el !== search && !["button", "checkbox", "radio", "range", "reset", "submit"].includes(el.type));

  addEventListener("pointerdown", () => (armed = false), { capture: true });

  addEventListener(
    "keydown",
    (event) => {
      const target = event.target;
      const done = () => {
        event.preventDefault();
        event.stopPropagation();
      };
      const plain = !event.ctrlKey && !event.metaKey && !event.altKey;

      // Stop first of all: in every state, also while an IME composes and before sign-in.
      if (event.key === "Escape") {
        done();
        handlers.stop();
        return;
      }
      if (!handlers.active() || event.isComposing || event.keyCode === 229) return;
      if (event.key === "Tab") {
        armed = false;
        return;
      }

      if (event.key === "F2" && plain) return done(), event.repeat || handlers.repeat();
      if (event.key === "F4" && plain) return done(), event.repeat || handlers.favourite();
      if (event.key === "F9" && plain) {
        done();
        if (event.repeat) return;
        if (event.shiftKey) handlers.dismiss();
        else handlers.accept();
        return;
      }
      if (event.altKey && !event.ctrlKey && !event.metaKey) {
        // By physical key (event.code), so Alt combinations work on every layout and OS.
        const digit = /^(?:Digit|Numpad)([0-9])$/.exec(event.code)?.[1];
        const letter = /^Key([A-Z])$/.exec(event.code)?.[1];
        if (event.shiftKey && digit && digit !== "0") {
          if (handlers.situation(Number(digit), { repeat: event.repeat })) done();
        } else if (event.shiftKey && letter === "N") {
          done();
          handlers.note();
        } else if (!event.shiftKey && (digit || letter)) {
          if (handlers.actKey(digit ?? letter, { repeat: event.repeat })) done();
        }
        return;
      }
      if (textField(target)) return;

      if ((event.key === "ArrowDown" || event.key === "ArrowUp") && plain) {
        done();
        armed = true;
        handlers.move(event.key === "ArrowDown" ? 1 : -1);
        return;
      }
      if (event.key === "Enter" && plain) {
        // With a search typed or after Up/Down, Enter is the chosen act's, wherever the focus
        // is; otherwise a control the operator tabbed to (a button, a proposal's Accept) takes
        // its own Enter.
        const forChoice = armed || search.value.trim() !== "";
        const control = target instanceof HTMLButtonElement || target instanceof HTMLSelectElement || target instanceof HTMLAnchorElement;
        if (!forChoice && control) return;
        done();
        if (event.repeat) return;
        if (handlers.fire({ interrupt: event.shiftKey })) armed = false;
        return;
      }
      if (target === search || !plain) return;
      // Space on a focused button or selector is its own, unless a search is being typed.
      if (event.key === " " && search.value === "" && target instanceof Element && target.matches("button, select, a")) return;
      // Type-to-search: a printable key (or Backspace) anywhere else goes into the search.
      if (event.key.length === 1 || event.key === "Backspace") {
        done();
        search.focus();
        search.value = event.key === "Backspace" ? search.value.slice(0, -1) : search.value + event.key;
        handlers.typed();
      }
    },
    { capture: true },
  );
}
