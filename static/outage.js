// outage.js: what visitors see while Docent is away. After a second without the server (a
// blip passes unseen) a calm notice appears in the page on show, styled by the bundle's CSS
// as `.docent-offline-notice` and placed where it hides none of the page's controls
// (overlay.js), in the page's language (the shell's table, shell-text.js); a page may write
// its own, in its own words, as an element with `data-docent-offline` (hidden; the shell
// shows it). A tap on a control meanwhile (a
// `data-act` element, a link, a button) is answered at once: the control gets
// `data-docent-busy` for a moment and the notice shows. The tap does nothing else: nothing
// is queued to fire later and no link leads to a page the server cannot send. Once Docent
// is back (its welcome), the notice and the busy marks go.

import { overlayElement, place } from "./overlay.js";

const NOTICE_AFTER_MS = 1_000;
const BUSY_MS = 1_500;
const CONTROLS = "[data-act], [data-docent-stop], a[href], button, [role=button]";
/**
 * @param {{documents: () => {page: Document|null, shell: Document}, avoid: () => DOMRect[],
 *          words: (key: string, doc: Document) => {text: string, lang: string}}} options
 *          `words`: the shell's words (shell-text.js), here the notice in the language of the
 *          page on show (its `<html lang>`): a German visitor on a German page is not told in
 *          English
 */
export function outage({ documents, avoid, words }) {
  let online = false;
  let noticeTimer = null;
  let noticeShown = false;
  const busy = new Set(); // elements marked busy

  function showNotice() {
    clearTimeout(noticeTimer);
    noticeTimer = null;
    noticeShown = true;
    const { page, shell } = documents();
    const doc = page ?? shell;
    const attributes = { role: "status", "aria-live": "polite" };
    const { element, own } = overlayElement(doc, "docent-offline-notice", "data-docent-offline", attributes);
    if (!own && !element.textContent) {
      const { text, lang } = words("one_moment", doc);
      element.textContent = text;
      element.lang = lang;
    }
    element.hidden = false;
    if (!own) place(element, doc, avoid());
  }

  function hideNotice() {
    clearTimeout(noticeTimer);
    noticeTimer = null;
    noticeShown = false;
    const { page, shell } = documents();
    for (const doc of [page, shell]) {
      for (const element of doc?.querySelectorAll(".docent-offline-notice[data-docent-overlay], [data-docent-offline]") ?? []) {
        element.hidden = true;
      }
    }
  }

  function markBusy(element) {
    element.dataset.docentBusy = "";
    busy.add(element);
    setTimeout(() => {
      delete element.dataset.docentBusy;
      busy.delete(element);
    }, BUSY_MS);
  }

  /** A tap while Docent is away: the control says "one moment"; nothing fires. */
  function tapped(event) {
    if (online) return;
    const control = event.target.closest?.(CONTROLS);
    if (!control) return;
    event.preventDefault();
    event.stopImmediatePropagation();
    if (event.type === "click") return;
    markBusy(control);
    showNotice();
  }

  return {
    /** The connection came (true, a welcome) or went (false). */
    online(now) {
      online = now;
      if (now) {
        hideNotice();
        for (const element of busy) delete element.dataset.docentBusy;
        busy.clear();
      } else {
        noticeTimer ??= setTimeout(showNotice, NOTICE_AFTER_MS);
      }
    },
    /** Whether Docent is there. */
    isOnline: () => online,
    /** A page is on show (its window `view`): taps there are answered while offline. */
    watch(view) {
      try {
        // On the window, capturing: before the page script's own handlers on its document.
        view.addEventListener("pointerdown", tapped, { capture: true });
        view.addEventListener("click", tapped, { capture: true });
      } catch (error) {
        console.warn("docent: cannot watch taps in the page", error);
      }
      if (noticeShown) showNotice();
    },
    /** Starts the wait for a first connection: no page is shown until Docent answers. */
    start() {
      if (!online) noticeTimer ??= setTimeout(showNotice, NOTICE_AFTER_MS);
    },
  };
}
