// render.js: the content report's DOM, built from GET /api/report's JSON. Acts are rendered in
// chunks, one per animation frame, each twice the one before: the first acts show at once, and
// since every frame costs style and layout in proportion to the acts already in the page, few
// frames (7 for 10,000 acts) keep the whole report fast; `renderAll` finishes at once (before printing). Texts are set with
// textContent only: content never becomes markup here.

/** Acts in the first chunk (more than a screen holds). */
const FIRST_CHUNK = 150;

/** An element `tag` with `className` and text or children. */
function el(tag, className, ...children) {
  const node = document.createElement(tag);
  if (className) node.className = className;
  for (const child of children) {
    if (child === null || child === undefined) continue;
    node.append(typeof child === "string" ? document.createTextNode(child) : child);
  }
  return node;
}

/** A comma-separated list of `items`, or a muted `empty` word. */
function list(items, empty = "none") {
  return items.length ? el("span", null, items.join(", ")) : el("span", "muted", empty);
}

/** The problems list: one line per problem, `file:line:column`, code and message. */
export function renderProblems(container, problems) {
  container.replaceChildren();
  if (!problems.length) {
    container.append(el("li", "muted", "No problems: `docent check` finds nothing to fix."));
    return;
  }
  for (const p of problems) {
    const item = el(
      "li",
      `problem ${p.severity}`,
      el("span", "place", `${p.file}:${p.line}:${p.column}`),
      " ",
      el("span", "code", `${p.severity}[${p.code}]`),
      " ",
      el("span", "message", p.message),
    );
    item.dataset.code = p.code;
    container.append(item);
  }
}

/** One act: label, place, group and key, its texts by variant, commands and pages. */
function actElement(act) {
  const head = el(
    "header",
    "act-head",
    el("h3", "label", act.label),
    el("span", "place muted", `${act.file}:${act.line}`),
    el("span", "group", `Group: ${act.group}`),
    act.key ? el("span", "key", `Alt+${act.key}`) : null,
  );
  const body = el("dl", "act-body");
  for (const variant of act.variants) {
    const texts = el("ul", "texts");
    for (const text of variant.texts) texts.append(el("li", null, text));
    body.append(el("dt", null, variant.name), el("dd", null, texts));
  }
  if (act.commands.length) {
    const commands = el("ol", "commands");
    for (const command of act.commands) commands.append(el("li", null, el("code", null, command)));
    body.append(el("dt", null, "Cmds"), el("dd", null, commands));
  }
  body.append(el("dt", null, "Offered on"), el("dd", null, list(act.offered_on, "no page")));
  const article = el("article", "act", head, body);
  article.id = `act-${act.label}`;
  article.dataset.label = act.label;
  // What the filter searches: label, texts and commands, lower case.
  article.dataset.search = [act.label, ...act.variants.flatMap((v) => v.texts), ...act.commands].join("\n").toLowerCase();
  return article;
}

/**
 * Renders `acts` into `container` a chunk per animation frame.
 * @returns {{done: Promise<void>, renderAll: () => void}} `done` settles when every act is in
 *          the page; `renderAll` puts the rest in at once.
 */
export function renderActs(container, acts) {
  container.replaceChildren();
  let next = 0;
  let finish;
  const done = new Promise((resolve) => {
    finish = resolve;
  });
  function chunk(size) {
    const fragment = document.createDocumentFragment();
    const end = Math.min(acts.length, next + size);
    for (; next < end; next += 1) fragment.append(actElement(acts[next]));
    container.append(fragment);
    if (next < acts.length) requestAnimationFrame(() => chunk(size * 2));
    else finish();
  }
  chunk(FIRST_CHUNK);
  return { done, renderAll: () => next < acts.length && chunk(acts.length) };
}

/** The pages table: path (home marked), offered acts with their lines, acts that show it. */
export function renderPages(tbody, pages, home) {
  tbody.replaceChildren();
  for (const page of pages) {
    const offers = el("ul", "offers");
    for (const offer of page.offers) {
      const item = el("li", offer.known ? null : "unknown", `${offer.label} `, el("span", "muted", `line ${offer.line}`));
      offers.append(item);
    }
    const name = el("td", "path", page.path, page.path === home ? el("span", "badge", "home") : null);
    const row = el("tr", null, name, el("td", null, page.offers.length ? offers : el("span", "muted", "none")), el("td", null, list(page.displayed_by)));
    row.dataset.page = page.path;
    tbody.append(row);
  }
}

/** The media table: file, acts that project it, pages that name it. */
export function renderMedia(tbody, media) {
  tbody.replaceChildren();
  for (const file of media) {
    const row = el("tr", null, el("td", "path", file.path), el("td", null, list(file.projected_by)), el("td", null, list(file.used_on)));
    row.dataset.media = file.path;
    tbody.append(row);
  }
}

/** Shows only the acts whose label, texts or commands contain `query` (all when empty). */
export function filterActs(container, query) {
  const wanted = query.trim().toLowerCase();
  let shown = 0;
  for (const article of container.children) {
    const match = !wanted || article.dataset.search.includes(wanted);
    article.hidden = !match;
    if (match) shown += 1;
  }
  return shown;
}
