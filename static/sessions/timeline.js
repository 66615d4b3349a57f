// timeline.js: one session on a timeline, a row (tier) per kind of event: the robot's speech,
// the pages shown, the other commands, the visitors' touches, the operator's marks, then one row
// per codebook tier of annotations. Items sit at their place on the session clock (percent of
// its length). Clicking the timeline moves the playhead there, clicking a mark or an annotation
// moves it to that item's start; the timeline is a keyboard slider too (arrows: 1 s, with
// Shift: 10 s, Home and End). Pure rendering: the playhead's time is the player's.

/** Seconds with milliseconds: `12.345 s`. */
export const seconds = (us) => `${(us / 1e6).toFixed(3)} s`;

function el(tag, className, text) {
  const node = document.createElement(tag);
  if (className) node.className = className;
  if (text !== undefined) node.textContent = text;
  return node;
}

/**
 * @param {{timeline: HTMLElement, tiers: HTMLElement, playhead: HTMLElement, lengthUs: number,
 *          onSeek: (us: number) => void}} options
 */
export function createTimeline({ timeline, tiers, playhead, lengthUs, onSeek }) {
  const span = Math.max(lengthUs, 1);
  const percent = (us) => `${(Math.min(Math.max(us, 0), span) / span) * 100}%`;
  timeline.setAttribute("aria-valuemax", String(Math.round(lengthUs / 1000)));
  timeline.setAttribute("aria-valuetext", `0 s of ${seconds(lengthUs)}`);

  /** A row: its label and its lane. */
  function row(label, kind) {
    const line = el("div", `tier tier-${kind}`);
    line.append(el("span", "tier-name", label));
    const lane = el("div", "lane");
    line.append(lane);
    tiers.append(line);
    return lane;
  }

  /** An interval (or a point, when `endUs` is null) on `lane`; a button when `seekable`. */
  function item(lane, { startUs, endUs, text, title, seekable, className }) {
    const node = el(seekable ? "button" : "div", `item ${endUs === null ? "point" : "interval"} ${className || ""}`, text);
    if (seekable) node.type = "button";
    node.style.left = percent(startUs);
    if (endUs !== null) node.style.width = `calc(${percent(endUs - startUs)} + 1px)`;
    node.title = title;
    node.dataset.startUs = String(startUs);
    if (seekable) node.setAttribute("aria-label", title);
    lane.append(node);
    return node;
  }

  let annotationLanes = new Map();

  function render(detail) {
    tiers.replaceChildren();
    const t = detail.timeline;
    const speech = row("Speech", "speech");
    for (const u of t.utterances) {
      item(speech, { startUs: u.start_us, endUs: u.end_us, text: u.text, title: `${seconds(u.start_us)} ${u.label}: ${u.text}` });
    }
    const pages = row("Pages", "pages");
    for (const p of t.pages) item(pages, { startUs: p.start_us, endUs: p.end_us, text: p.page, title: `${seconds(p.start_us)} page ${p.page}` });
    const commands = row("Commands", "commands");
    for (const c of t.commands) {
      const text = c.arg ? `${c.verb} ${c.arg}` : c.verb;
      item(commands, { startUs: c.start_us, endUs: c.end_us, text, title: `${seconds(c.start_us)} ${text} (${c.outcome})` });
    }
    const touches = row("Touches", "touches");
    for (const touch of t.touches) {
      item(touches, { startUs: touch.at_us, endUs: null, text: "", title: `touch at ${seconds(touch.at_us)}: ${touch.kind} ${touch.value}`, seekable: true });
    }
    const marks = row("Marks", "marks");
    for (const m of t.marks) {
      item(marks, { startUs: m.at_us, endUs: null, text: "", title: `mark at ${seconds(m.at_us)}: ${m.kind} ${m.value}`, seekable: true, className: `mark mark-${m.kind}` });
    }
    annotationLanes = new Map();
    const names = detail.codebook.tiers.map((tier) => tier.name);
    for (const a of detail.annotations) if (!names.includes(a.tier)) names.push(a.tier);
    for (const name of names) annotationLanes.set(name, row(`Code: ${name}`, "coded"));
    showAnnotations(detail.annotations);
  }

  function showAnnotations(annotations) {
    for (const lane of annotationLanes.values()) lane.replaceChildren();
    for (const a of annotations) {
      let lane = annotationLanes.get(a.tier);
      if (!lane) {
        lane = row(`Code: ${a.tier}`, "coded");
        annotationLanes.set(a.tier, lane);
      }
      const point = a.start_us === a.end_us;
      const node = item(lane, {
        startUs: a.start_us,
        endUs: point ? null : a.end_us,
        text: point ? "" : a.code,
        title: `${a.tier}: ${a.code} at ${seconds(a.start_us)}${point ? "" : ` to ${seconds(a.end_us)}`}`,
        seekable: true,
        className: "annotation",
      });
      node.dataset.id = a.id;
    }
  }

  timeline.addEventListener("click", (event) => {
    const seekable = event.target.closest("button.item");
    if (seekable) {
      onSeek(Number(seekable.dataset.startUs));
      return;
    }
    const lane = tiers.querySelector(".lane");
    if (!lane) return;
    const box = lane.getBoundingClientRect();
    if (event.clientX < box.left) return;
    onSeek(((event.clientX - box.left) / box.width) * span);
  });

  timeline.addEventListener("keydown", (event) => {
    if (event.target !== timeline) return;
    const now = Number(playhead.dataset.timeUs);
    const step = event.shiftKey ? 10e6 : 1e6;
    const to = { ArrowLeft: now - step, ArrowRight: now + step, PageDown: now - 10e6, PageUp: now + 10e6, Home: 0, End: span }[event.key];
    if (to === undefined) return;
    event.preventDefault();
    onSeek(to);
  });

  return {
    render,
    showAnnotations,
    /** Puts the playhead at `us`. */
    setPlayhead(us) {
      playhead.style.left = `calc(var(--label-width) + (100% - var(--label-width)) * ${Math.min(us, span) / span})`;
      playhead.dataset.timeUs = String(Math.round(us));
      timeline.setAttribute("aria-valuenow", String(Math.round(us / 1000)));
      timeline.setAttribute("aria-valuetext", `${seconds(us)} of ${seconds(lengthUs)}`);
    },
  };
}
