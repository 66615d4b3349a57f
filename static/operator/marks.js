// marks.js: corpus marks. Start and end a visitor session, note what its visitors agreed to
// (consent: recorded, declined, withdrawn; a withdrawal is final), note the visitor group
// (single, group, children; the server may switch the context for it, see docent.yaml
// `operator.visitor_groups`) and mark dialog situations (from `operator.situations`, keys
// Alt+Shift+1..9), and write a note in the operator's own words (Alt+Shift+N goes to it; the
// text stays in the field until its note.written event says it is in the corpus). Each sends
// a `mark` frame; what is shown follows the session.* and consent.changed events. A consent
// change that deletes the session's recordings (`recorded` to `declined` or `withdrawn`) is
// sent only once the operator confirmed it (`confirmDeletion`: consentconfirm.js), with
// `confirm: true`.

import { h } from "./dom.js";

const GROUPS = [
  ["single", "Single"],
  ["group", "Group"],
  ["children", "Children"],
];

/**
 * @param {{session: HTMLElement, start: HTMLElement, end: HTMLElement, consent: HTMLSelectElement,
 *          groups: HTMLElement, situations: HTMLElement,
 *          note: {form: HTMLFormElement, input: HTMLInputElement},
 *          mark: (mark: string, value?: string, extra?: object) => void,
 *          confirmDeletion: (session: number, consent: string) => Promise<boolean>}} options
 */
export function createMarks({ session, start, end, consent, groups, situations, note, mark, confirmDeletion }) {
  let current = null;
  let consentNow = null;
  let situationNames = [];

  note.form.addEventListener("submit", (event) => {
    event.preventDefault();
    const text = note.input.value.trim();
    if (text) mark("note", text);
  });

  start.addEventListener("click", () => mark("session_start"));
  end.addEventListener("click", () => mark("session_end"));
  consent.addEventListener("change", async () => {
    const chosen = consent.value;
    // Shown as the server has it until its consent.changed arrives (or an error says why not).
    showConsent();
    if (chosen === consentNow) return;
    const deletes = (consentNow ?? "recorded") === "recorded" && chosen !== "recorded";
    if (!deletes) return mark("consent", chosen);
    const asked = current;
    // Sent only if confirmed while the same session still runs.
    if ((await confirmDeletion(asked, chosen)) && current === asked) mark("consent", chosen, { confirm: true });
  });

  function showSession() {
    session.textContent = current === null ? "no session" : `session ${current}`;
    session.classList.toggle("running", current !== null);
    end.disabled = current === null;
    showConsent();
  }

  function showConsent() {
    consent.disabled = current === null || consentNow === "withdrawn";
    consent.value = consentNow ?? "recorded";
    consent.dataset.state = current === null ? "none" : (consentNow ?? "unknown");
  }

  function showGroup(group) {
    for (const button of groups.querySelectorAll("button")) {
      button.setAttribute("aria-pressed", String(button.dataset.group === group));
    }
  }

  return {
    /** GET /api/operator: `visitor_groups` (group -> context) and `situations`. */
    configure(settings) {
      const contexts = settings?.visitor_groups ?? {};
      groups.replaceChildren(
        ...GROUPS.map(([group, name]) =>
          h(
            "button",
            {
              type: "button",
              class: "group",
              "aria-pressed": "false",
              dataset: { group },
              title: contexts[group] ? `Mark the visitor group; sets context ${contexts[group]}` : "Mark the visitor group",
              onclick: () => mark("group", group),
            },
            name,
          ),
        ),
      );
      situationNames = (settings?.situations ?? []).slice(0, 9);
      situations.replaceChildren(
        ...(situationNames.length
          ? situationNames.map((name, i) =>
              h(
                "button",
                { type: "button", class: "situation", dataset: { situation: name }, "aria-keyshortcuts": `Alt+Shift+${i + 1}`, onclick: () => mark("situation", name) },
                h("kbd", {}, String(i + 1)),
                ` ${name}`,
              ),
            )
          : [h("p", { class: "muted small" }, "none configured (docent.yaml operator.situations)")]),
      );
    },
    /** Puts the keyboard in the note field. */
    focusNote: () => note.input.focus(),
    /** The situation bound to Alt+Shift+`n` (1-based), or null. */
    situation: (n) => situationNames[n - 1] ?? null,
    /** The current session id and its consent (GET /api/state `session`, `consent`). */
    setSession(id, state) {
      current = id ?? null;
      if (state !== undefined) consentNow = state ?? null;
      showSession();
    },
    event(e) {
      if (e.type === "session.started") {
        current = e.session;
        consentNow = e.consent ?? null;
        showGroup(null);
        showSession();
      } else if (e.type === "session.ended") {
        if (current === e.session) {
          current = null;
          consentNow = null;
        }
        showGroup(null);
        showSession();
      } else if (e.type === "consent.changed") {
        if (current === e.session) consentNow = e.consent;
        showConsent();
      } else if (e.type === "visitor.group") {
        showGroup(e.group);
      } else if (e.type === "note.written" && e.text === note.input.value.trim()) {
        note.input.value = ""; // in the corpus now: the field is free for the next one
      }
    },
  };
}
