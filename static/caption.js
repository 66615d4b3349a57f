// caption.js: the kiosk's caption of what the robot says, while it says it. Docent sends a
// `caption` frame when a SAY starts on the speech device and when it ends (docs/PROTOCOL.md);
// the text is the one spoken. The caption is shown in the page on show (overlay.js: styled by
// the bundle's CSS as `.docent-caption`, placed where it hides no control) with
// `aria-live="polite"`, so screen readers read it too. A page opts out with
// <meta name="docent-captions" content="off">; a bundle turns captions off in docent.yaml
// (`captions: kiosk: false`, then Docent sends none). A page may place the caption itself: an
// element with `data-docent-caption` gets the text instead. Pages may also follow the
// `caption` frames with docent.on("caption", ...).

import { overlayElement, place } from "./overlay.js";

/**
 * @param {{documents: () => {page: Document|null, shell: Document}, avoid: () => DOMRect[]}} options
 *        `documents`: the shown page's document (null when it cannot be reached) and the
 *        shell's; `avoid`: the shell's own controls on screen.
 */
export function captions({ documents, avoid }) {
  let text = null; // the caption in force, or null

  function optedOut(doc) {
    return Boolean(doc.querySelector('meta[name="docent-captions" i][content="off" i]'));
  }

  function hideIn(doc) {
    const shown = doc?.querySelector(".docent-caption[data-docent-overlay], [data-docent-caption]");
    if (!shown) return;
    shown.textContent = "";
    if (shown.dataset.docentOverlay !== undefined) shown.hidden = true;
  }

  function render() {
    const { page, shell } = documents();
    const doc = page ?? shell;
    if (doc !== shell) hideIn(shell);
    if (!text || optedOut(doc)) return hideIn(doc);
    const attributes = { role: "status", "aria-live": "polite" };
    const { element, own } = overlayElement(doc, "docent-caption", "data-docent-caption", attributes);
    element.textContent = text;
    if (own) return;
    element.hidden = false;
    place(element, doc, avoid());
  }

  addEventListener("resize", () => text && render());

  return {
    /** A `caption` frame from Docent. */
    onFrame(frame) {
      text = typeof frame.text === "string" && frame.text.trim() ? frame.text : null;
      render();
    },
    /** Another page is on show: the caption in force moves there. */
    page: render,
    /** The connection is lost: nothing is known to be said until Docent says so again. */
    forget() {
      text = null;
      render();
    },
  };
}
