// The operator console (`GET /operator`) in headless Chromium, driven by the keyboard as an
// operator drives it: finding an act by a word of its text (case and accents ignored, labels and
// groups too) and firing it with Enter so that the kiosk open in another browser context changes
// page, the context, F2 and F4, keys reaching the search from any focused control, held keys
// firing once, and the keystrokes each museum-tour act takes (measured for docs/OPERATOR.md).
// Each test runs the real `docent` binary with operator and dialog-manager credentials;
// observers on the websocket read the server's events, so every wait is for an event or an
// element, with a deadline only.

import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext, watchProblems } from './lib/browser.mjs';
import { makeBundle, removeTemp } from './lib/docent.mjs';
import { openShell, waitForShownPage } from './lib/kiosk.mjs';
import { actLabels, chosenLabel, FAKE_MEDIA, museumTour, signIn, withConsoleServer } from './lib/operator.mjs';

let browser;
before(async () => {
  browser = await launchBrowser(FAKE_MEDIA);
});
after(() => browser?.close());

/** lib/operator.mjs's `withConsoleServer` with this file's browser. */
const withServer = (bundle, body) => withConsoleServer(browser, bundle, body);

test('search ignores case and accents, finds labels and groups; Up/Down choose, Enter fires the choice', { timeout: 60_000 }, async () => {
  const bundle = makeBundle({
    'acts.yaml': [
      '- Label: ORDER_COFFEE',
      '  Group: Café',
      '  Text:',
      "    - Un café, s'il vous plaît.",
      '- Label: COFFEE_MACHINE',
      '  Group: Café',
      '  Text:',
      '    - The coffee machine is over there.',
      '- Label: GOODBYE',
      '  Key: G',
      '  Text:',
      '    - Goodbye and thank you.',
      '  TextChild:',
      '    - Bye bye, see you!',
      '',
    ].join('\n'),
    'pages/index.html': '<!doctype html><title>home</title><h1>home</h1>\n',
  });
  try {
    await withServer(bundle, async ({ server, observer, newPage }) => {
      const page = await newPage();
      const problems = watchProblems(page);
      await signIn(page, server);
      assert.ok(await page.locator('.act-group h3', { hasText: 'Café' }).count(), 'no group "Café"');
      assert.equal(await page.locator('.act[data-label="GOODBYE"] kbd').textContent(), 'Alt+G');

      await page.keyboard.type('CAFE PLAIT');
      assert.deepEqual(await actLabels(page), ['ORDER_COFFEE']);
      assert.equal(await page.locator('#act-list mark').first().textContent(), 'café');
      await page.fill('#search', 'café');
      assert.deepEqual(await actLabels(page), ['ORDER_COFFEE', 'COFFEE_MACHINE'], 'a group name matches its acts');
      await page.fill('#search', 'coffee');
      assert.deepEqual((await actLabels(page)).sort(), ['COFFEE_MACHINE', 'ORDER_COFFEE']);
      // A text of another variant is found too (the child's "bye bye"); the preview shows the
      // current context's texts.
      await page.fill('#search', 'see you');
      assert.deepEqual(await actLabels(page), ['GOODBYE']);
      assert.match(await page.locator('#preview').textContent(), /Goodbye and thank you/);

      await page.fill('#search', 'coffee');
      const first = await chosenLabel(page);
      await page.keyboard.press('ArrowDown');
      const second = await chosenLabel(page);
      assert.notEqual(first, second);
      await page.keyboard.press('ArrowUp');
      assert.equal(await chosenLabel(page), first);
      await page.keyboard.press('ArrowDown');
      await page.keyboard.press('Enter');
      const fired = await observer.waitForEvent((e) => e.type === 'act.triggered');
      assert.equal(fired.label, second);
      assert.equal(await page.inputValue('#search'), '');

      // The preview shows the variant the server says an act speaks in the context: its own,
      // else Text standing in for it.
      await page.selectOption('#context', 'TextChild');
      await observer.waitForEvent((e) => e.type === 'context.changed' && e.context === 'TextChild');
      await page.fill('#search', 'see you');
      await page.locator('#preview .preview-texts', { hasText: 'Bye bye, see you!' }).waitFor();
      assert.equal(await page.locator('#preview .preview-variant').textContent(), 'TextChild');
      await page.fill('#search', 'coffee machine');
      assert.equal(await chosenLabel(page), 'COFFEE_MACHINE');
      await page.locator('#preview .preview-variant', { hasText: 'no TextChild text: says Text' }).waitFor();
      assert.deepEqual(problems, [], 'problems in the console');
    });
  } finally {
    removeTemp(bundle);
  }
});

test('type a word of an act\'s text anywhere, Enter: the kiosk in another browser shows the act\'s page; the context applies; F2 repeats', { timeout: 90_000 }, async () => {
  const bundle = museumTour();
  try {
    const events = await withServer(bundle, async ({ server, observer, newPage }) => {
      const kiosk = await newPage(newTouchContext);
      await openShell(kiosk, server, 'index.html');
      const page = await newPage();
      const problems = watchProblems(page);
      await signIn(page, server, 'Ada');

      // Typing goes to the search from anywhere (focus is on the page, not in the field).
      await page.locator('h1.brand').click();
      const keys = 'switches';
      await page.keyboard.type(keys);
      assert.equal(await page.inputValue('#search'), keys);
      assert.equal(await chosenLabel(page), 'EXPLAIN_MINICOMPUTER', `matches: ${await actLabels(page)}`);
      // The preview shows what it would say and do before it is fired.
      const preview = await page.locator('#preview').textContent();
      assert.match(preview, /Meridian M-16/);
      assert.match(preview, /DISPLAY_PAGE minicomputer\.html/);
      await page.keyboard.press('Enter');

      const fired = await observer.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'EXPLAIN_MINICOMPUTER');
      assert.equal(fired.source, 'operator');
      await waitForShownPage(kiosk, 'minicomputer.html');
      assert.equal(await page.inputValue('#search'), '', 'the search was not cleared');
      // The history shows the exact text said.
      const line = page.locator(`#history li[data-seq="${fired.seq}"]`);
      await line.waitFor();
      assert.ok((await line.textContent()).includes(fired.text), await line.textContent());
      assert.match(await line.textContent(), /operator \(you\)/);
      // Recently used lists it.
      await page.locator('.recent .act[data-label="EXPLAIN_MINICOMPUTER"]').waitFor();

      // The context selector sets the shared context; the preview follows it.
      await page.selectOption('#context', 'TextChild');
      await observer.waitForEvent((e) => e.type === 'context.changed' && e.context === 'TextChild');
      await page.waitForFunction(() => document.querySelector('#context').value === 'TextChild');
      await page.keyboard.press('F2');
      const again = await observer.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'EXPLAIN_MINICOMPUTER' && e.seq > fired.seq);
      assert.equal(again.variant, 'TextChild');
      assert.equal(again.source, 'operator');
      assert.deepEqual(problems, [], 'problems in the console');
    });
    const sources = events.filter((e) => e.type === 'act.triggered').map((e) => [e.label, e.source]);
    assert.deepEqual(sources, [['EXPLAIN_MINICOMPUTER', 'operator'], ['EXPLAIN_MINICOMPUTER', 'operator']]);
  } finally {
    removeTemp(bundle);
  }
});

test('keys reach the search from a focused selector or button; Enter fires the chosen act, never a focused button, once however long it is held; the choice survives redraws and is what the preview shows', { timeout: 90_000 }, async () => {
  const bundle = museumTour();
  const expected = [];
  try {
    const events = await withServer(bundle, async ({ server, observer, newPage }) => {
      const page = await newPage();
      const problems = watchProblems(page);
      await signIn(page, server, 'Ada');
      let last = 0;
      const fired = async (label) => {
        const e = await observer.waitForEvent((x) => x.type === 'act.triggered' && x.seq > last);
        assert.equal(e.label, label, `fired ${e.label}, not ${label}`);
        expected.push(label);
        last = e.seq;
      };
      const focused = () => page.evaluate(() => document.activeElement?.id || document.activeElement?.tagName);

      // Letters and arrows with the focus on the context selector go to the search; the
      // selector's own type-ahead ("t": TextGroup) and arrows would change the robot's context.
      await page.focus('#context');
      await page.keyboard.type('tchild');
      assert.equal(await page.inputValue('#search'), 'tchild');
      assert.equal(await page.inputValue('#context'), 'Text');
      await page.fill('#search', '');
      await page.focus('#context');
      await page.keyboard.press('ArrowDown');
      assert.equal(await page.inputValue('#context'), 'Text');
      assert.equal(await focused(), 'search', 'ArrowDown left the focus on the selector');
      assert.ok(await chosenLabel(page), 'ArrowDown chose nothing');
      await page.keyboard.press('ArrowUp');
      // Once a context is chosen, the selector lets go of the focus.
      await page.focus('#context');
      await page.selectOption('#context', 'TextChild');
      await observer.waitForEvent((e) => e.type === 'context.changed' && e.context === 'TextChild');
      assert.notEqual(await focused(), 'context');

      // Start clicked keeps the focus; Down and Enter then fire the chosen act, not Start again.
      await page.click('#session-start');
      await observer.waitForEvent((e) => e.type === 'session.started');
      assert.equal(await focused(), 'session-start');
      await page.keyboard.press('ArrowDown');
      assert.equal(await focused(), 'search');
      const first = await chosenLabel(page);
      await page.keyboard.press('Enter');
      await fired(first);
      // A search typed, then the focus on Sign out (not by Tab): Enter fires the act.
      await page.keyboard.type('bye bye');
      await page.focus('#signout');
      await page.keyboard.press('Enter');
      await fired('FAREWELL');
      assert.equal(await page.locator('#link').getAttribute('data-state'), 'online', 'Enter signed out');

      // Held keys (auto-repeat) fire once: Enter, Alt+W, F2; F4 stars once (not on and off).
      await page.keyboard.press('ArrowDown');
      const held = await chosenLabel(page);
      for (let i = 0; i < 3; i++) await page.keyboard.down('Enter');
      await page.keyboard.up('Enter');
      await fired(held);
      await page.keyboard.down('Alt');
      for (let i = 0; i < 3; i++) await page.keyboard.down('KeyW');
      await page.keyboard.up('KeyW');
      await page.keyboard.up('Alt');
      await fired('GREETING');
      for (let i = 0; i < 3; i++) await page.keyboard.down('F2');
      await page.keyboard.up('F2');
      await fired('GREETING');
      for (let i = 0; i < 2; i++) await page.keyboard.down('F4');
      await page.keyboard.up('F4');
      await page.locator(`.favourites .act[data-label="${held}"]`).waitFor();

      // The choice stays on its act when the list is redrawn: a star (F4), a context set elsewhere.
      await page.keyboard.type('the');
      const matches = await actLabels(page);
      assert.ok(matches.length > 3, `matches: ${matches}`);
      await page.keyboard.press('ArrowDown');
      await page.keyboard.press('ArrowDown');
      const picked = matches[2];
      assert.equal(await chosenLabel(page), picked);
      await page.keyboard.press('F4');
      await page.locator(`.act-row:has(.act[data-label="${picked}"]) .star[aria-pressed="true"]`).waitFor();
      assert.equal(await chosenLabel(page), picked, 'a star moved the choice');
      observer.send({ type: 'context', context: 'TextGroup', ref: 'elsewhere' });
      await page.waitForFunction(() => document.querySelector('#context').value === 'TextGroup');
      assert.equal(await chosenLabel(page), picked, 'a context change moved the choice');
      // The preview shows the chosen act, also while the mouse rests on another; Enter fires it.
      const other = matches.find((l) => l !== picked);
      await page.hover(`#act-list .act[data-label="${other}"]`);
      assert.equal(await page.locator('#preview .preview-label').textContent(), picked);
      await page.keyboard.press('Enter');
      await fired(picked);
      assert.deepEqual(problems, [], 'problems in the console');
    });
    // Nothing fired twice, Start marked once, the context changed only when asked.
    assert.deepEqual(events.filter((e) => e.type === 'act.triggered').map((e) => e.label), expected);
    assert.equal(events.filter((e) => e.type === 'session.started').length, 1);
    assert.deepEqual(events.filter((e) => e.type === 'context.changed').map((e) => e.context), ['TextChild', 'TextGroup']);
  } finally {
    removeTemp(bundle);
  }
});

test('keystrokes to find and fire each museum-tour act by one word of its text', { timeout: 60_000 }, async (t) => {
  const bundle = museumTour();
  try {
    await withServer(bundle, async ({ server, newPage }) => {
      const page = await newPage();
      await signIn(page, server);
      // For every act and every word of its texts, as the console's own search ranks them: the
      // operator types the word until the act is the first match (chosen, so Enter fires it);
      // if it is not first even with the whole word typed, Down moves the choice to it.
      // Keystrokes = letters typed + Down presses + Enter.
      const costs = await page.evaluate(async () => {
        const { readActs } = await import('/static/operator/acts.js');
        const { indexActs, search } = await import('/static/operator/search.js');
        const acts = readActs(await (await fetch('/api/acts')).json());
        const index = indexActs(acts);
        const result = [];
        for (const act of acts) {
          const texts = [...act.variants.values()].flat();
          const words = new Set(texts.flatMap((t) => t.toLowerCase().match(/[\p{L}\p{N}']+/gu) ?? []));
          for (const word of words) {
            let cost = null;
            for (let n = 1; n <= word.length && cost === null; n++) {
              const matches = search(index, word.slice(0, n), 'Text');
              if (matches[0]?.act === act) cost = { typed: n, down: 0 };
              else if (n === word.length) cost = { typed: n, down: matches.findIndex((m) => m.act === act) };
            }
            result.push({ label: act.label, word, ...cost, keys: cost.typed + cost.down + 1 });
          }
        }
        return { acts: acts.map((a) => a.label), keyed: acts.filter((a) => a.key).map((a) => `${a.label}=Alt+${a.key}`), result };
      });
      const byAct = new Map(costs.acts.map((label) => [label, costs.result.filter((c) => c.label === label)]));
      const all = costs.result.map((c) => c.keys).sort((a, b) => a - b);
      const best = [...byAct].filter(([, cs]) => cs.length).map(([label, cs]) => cs.reduce((a, b) => (b.keys < a.keys ? b : a)));
      const bestKeys = best.map((c) => c.keys).sort((a, b) => a - b);
      const stats = (xs) => {
        const mean = xs.reduce((a, b) => a + b, 0) / xs.length;
        const at = (q) => xs[Math.min(xs.length - 1, Math.floor(q * xs.length))];
        return `min ${xs[0]}, median ${at(0.5)}, mean ${mean.toFixed(1)}, p90 ${at(0.9)}, max ${xs.at(-1)}`;
      };
      t.diagnostic(`acts with text: ${best.length} of ${byAct.size}; (act, word) pairs: ${all.length}`);
      t.diagnostic(`acts with an Alt key (one chord, no search): ${costs.keyed.length}: ${costs.keyed.join(' ')}`);
      t.diagnostic(`any word of the act's texts, typed until the act is chosen (+ Down, + Enter): ${stats(all)}`);
      t.diagnostic(`the best word per act: ${stats(bestKeys)}`);
      // Words found in the texts of one act only: the ones an operator remembers an act by.
      const owners = new Map();
      for (const c of costs.result) owners.set(c.word, (owners.get(c.word) ?? 0) + 1);
      const own = costs.result.filter((c) => owners.get(c.word) === 1).map((c) => c.keys).sort((a, b) => a - b);
      t.diagnostic(`a word found in that act's texts only (${own.length} pairs): ${stats(own)}`);
      for (const c of best) t.diagnostic(`  ${c.label}: "${c.word.slice(0, c.typed)}" (of ${c.word})${c.down ? ` + ${c.down} Down` : ''} + Enter = ${c.keys}`);
      assert.ok(bestKeys.at(-1) <= 4, `an act needs ${bestKeys.at(-1)} keystrokes at best`);
      assert.ok(all[Math.floor(all.length / 2)] <= 6, 'the median word needs more than 6 keystrokes');
      assert.ok(own[Math.floor(own.length / 2)] <= 5, 'the median own word needs more than 5 keystrokes');
      // An act without text (SHOW_TOUR_MAP) is found by its label.
      for (const [label, cs] of byAct) {
        if (cs.length) continue;
        await page.fill('#search', label.toLowerCase().replace(/_/g, ' '));
        await page.dispatchEvent('#search', 'input');
        assert.equal(await chosenLabel(page), label);
      }
    });
  } finally {
    removeTemp(bundle);
  }
});
