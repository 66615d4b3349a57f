// caption.js: the console's caption line beside Stop: what the robot is saying now, as the
// visitors read it in the kiosk's caption. It follows the same events Docent captions by
// (docs/PROTOCOL.md, `caption`): a SAY's text from its `command.sent`, shown from its
// `command.started` to its end (`command.done`, `failed`, `cancelled`). Each welcome starts
// it empty: the recent history that follows replays a SAY still being said.

const ENDED = new Set(["command.done", "command.failed", "command.cancelled"]);

/** @param {HTMLElement} element the line; its `data-state` is `speaking` or `silent`. */
export function createCaptionLine(element) {
  const texts = new Map(); // SAY command id -> text, from command.sent until it ends
  let shown = null; // the id of the SAY being said

  function show(text) {
    element.dataset.state = text ? "speaking" : "silent";
    element.textContent = text ? `“${text}”` : "–";
    element.title = text ?? "";
  }

  function onEvent(e) {
    if (e.type === "command.sent" && e.verb === "SAY") {
      texts.set(e.command, e.args?.text ?? e.arg ?? "");
    } else if (e.type === "command.started" && texts.has(e.command)) {
      shown = e.command;
      show(texts.get(e.command));
    } else if (ENDED.has(e.type)) {
      texts.delete(e.command);
      if (e.command !== shown) return;
      shown = null;
      show(null);
    }
  }

  show(null);
  return {
    /** Takes every frame; uses `welcome` and the `event` frames. */
    onFrame(frame) {
      if (frame.type === "welcome") {
        texts.clear();
        shown = null;
        show(null);
      } else if (frame.type === "event" && frame.event) {
        onEvent(frame.event);
      }
    },
  };
}
