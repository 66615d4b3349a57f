// caption.js: the console's caption line beside Stop: what the robot is saying now, as the
// visitors read it in the kiosk's caption, from Docent's `caption` frames (sent from the
// speech device's start to its end, docs/PROTOCOL.md). Each welcome starts it empty: Docent
// then sends the caption in force, if any.

/** @param {HTMLElement} element the line; its `data-state` is `speaking` or `silent`. */
export function createCaptionLine(element) {
  function show(text) {
    element.dataset.state = text ? "speaking" : "silent";
    element.textContent = text ? `“${text}”` : "–";
    element.title = text ?? "";
  }
  show(null);
  return {
    /** Takes every frame; uses `welcome` and `caption`. */
    onFrame(frame) {
      if (frame.type === "welcome") show(null);
      else if (frame.type === "caption") show(typeof frame.text === "string" ? frame.text : null);
    },
  };
}
