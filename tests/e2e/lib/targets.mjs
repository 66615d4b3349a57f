// Touch targets as a visitor (or an operator on a tablet) meets them: where each one is, how big
// it is, and whether a tap at its centre lands on it. Shared by the reflow test (the bundles'
// pages in the kiosk shell) and the console layout test.

/** The smallest touch target, in CSS pixels, both ways (WCAG 2.5.5, Apple's and Google's 44-48). */
export const MIN_TARGET_PX = 44;

/**
 * Runs in a document: the elements matching `selector` that are rendered (not `hidden`, not
 * `display: none`, not inside a closed `<details>`), each with its box in the viewport and
 * whether `document.elementFromPoint` at its centre is the element or inside it. With
 * `scroll`, each element is first scrolled to the middle of the viewport (as a visitor would
 * swipe to it). Self-contained: Playwright sends its source text to the page.
 */
export function measureTargets({ selector, scroll }) {
  const describe = (el) => {
    const act = el.getAttribute('data-act');
    const text = (el.getAttribute('aria-label') || el.textContent || '').replace(/\s+/g, ' ').trim().slice(0, 40);
    return act ? `[data-act=${act}] "${text}"` : `${el.tagName.toLowerCase()}${el.id ? `#${el.id}` : ''} "${text}"`;
  };
  const rendered = (el) => el.getClientRects().length > 0 && getComputedStyle(el).visibility !== 'hidden';
  return [...document.querySelectorAll(selector)].filter(rendered).map((el) => {
    if (scroll) el.scrollIntoView({ block: 'center', inline: 'center', behavior: 'instant' });
    const box = el.getBoundingClientRect();
    const x = box.left + box.width / 2;
    const y = box.top + box.height / 2;
    const hit = document.elementFromPoint(x, y);
    return {
      name: describe(el),
      left: Math.round(box.left),
      top: Math.round(box.top),
      right: Math.round(box.right),
      bottom: Math.round(box.bottom),
      width: Math.round(box.width * 10) / 10,
      height: Math.round(box.height * 10) / 10,
      centre: { x: Math.round(x), y: Math.round(y) },
      hitsItself: hit !== null && (hit === el || el.contains(hit)),
      coveredBy: hit && hit !== el && !el.contains(hit) ? describe(hit) : null,
      viewport: { width: innerWidth, height: innerHeight },
    };
  });
}

/**
 * The problems of measured targets, as sentences: outside the viewport (more than half a pixel,
 * for rounding), smaller than `min` either way, or covered at their centre.
 */
export function targetProblems(targets, { min = MIN_TARGET_PX } = {}) {
  const problems = [];
  for (const t of targets) {
    const { width, height } = t.viewport;
    if (t.left < -0.5 || t.top < -0.5 || t.right > width + 0.5 || t.bottom > height + 0.5) {
      problems.push(`${t.name} is outside the ${width}x${height} viewport (${t.left},${t.top} to ${t.right},${t.bottom})`);
    }
    if (t.width < min || t.height < min) problems.push(`${t.name} is ${t.width}x${t.height} px, under ${min}x${min}`);
    if (!t.hitsItself) problems.push(`${t.name}: a tap at its centre (${t.centre.x},${t.centre.y}) hits ${t.coveredBy ?? 'nothing'}`);
  }
  return problems;
}
