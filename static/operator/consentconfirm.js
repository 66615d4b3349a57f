// consentconfirm.js: asks the operator before a consent change that deletes a session's
// recordings (`recorded` to `declined` or `withdrawn`; docs/OPERATOR.md, "Consent"). A modal
// alert dialog names what would be deleted, as the server counts it now (/api/state's
// `recording.kept`: "Delete the recording of session 12 (3 min 20 s, 2 files, 1.4 MB)? This
// cannot be undone."), with Cancel focused, so that a slip of the keyboard (Alt+Down, Down,
// Enter on the selector) deletes nothing. Escape cancels (and, as everywhere in the console,
// is Stop: keys.js). Only a confirmed change is sent, with `confirm: true`; the server refuses
// one without it (`confirmation-required`).

import { describeBytes } from "./dom.js";

/**
 * @param {{dialog: HTMLDialogElement, title: HTMLElement, text: HTMLElement,
 *          cancel: HTMLButtonElement, confirm: HTMLButtonElement,
 *          recording: () => Promise<object|null>}} options `recording`: /api/state's
 *          `recording` (its `kept`: what the session being recorded holds), or null when the
 *          state cannot be read
 */
export function createConsentConfirm({ dialog, title, text, cancel, confirm, recording }) {
  let answer = null; // resolves the open question

  const settle = (yes) => {
    const resolve = answer;
    answer = null;
    if (dialog.open) dialog.close();
    resolve?.(yes);
  };
  cancel.addEventListener("click", () => settle(false));
  confirm.addEventListener("click", () => settle(true));
  dialog.addEventListener("cancel", (event) => {
    event.preventDefault();
    settle(false);
  });
  dialog.addEventListener("close", () => settle(false));

  return {
    /** Asks whether to set session `session`'s consent to `consent`; resolves true if confirmed. */
    async ask(session, consent) {
      settle(false); // one question at a time
      const view = await recording().catch(() => null);
      // Unknown (the state could not be read): asked as if there were a recording.
      const known = view?.kept?.session === session ? view.kept : null;
      title.textContent = `Consent ${consent} for session ${session}`;
      if (!view || known?.files > 0 || known?.bytes > 0) {
        text.textContent = `Delete the recording of session ${session}${known ? ` (${describeKept(known)})` : ""}? This cannot be undone.`;
        confirm.textContent = "Delete recording";
      } else {
        text.textContent = `Nothing of session ${session} has been recorded yet; from now on nothing is.${consent === "withdrawn" ? " A withdrawal cannot be undone." : ""}`;
        confirm.textContent = `Set ${consent}`;
      }
      dialog.dataset.consent = consent;
      const asked = new Promise((resolve) => (answer = resolve));
      dialog.showModal();
      cancel.focus(); // the safe choice is the default
      return asked;
    },
    /** Esc: an open question is answered no. */
    cancel: () => settle(false),
  };
}

/** "3 min 20 s, 2 files, 1.4 MB" */
function describeKept({ seconds, files, bytes }) {
  const minutes = Math.floor(seconds / 60);
  const time = minutes ? `${minutes} min ${seconds % 60} s` : `${seconds} s`;
  return `${time}, ${files === 1 ? "1 file" : `${files} files`}, ${describeBytes(bytes)}`;
}
