// reloadbanner.js: the live-reload banner. While `docent serve` watches the bundle, a save with
// errors is refused and the last good bundle keeps running; until a good save is live this
// banner lists the problems, each at its file, line and column. It also says when the bundle
// folder cannot be watched (deleted, renamed) and which changed settings are not in effect yet
// (they need a restart), and which media files are still being converted for Chromium or could
// not be (state.reload.media, then `media` frames). A console joining later reads the same
// from `welcome` (state.reload); a console already connected follows the `bundle.*` events.

const EMPTY = { refused: null, trouble: null, not_applied: [], media: [] };

/**
 * @param {{element: HTMLElement, onReloaded: (event: object) => void}} options `element`: the
 *          banner (hidden when there is nothing to say); `onReloaded`: a good save went live
 * @returns {{onFrame: (frame: object) => void}}
 */
export function createReloadBanner({ element, onReloaded }) {
  let view = { ...EMPTY };

  function problemLine(d) {
    const li = document.createElement("li");
    li.dataset.code = d.code;
    const where = document.createElement("strong");
    where.textContent = `${d.file}, line ${d.line}, column ${d.column}`;
    // A refused save lists errors, warnings and notes (files ignored, media converted); an
    // unknown word is shown as an error, the safe side.
    const kind = ["warning", "note"].includes(d.severity) ? d.severity : "error";
    li.append(where, `: ${d.message} (${kind}: ${d.code})`);
    return li;
  }

  function paragraph(text, className) {
    const p = document.createElement("p");
    p.className = className;
    p.textContent = text;
    return p;
  }

  function render() {
    element.replaceChildren();
    const refused = view.refused ?? [];
    const errors = refused.filter((d) => !["warning", "note"].includes(d.severity)).length;
    if (view.refused) {
      element.append(
        paragraph(
          `The last save of the bundle has ${errors} error(s) and was not put live; Docent is still running the last good bundle until they are fixed:`,
          "reload-title",
        ),
      );
      const list = document.createElement("ul");
      list.className = "reload-problems";
      list.append(...refused.map(problemLine));
      element.append(list);
    }
    if (view.trouble) element.append(paragraph(view.trouble, "reload-trouble"));
    if (view.not_applied.length > 0) {
      element.append(paragraph("Saved but not in effect yet:", "reload-title"));
      const list = document.createElement("ul");
      list.className = "reload-not-applied";
      for (const sentence of view.not_applied) {
        const li = document.createElement("li");
        li.textContent = sentence;
        list.append(li);
      }
      element.append(list);
    }
    if (view.media.length > 0) {
      element.append(paragraph("Media for the kiosk and projector:", "reload-title"));
      const list = document.createElement("ul");
      list.className = "reload-media";
      list.append(...view.media.map(mediaLine));
      element.append(list);
    }
    const failed = view.media.some((m) => m.state === "failed");
    element.hidden =
      !view.refused && !view.trouble && view.not_applied.length === 0 && view.media.length === 0;
    element.dataset.state = view.refused || view.trouble || failed ? "refused" : "ok";
  }

  /** One media file on its way: the server's own words, nothing decided here. */
  function mediaLine(m) {
    const li = document.createElement("li");
    li.dataset.state = m.state;
    const file = document.createElement("strong");
    file.textContent = m.file;
    const how =
      m.state === "failed"
        ? ` cannot be shown: ${m.reason}`
        : m.state === "converting"
          ? ` (${m.format}) is being converted${m.percent == null ? "" : `: ${m.percent} %`}`
          : ` (${m.format}) is waiting to be converted`;
    li.append(file, how);
    return li;
  }

  function onFrame(frame) {
    if ((frame.type === "welcome" || frame.type === "state") && frame.state?.reload) {
      view = { ...EMPTY, ...frame.state.reload };
      render();
      return;
    }
    if (frame.type === "media") {
      view = { ...view, media: frame.files ?? [] };
      render();
      return;
    }
    if (frame.type !== "event") return;
    const e = frame.event ?? {};
    if (e.type === "bundle.refused") {
      view = { ...view, refused: e.diagnostics ?? [], trouble: null };
    } else if (e.type === "bundle.watch-failed") {
      view = { ...view, trouble: e.message ?? e.code };
    } else if (e.type === "bundle.reloaded") {
      view = { ...EMPTY, not_applied: e.not_applied ?? [], media: view.media };
      onReloaded(e);
    } else {
      return;
    }
    render();
  }

  render();
  return { onFrame };
}
