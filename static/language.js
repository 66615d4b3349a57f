// language.js: the visitor's language in the kiosk shell (docs/AUTHORING.md, "Several
// languages"). Knows the bundle's languages (the shell's `data-languages`, the default first),
// the folder under pages/ the server says each shows its pages from (`data-page-folders`:
// none for the default, `de/` for German; the server serves the default language's page where
// the folder lacks it), and the language in force (from `welcome` and `state` frames'
// `state.language` and from `language` frames). A page is shown from the folder in force
// (`pages/de/tour.html`) and reported to Docent without a language's folder, as the bundle
// names it (`tour.html`). A page's `data-language` button (docent-page.js) asks through `ask`: the
// answer is the `language` frame or Docent's `error` (`not-offered`, `unknown-language`),
// which the shell says on screen and in the browser's log: a refusal is never silent.

const ANSWER_TIMEOUT_MS = 10_000;

/**
 * @param {{languages: string, pageFolders: Object<string, string>,
 *          send: (frame: object) => boolean, say: (key: string) => void,
 *          onChange: (language: string) => void}} options `languages`: the tags separated by
 *          spaces, the default first; `pageFolders`: each language's folder under pages/, as
 *          the server resolved it; `send`: the shell's socket; `say`: the shell's notice, by
 *          the key of its words (shell-text.js);
 *          `onChange`: the language changed (the shell shows its page again in it)
 */
export function kioskLanguage({ languages, pageFolders, send, say, onChange }) {
  const all = String(languages || "en").toLowerCase().split(/\s+/).filter(Boolean);
  const fallback = all[0] ?? "en";
  const folders = Object.entries(pageFolders ?? {}); // [[language, folder]] as the server resolved them
  const folderOf = (tag) => folders.find(([language]) => language === tag)?.[1] ?? "";
  let current = fallback;
  const pending = new Map(); // ref -> resolve
  let refCount = 0;

  /** Takes `tag` as the language in force; true when it changed. */
  function set(tag) {
    const wanted = String(tag ?? "").toLowerCase();
    if (!wanted || wanted === current) return false;
    current = wanted;
    onChange(wanted);
    return true;
  }

  function refused(answer) {
    const message = answer.message || answer.code || "not possible";
    console.warn(`docent: the language was not changed: ${message}`);
    say(answer.code === "offline" || answer.code === "disconnected" ? "language_offline" : "language_unavailable");
  }

  return {
    /** The language in force. */
    current: () => current,
    /** The visitor's language when it is not the default, else null (for the hello). */
    chosen: () => (current === fallback ? null : current),
    /** The path under pages/ that shows `page` in the language in force. */
    path: (page) => (page ? folderOf(current) + page : page),
    /** The page the bundle names for a path under pages/: without its language folder. */
    page(path) {
      const text = String(path);
      const folder = folders.find(([, f]) => f && text.toLowerCase().startsWith(f) && text.length > f.length)?.[1];
      return folder ? text.slice(folder.length) : path;
    },
    /** Takes a server frame: the language in `welcome`/`state`, `language`, answers. */
    onFrame(frame) {
      if (frame.type === "welcome" || frame.type === "state") set(frame.state?.language);
      else if (frame.type === "language") set(frame.language);
      if ((frame.type === "language" || frame.type === "error") && pending.has(frame.ref)) {
        const resolve = pending.get(frame.ref);
        pending.delete(frame.ref);
        if (frame.type === "error") refused(frame);
        resolve(frame);
      }
    },
    /** Asks Docent for `tag`; resolves with the `language` or `error` frame. */
    ask(tag) {
      const ref = `kiosk-language-${Date.now().toString(36)}-${++refCount}`;
      return new Promise((resolve) => {
        if (!send({ type: "language", language: String(tag), ref })) {
          const answer = { type: "error", code: "offline", message: "not connected to Docent", ref };
          refused(answer);
          resolve(answer);
          return;
        }
        pending.set(ref, resolve);
        setTimeout(() => {
          if (!pending.delete(ref)) return;
          const answer = { type: "error", code: "timeout", message: "Docent did not answer", ref };
          refused(answer);
          resolve(answer);
        }, ANSWER_TIMEOUT_MS);
      });
    },
  };
}
