// marks.js: corpus marks. Start and end a visitor session, note the visitor group (single,
// group, children; the server may switch the context for it, see docent.yaml
// `operator.visitor_groups`) and mark dialog situations (from `operator.situations`, keys
// Alt+Shift+1..9). Each sends a `mark` frame; the session shown follows the session.* events.

import { h } from "./dom.js";

const GROUPS = [
  ["single", "Single"],
  ["group", "Group"],
  ["children", "Children"],
];

/**
 * @param {{session: HTMLElement, start: HTMLElement, end: HTMLElement, groups: HTMLElement,
 *          situations: HTMLElement, mark: (mark: string, value?: string) => void}} options
 */
export function createMarks({ session, start, end, groups, situations, mark }) {
  let current = null;
  let situationNames = [];

  start.addEventListener("click", () => mark("session_start"));
  end.addEventListener("click", () => mark("session_end"));

  function showSession() {
    session.textContent = current === null ? "no session" : `session ${current}`;
    session.classList.toggle("running", current !== null);
    end.disabled = current === null;
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
    /** The situation bound to Alt+Shift+`n` (1-based), or null. */
    situation: (n) => situationNames[n - 1] ?? null,
    /** The current session id (GET /api/state `session`, a `marked` answer). */
    setSession(id) {
      current = id ?? null;
      showSession();
    },
    event(e) {
      if (e.type === "session.started") {
        current = e.session;
        showGroup(null);
        showSession();
      } else if (e.type === "session.ended") {
        if (current === e.session) current = null;
        showGroup(null);
        showSession();
      } else if (e.type === "visitor.group") {
        showGroup(e.group);
      }
    },
  };
}
