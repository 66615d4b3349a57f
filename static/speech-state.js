// speech-state.js: what the kiosk shell shows of the robot's speech. While it speaks, the
// shell's <body> and the shown page's <html> carry `data-docent-speaking` with who asked for
// it (`kiosk` for visitors, `operator`, `dm`, `http`), so a bundle page can style itself; the
// "Stop speaking" button shows only while visitors' own speech runs (Docent refuses a kiosk's
// stop for anyone else's). A tap on an act already speaking, or a visitor's speech that will
// not be said (`outcome` frames), is answered with a short notice: never silently ignored.
// The button's label and the notices are in the shown page's language (`words`,
// shell-text.js).

const NOTICE_MS = 3_000;

/**
 * The state of one shell: `button` and `notice` are its elements, `stop()` asks Docent,
 * `words(key, doc)` gives the shell's words for the page on show (shell-text.js).
 */
export function speechState({ button, notice, stop, words }) {
  let shownDoc = null; // the document of the page on show, for its language
  let speaking = null; // the `speaking` frame in force, or null
  let noticeTimer = null;

  function mark(element) {
    if (!element) return;
    if (speaking) element.dataset.docentSpeaking = speaking.source ?? "robot";
    else delete element.dataset.docentSpeaking;
  }

  let pageStops = false; // the shown page offers its own stop control (data-docent-stop)

  function markPage(frame) {
    try {
      shownDoc = frame?.contentDocument ?? null;
      mark(frame?.contentDocument?.documentElement);
      pageStops = Boolean(frame?.contentDocument?.querySelector("[data-docent-stop]"));
    } catch {
      // a page of another origin (the friendly offline copy) cannot be marked
      shownDoc = null;
      pageStops = false;
    }
    label();
    showButton();
  }

  /** The button says "Stop speaking" in the shown page's language. */
  function label() {
    if (!button) return;
    const { text, lang } = words("stop", shownDoc);
    button.textContent = text;
    button.lang = lang;
  }

  function showButton() {
    if (button) button.hidden = !(speaking && speaking.stoppable) || pageStops;
  }

  /** Shows the shell's words for `key` (shell-text.js) in the shown page's language. */
  function say(key) {
    if (!notice) return;
    const { text, lang } = words(key, shownDoc);
    notice.textContent = text;
    notice.lang = lang;
    notice.hidden = false;
    clearTimeout(noticeTimer);
    noticeTimer = setTimeout(() => {
      notice.hidden = true;
    }, NOTICE_MS);
  }

  button?.addEventListener("click", () => stop());
  label();

  return {
    markPage,
    /** Shows a short notice by its key (also language.js's refusals). */
    say,
    /** The connection is gone: nothing is known to speak until Docent says so again. */
    forget(shown) {
      speaking = null;
      mark(document.body);
      markPage(shown);
    },
    /** Takes a server frame; `shown` is the frame on show. */
    onFrame(frame, shown) {
      if (frame.type === "speaking") {
        speaking = frame.speaking ? frame : null;
        mark(document.body);
        markPage(shown);
      } else if (frame.type === "error" && frame.code === "already-speaking") {
        say("already_speaking");
      } else if (frame.type === "outcome" && frame.verb === "SAY" && !frame.ended_by_visitor) {
        // Speech a visitor asked for that will not come (a full queue, the operator took over);
        // what the visitor ended themselves (stop, leaving the page) needs no word.
        say("cannot_say");
      }
    },
  };
}
