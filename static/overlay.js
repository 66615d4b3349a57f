// overlay.js: what the kiosk shell lays over the page on show, the caption (caption.js) and
// the calm outage notice (outage.js). Each lives in the page's own document, so the bundle's
// own CSS styles it by its class (`.docent-caption`, `.docent-offline-notice`; the defaults
// below have no specificity, `:where()`, so any rule of the bundle wins), and it is placed
// where it hides none of the page's controls: the lowest band of the screen, across the
// overlay's width, that no `data-act` element, link or button reaches (nor the shell's own
// controls). It says where in `data-docent-place` (`bottom`, `top`, `between`, or `squeezed`
// when no band is tall enough: then it takes the tallest and keeps to its height). A page
// that places its own (an element with `data-docent-caption` or `data-docent-offline`) gets
// the text there instead and is not moved.

const STYLE_ID = "docent-overlay-style";
const MARGIN_PX = 12;
const CONTROLS = "[data-act], [data-docent-stop], a[href], button, [role=button], input, select, textarea";

const DEFAULT_CSS = `
:where(.docent-caption, .docent-offline-notice) {
  position: fixed; z-index: 2147483000; left: 50%; transform: translateX(-50%);
  box-sizing: border-box; width: max-content; max-width: min(92vw, 60rem); margin: 0;
  padding: 0.45em 0.9em; border-radius: 0.45em; text-align: center; pointer-events: none;
  overflow: hidden; top: var(--docent-place-top, auto);
}
:where(.docent-caption) {
  font: 500 clamp(1.1rem, 3.2vmin, 2rem)/1.35 system-ui, sans-serif;
  color: var(--docent-caption-color, #fff);
  background: var(--docent-caption-background, rgb(0 0 0 / 82%));
}
:where(.docent-offline-notice) {
  font: 500 clamp(1rem, 2.6vmin, 1.5rem)/1.35 system-ui, sans-serif;
  color: var(--docent-notice-color, #1d2a33);
  background: var(--docent-notice-background, rgb(246 248 250 / 95%));
  box-shadow: 0 2px 10px rgb(0 0 0 / 18%);
}
:where(.docent-caption, .docent-offline-notice)[data-docent-place="bottom"] { top: auto; bottom: ${MARGIN_PX}px; }
:where(.docent-caption, .docent-offline-notice)[data-docent-place="squeezed"] {
  max-height: var(--docent-place-height, 3em); font-size: 1rem;
}
:where([data-docent-busy]) { opacity: 0.55; cursor: progress; transition: opacity 120ms ease-out; }
`;

/** Adds the default styles to `doc` once, first in its <head>, so the page's own CSS wins. */
export function ensureStyle(doc) {
  if (doc.getElementById(STYLE_ID)) return;
  const style = doc.createElement("style");
  style.id = STYLE_ID;
  style.textContent = DEFAULT_CSS;
  (doc.head ?? doc.documentElement).prepend(style);
}

/**
 * The element of class `className` in `doc` that shows an overlay: the page's own
 * (`[ownAttribute]`) if it has one, else one made here with `attributes` (e.g. aria-live).
 * Returns {element, own}.
 */
export function overlayElement(doc, className, ownAttribute, attributes = {}) {
  const own = doc.querySelector(`[${ownAttribute}]`);
  if (own) return { element: own, own: true };
  let element = doc.querySelector(`.${className}[data-docent-overlay]`);
  if (!element) {
    ensureStyle(doc);
    element = doc.createElement("div");
    element.className = className;
    element.dataset.docentOverlay = "";
    for (const [name, value] of Object.entries(attributes)) element.setAttribute(name, value);
    element.hidden = true;
    (doc.body ?? doc.documentElement).append(element);
  }
  return { element, own: false };
}

/** The screen rectangles the overlay must not hide: the page's visible controls and `extra`. */
function obstacles(doc, extra) {
  const view = doc.defaultView;
  const rects = [...doc.querySelectorAll(CONTROLS)]
    .filter((el) => !el.closest("[data-docent-overlay]") && view.getComputedStyle(el).visibility !== "hidden")
    .map((el) => el.getBoundingClientRect())
    .filter((r) => r.width > 0 && r.height > 0 && r.bottom > 0 && r.top < view.innerHeight);
  return rects.concat(extra);
}

/**
 * Places `element` (made by overlayElement, shown) where it hides no control of `doc` nor any
 * of the rectangles `avoid` (the shell's own controls, in the same screen coordinates).
 */
export function place(element, doc, avoid = []) {
  const view = doc.defaultView;
  element.dataset.docentPlace = "bottom";
  element.style.removeProperty("--docent-place-top");
  element.style.removeProperty("--docent-place-height");
  const box = element.getBoundingClientRect();
  const height = box.height + 2 * MARGIN_PX;
  // Only controls across the overlay's own width are in its way.
  const inWay = obstacles(doc, avoid).filter((r) => r.right > box.left && r.left < box.right);
  const bands = freeBands(inWay, view.innerHeight);
  const fits = bands.filter((b) => b.bottom - b.top >= height);
  const bottomMost = (a, b) => b.bottom - a.bottom;
  const band = fits.sort(bottomMost)[0];
  if (band) {
    if (band.bottom >= view.innerHeight) return "bottom";
    // At the top of the screen, or low in a band between controls (near the text it follows).
    const top = band.top <= 0 ? MARGIN_PX : band.bottom - MARGIN_PX - box.height;
    element.dataset.docentPlace = band.top <= 0 ? "top" : "between";
    element.style.setProperty("--docent-place-top", `${top}px`);
    return element.dataset.docentPlace;
  }
  // Nowhere tall enough: the tallest band, the overlay kept to its height.
  const tallest = bands.sort((a, b) => b.bottom - b.top - (a.bottom - a.top))[0] ?? { top: 0, bottom: view.innerHeight };
  element.dataset.docentPlace = "squeezed";
  element.style.setProperty("--docent-place-top", `${tallest.top + 2}px`);
  element.style.setProperty("--docent-place-height", `${Math.max(24, tallest.bottom - tallest.top - 4)}px`);
  return "squeezed";
}

/** The vertical bands of the screen (0..height) that no rectangle of `rects` reaches. */
function freeBands(rects, height) {
  const spans = rects.map((r) => [Math.max(0, r.top), Math.min(height, r.bottom)]).sort((a, b) => a[0] - b[0]);
  const bands = [];
  let from = 0;
  for (const [top, bottom] of spans) {
    if (top > from) bands.push({ top: from, bottom: top });
    from = Math.max(from, bottom);
  }
  if (from < height) bands.push({ top: from, bottom: height });
  return bands;
}
