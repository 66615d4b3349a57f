// main.js: the content report (GET /report). Signs in with the operator console's sign-in
// module (../operator/signin.js: the credential kept for this tab only, never in a URL), fetches
// GET /api/report with it as a Bearer header and renders the report (render.js). A refused
// credential is forgotten and the form asks again; a lockout (429) is shown and waited out.
// Printing renders every act first. `body[data-state]` says where the page is: signed-out,
// loading, rendering, ready. The problems are those of the files on disk now, as `docent check`
// lists them; while they have errors (`report.refused`) the summary says so first, and that
// the running bundle is the last good one, from when (`body[data-refused]`).

import { authHeaders, retryAfter } from "../operator/api.js";
import * as signin from "../operator/signin.js";
import { filterActs, renderActs, renderMedia, renderPages, renderProblems } from "./render.js";

const byId = (id) => document.getElementById(id);
const body = document.body;
const open = body.dataset.credential === "open";
const apiPath = body.dataset.api;

let acts = null; // renderActs' handle once a report is shown

const dialog = signin.createSignIn({
  dialog: byId("signin"),
  form: byId("signin-form"),
  token: byId("signin-token"),
  name: byId("signin-name"),
  error: byId("signin-error"),
  onSubmit: ({ token }) => load(token),
});

function setState(state, summary) {
  body.dataset.state = state;
  if (summary !== undefined) byId("summary").textContent = summary;
}

/** Fetches the report with `token` (null on an open server) and shows it. */
async function load(token) {
  setState("loading", "Loading the report…");
  let res;
  try {
    res = await fetch(apiPath, { headers: authHeaders(token) });
  } catch {
    setState("signed-out", "Docent did not answer. Is it running?");
    return;
  }
  if (res.status === 429) {
    const seconds = retryAfter(res);
    const lockout = byId("lockout");
    lockout.textContent = `Too many wrong or missing credentials from this computer: Docent refuses wrong ones from it (the right credential is always taken) for ${seconds} s. Try again then.`;
    lockout.hidden = false;
    setState("signed-out", "Locked out for now.");
    setTimeout(() => {
      lockout.hidden = true;
      dialog.ask();
    }, seconds * 1000);
    return;
  }
  if (res.status === 401) {
    signin.forget();
    setState("signed-out", "Not signed in.");
    dialog.ask("That credential was refused. Check it and try again.");
    return;
  }
  if (!res.ok) {
    setState("signed-out", `Docent answered ${res.status}: the report could not be made. See the server log.`);
    return;
  }
  if (token) signin.remember(token, null);
  show(await res.json());
}

/**
 * The files on disk do not load: said first, as `docent check` would fail. The acts, pages and
 * media listed are then the running bundle's, the last good one.
 */
function refusedSummary({ errors, live_since_ms }) {
  const since = new Date(live_since_ms);
  const time = `${String(since.getHours()).padStart(2, "0")}:${String(since.getMinutes()).padStart(2, "0")}`;
  return `The files on disk have ${errors} error${errors === 1 ? "" : "s"}; the running bundle is the last good one from ${time}. Its acts, pages and media are listed below, the problems of the files on disk first.`;
}

function show(report) {
  const started = performance.now();
  setState("rendering");
  byId("bundle-name").textContent = report.bundle;
  // Notes (files ignored, media converted) are listed with the problems but are none.
  const notes = report.problems.filter((p) => p.severity === "note").length;
  const warnings = report.problems.length - notes;
  const noted = notes ? `, ${notes} note${notes === 1 ? "" : "s"}` : "";
  const counted = `${report.acts.length} acts, ${report.pages.length} pages, ${report.media.length} media files, ${warnings} problem${warnings === 1 ? "" : "s"}${noted}.`;
  byId("summary").textContent = report.refused ? refusedSummary(report.refused) : counted;
  body.dataset.refused = report.refused ? "true" : "false";
  byId("problem-count").textContent = `(${report.problems.length})`;
  byId("act-count").textContent = `(${report.acts.length})`;
  byId("page-count").textContent = `(${report.pages.length})`;
  byId("media-count").textContent = `(${report.media.length})`;
  renderProblems(byId("problems"), report.problems);
  renderPages(byId("pages"), report.pages, report.home);
  renderMedia(byId("media"), report.media);
  acts = renderActs(byId("acts"), report.acts);
  byId("filter").disabled = false;
  byId("print").disabled = false;
  acts.done.then(() => {
    body.dataset.renderMs = String(Math.round(performance.now() - started));
    setState("ready");
    const query = byId("filter").value;
    if (query) filterActs(byId("acts"), query);
  });
}

byId("filter").addEventListener("input", (event) => {
  const shown = filterActs(byId("acts"), event.target.value);
  byId("act-count").textContent = event.target.value.trim() ? `(${shown} found)` : `(${byId("acts").children.length})`;
});

// Printing shows every act, whatever is still being rendered or filtered out.
window.addEventListener("beforeprint", () => {
  acts?.renderAll();
  for (const article of byId("acts").children) article.hidden = false;
});
byId("print").addEventListener("click", () => window.print());

byId("signout").addEventListener("click", () => {
  signin.forget();
  for (const id of ["problems", "acts", "pages", "media"]) byId(id).replaceChildren();
  acts = null;
  setState("signed-out", "Signed out.");
  dialog.ask();
});

if (open) {
  byId("signout").hidden = true;
  load(null);
} else {
  const saved = signin.stored().token;
  if (saved) load(saved);
  else dialog.ask();
}
