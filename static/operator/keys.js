// keys.js: the console's keyboard, one listener for the whole page. Esc is always Stop, even
// inside a text field. Typing anywhere goes into the search; Up/Down choose among the acts,
// Enter fires the chosen one (Shift+Enter interrupting speech), Alt+<key> fires the act with
// that `Key`, F2 repeats the last act, F4 stars the chosen act, F9 accepts the oldest
// proposal and Shift+F9 dismisses it, Alt+Shift+1..9 mark a situation.

/**
 * @param {{search: HTMLInputElement, active: () => boolean, stop: () => void,
 *          fire: (options: {interrupt: boolean}) => boolean, move: (delta: number) => void,
 *          repeat: () => void, favourite: () => void, accept: () => void,
 *          dismiss: () => void, actKey: (key: string) => boolean,
 *          situation: (n: number) => boolean, typed: () => void}} handlers `active`: whether
 *          the console is signed in; `typed`: the search text changed.
 */
export function bindKeys(handlers) {
  const { search } = handlers;

  const editable = (el) =>
    el instanceof HTMLSelectElement || el instanceof HTMLTextAreaElement || (el instanceof HTMLInputElement && el !== search);

  addEventListener(
    "keydown",
    (event) => {
      if (!handlers.active() || event.isComposing) return;
      const target = event.target;
      const done = () => {
        event.preventDefault();
        event.stopPropagation();
      };
      const plain = !event.ctrlKey && !event.metaKey && !event.altKey;

      if (event.key === "Escape") {
        done();
        handlers.stop();
        return;
      }
      if (event.key === "F2" && plain) return done(), handlers.repeat();
      if (event.key === "F4" && plain) return done(), handlers.favourite();
      if (event.key === "F9" && !event.ctrlKey && !event.metaKey && !event.altKey) {
        done();
        if (event.shiftKey) handlers.dismiss();
        else handlers.accept();
        return;
      }
      if (event.altKey && !event.ctrlKey && !event.metaKey) {
        // By physical key (event.code), so Alt combinations work on every layout and OS.
        const digit = /^(?:Digit|Numpad)([0-9])$/.exec(event.code)?.[1];
        const letter = /^Key([A-Z])$/.exec(event.code)?.[1];
        if (event.shiftKey && digit && digit !== "0") {
          if (handlers.situation(Number(digit))) done();
          return;
        }
        if (!event.shiftKey && (digit || letter)) {
          if (handlers.actKey(digit ?? letter)) done();
          return;
        }
        return;
      }
      if (editable(target)) return;

      if ((event.key === "ArrowDown" || event.key === "ArrowUp") && plain) {
        done();
        handlers.move(event.key === "ArrowDown" ? 1 : -1);
        return;
      }
      if (event.key === "Enter" && !event.ctrlKey && !event.metaKey && !event.altKey) {
        // A focused button handles its own Enter (a click); elsewhere Enter fires the choice.
        if (target instanceof HTMLButtonElement) return;
        if (handlers.fire({ interrupt: event.shiftKey })) done();
        return;
      }
      if (target === search) return;
      // Type-to-search: a printable key (or Backspace) anywhere else goes into the search.
      if (target instanceof HTMLButtonElement && (event.key === " " || event.key === "Enter")) return;
      if (plain && (event.key.length === 1 || event.key === "Backspace")) {
        done();
        search.focus();
        search.value = event.key === "Backspace" ? search.value.slice(0, -1) : search.value + event.key;
        handlers.typed();
      }
    },
    { capture: true },
  );
}
