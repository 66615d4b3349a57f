// The operator console on the screens an operator brings: a 1366x768 laptop (mouse), and a
// tablet in landscape 1024x768 and portrait 768x1024 with touch. On each: the console signs in
// and shows the museum tour's acts with a dialog manager's proposal; no act label (of an act
// button or a proposal) is cut off or sticks out of its box: a long one wraps after an
// underscore instead; nothing sticks out sideways; the Stop button and the search are on screen. On touch
// (`pointer: coarse`) every control (buttons, selects, inputs, links) is at least 44x44 CSS px
// and is what a tap at its centre hits once scrolled to (the columns scroll by themselves). The
// page may be zoomed everywhere (no `maximum-scale`, no `user-scalable`). Screenshots go to
// target/e2e/console/ (not committed).

import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser } from './lib/browser.mjs';
import { REPO } from './lib/docent.mjs';
import { connectWithToken, museumTour, signIn, withConsoleServer } from './lib/operator.mjs';
import { measureTargets, targetProblems } from './lib/targets.mjs';

const SIZES = [
  { name: 'laptop', width: 1366, height: 768, touch: false },
  { name: 'tablet landscape', width: 1024, height: 768, touch: true },
  { name: 'tablet portrait', width: 768, height: 1024, touch: true },
];

const OUT = path.join(REPO, 'target/e2e/console');
const CONTROLS = 'button, select, input, a[href], summary';

let browser;
before(async () => {
  browser = await launchBrowser();
  fs.mkdirSync(OUT, { recursive: true });
});
after(() => browser?.close());

// Runs in the console: act labels (the act buttons' and the proposals') cut off or sticking
// out of their box, and how wide the page is. Self-contained (Playwright sends its source).
function labelsAndWidth() {
  const cut = [];
  for (const label of document.querySelectorAll('#act-list .act-label, .proposal-label')) {
    const box = label.closest('.act, .proposal-what').getBoundingClientRect();
    const clipped = getComputedStyle(label).display !== 'inline' && label.scrollWidth > label.clientWidth + 1;
    const outside = [...label.getClientRects()].some((r) => r.right > box.right + 1 || r.left < box.left - 1);
    if (clipped || outside) cut.push(`${label.textContent} (${Math.round(label.getBoundingClientRect().width)} px in a ${Math.round(box.width)} px box)`);
  }
  const visible = (sel) => {
    const box = document.querySelector(sel).getBoundingClientRect();
    return box.width > 0 && box.top >= 0 && box.left >= 0 && box.bottom <= innerHeight && box.right <= innerWidth;
  };
  return {
    cut,
    scrollWidth: document.scrollingElement.scrollWidth,
    width: innerWidth,
    coarse: matchMedia('(pointer: coarse)').matches,
    stopShown: visible('#stop'),
    searchShown: visible('#search'),
    viewport: document.querySelector('meta[name="viewport"]').content,
  };
}

for (const size of SIZES) {
  test(`the console works on a ${size.name} (${size.width}x${size.height}${size.touch ? ', touch' : ''})`, { timeout: 120_000 }, async () => {
    await withConsoleServer(browser, museumTour(), async ({ server, newPage, cleanup }) => {
      const page = await newPage((b) => b.newContext({ viewport: { width: size.width, height: size.height }, hasTouch: size.touch, isMobile: false }));
      await signIn(page, server);
      const dm = await connectWithToken(server, 'dm', 'e2e-planner');
      cleanup.unshift(() => dm.close());
      dm.send({ type: 'propose', label: 'FAREWELL', reason: 'the visitors turned to the exit', ref: 'p1' });
      await page.locator('#proposals:not([hidden]) .accept').waitFor();
      await page.screenshot({ path: path.join(OUT, `${size.width}x${size.height}.png`) });

      const seen = await page.evaluate(labelsAndWidth);
      assert.doesNotMatch(seen.viewport, /maximum-scale|user-scalable/, 'the console may be zoomed');
      assert.equal(seen.coarse, size.touch, 'pointer: coarse on touch only (the test would prove nothing otherwise)');
      assert.deepEqual(seen.cut, [], 'act labels cut off');
      assert.ok(seen.scrollWidth <= seen.width + 1, `the console is ${seen.scrollWidth} px wide on a ${seen.width} px screen`);
      assert.ok(seen.stopShown, 'the Stop button is on screen');
      assert.ok(seen.searchShown, 'the search is on screen');

      const targets = await page.evaluate(measureTargets, { selector: CONTROLS, scroll: true });
      assert.ok(targets.length > 20, `only ${targets.length} controls found`);
      const problems = targetProblems(targets, { min: size.touch ? 44 : 0 });
      assert.deepEqual(problems, [], `controls on the ${size.name}`);
    });
  });
}
