// dom.js: the few DOM helpers the console's modules share: build an element tree with `h`,
// find an element by id with `byId`, format an event's time as the operator's clock, and a size in words.

/**
 * A new element: `h("button", {class: "act", onclick: fn, dataset: {label}}, "text", child)`.
 * Attributes named `on...` become listeners, `dataset` fills data-*, `false`/`null` skip,
 * `true` sets an empty attribute. Children may be strings, nodes, arrays or null.
 */
export function h(tag, attrs = {}, ...children) {
  const el = document.createElement(tag);
  for (const [name, value] of Object.entries(attrs ?? {})) {
    if (value === false || value === null || value === undefined) continue;
    if (name.startsWith("on") && typeof value === "function") {
      el.addEventListener(name.slice(2), value);
    } else if (name === "dataset") {
      Object.assign(el.dataset, value);
    } else if (name === "class") {
      el.className = value;
    } else {
      el.setAttribute(name, value === true ? "" : String(value));
    }
  }
  append(el, children);
  return el;
}

function append(el, children) {
  for (const child of children) {
    if (child === null || child === undefined || child === false) continue;
    if (Array.isArray(child)) append(el, child);
    else el.append(child instanceof Node ? child : String(child));
  }
}

/** The element with this id; throws when the page lacks it (a template and script mismatch). */
export function byId(id) {
  const el = document.getElementById(id);
  if (!el) throw new Error(`docent console: the page has no #${id}`);
  return el;
}

/** `HH:MM:SS` in local time for an RFC 3339 time (an event's `time`), or now. */
export function clock(time) {
  const date = time ? new Date(time) : new Date();
  return date.toLocaleTimeString([], { hour: "2-digit", minute: "2-digit", second: "2-digit", hour12: false });
}

/**
 * An act label as children for `h` that may wrap after each `_` (GO_TO_<wbr>HOME_<wbr>COMPUTER):
 * a narrow column shows the whole label on two lines instead of cutting it off.
 */
export function wrappableLabel(label) {
  return String(label)
    .split(/(?<=_)/)
    .flatMap((part, i) => (i === 0 ? [part] : [document.createElement("wbr"), part]));
}

/** Text shortened to `max` characters with an ellipsis. */
export function shorten(text, max = 80) {
  const s = String(text ?? "");
  return s.length > max ? `${s.slice(0, max - 1)}…` : s;
}

/**
 * A notice shown in `element` for `ms`, a later one replacing it; returns `show(message)`.
 * @param {HTMLElement} element
 * @param {number} ms
 */
export function createNotice(element, ms) {
  let timer = null;
  return (message) => {
    element.textContent = message;
    element.hidden = false;
    clearTimeout(timer);
    timer = setTimeout(() => (element.hidden = true), ms);
  };
}

/** A size as people read it: "812 bytes", "40 KB", "1.4 MB". */
export function describeBytes(bytes) {
  if (bytes < 1000) return `${bytes} bytes`;
  if (bytes < 1e6) return `${Math.round(bytes / 1e3)} KB`;
  if (bytes < 1e9) return `${(bytes / 1e6).toFixed(1)} MB`;
  return `${(bytes / 1e9).toFixed(1)} GB`;
}
