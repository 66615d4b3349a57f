// The operator console (`GET /operator`) in headless Chromium, driven by the keyboard as an
// operator drives it: signing in (and being refused), finding an act by a word of its text and
// firing it with Enter so that the kiosk open in another browser context changes page, Stop on
// Esc against a long SAY and a running drive, a dialog manager's proposals accepted with F9 and
// dismissed with Shift+F9 across two consoles, corpus marks, and the screenshot in
// docs/OPERATOR.md. Each test runs the real `docent` binary with operator and dialog-manager
// credentials; observers on the websocket read the server's events, so every wait is for an
// event or an element, with a deadline only.

import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext, watchProblems } from './lib/browser.mjs';
import { copyBundle, corpusEvents, freePort, makeBundle, removeTemp, REPO, startDocent } from './lib/docent.mjs';
import { openShell, waitForShownPage } from './lib/kiosk.mjs';
import {
  actLabels,
  chosenLabel,
  connectWithToken,
  newConsoleContext,
  openConsole,
  operatorToken,
  routeConsoleSocket,
  signIn,
  submitCredential,
  waitOnline,
} from './lib/operator.mjs';

/** Chromium's fake camera, granted without a prompt, on loopback: the kiosk's camera in the screenshot. */
const FAKE_MEDIA = ['--use-fake-device-for-media-stream', '--use-fake-ui-for-media-stream', '--allow-loopback-in-peer-connection'];

let browser;
before(async () => {
  browser = await launchBrowser(FAKE_MEDIA);
});
after(() => browser?.close());

/** The museum tour with the console's settings, logged speech and a drive of `speed` m/s. */
function museumTour({ speed = 0.5, camera = 'none' } = {}) {
  return copyBundle('museum-tour', {
    'docent.yaml': [
      'home: index.html',
      'contexts: [TextGroup, TextChild]',
      'speech: {adapter: log, rate: 160}',
      'drive:',
      `  speed: ${speed}`,
      '  pose_rate: 10',
      '  bounds: { min_x: 0, min_y: 0, max_x: 20, max_y: 12 }',
      'operator:',
      '  map: pages/images/map.png',
      `  camera: ${camera}`,
      '  situations: [question, misunderstanding, laughter, interruption, leaving]',
      '',
    ].join('\n'),
  });
}

/**
 * Runs `body` with a server on `bundle`, an observing operator client and a fresh console
 * context; closes everything afterwards and returns the corpus events of the run.
 */
async function withServer(bundle, body) {
  const server = await startDocent(bundle);
  const cleanup = [() => server.stop()];
  try {
    const observer = await connectWithToken(server, 'operator', 'e2e-observer');
    cleanup.unshift(() => observer.close());
    const newPage = async (makeContext = newConsoleContext) => {
      const context = await makeContext(browser);
      cleanup.unshift(() => context.close());
      return context.newPage();
    };
    await body({ server, observer, newPage, cleanup });
  } finally {
    for (const step of cleanup) await step();
  }
  return corpusEvents(server.corpusFile);
}

const clientsOf = async (server, role) =>
  Object.values((await server.api('/api/state')).clients).filter((c) => c.role === role);

test('the console needs the operator credential: none shows only the form, a wrong one is refused without retrying', { timeout: 90_000 }, async () => {
  const bundle = museumTour();
  try {
    await withServer(bundle, async ({ server, observer, newPage }) => {
      const page = await newPage();
      const problems = watchProblems(page);
      const sockets = [];
      page.on('websocket', (ws) => sockets.push(ws.url()));

      await openConsole(page, server);
      assert.ok(await page.locator('#signin').evaluate((d) => d.open), 'the sign-in dialog is not open');
      assert.equal(sockets.length, 0, 'the console connected before it had a credential');
      const settings = await fetch(`${server.base}/api/operator`);
      assert.equal(settings.status, 401, 'GET /api/operator answered without a credential');

      // A wrong credential: refused, said so, asked again, and no reconnecting.
      await submitCredential(page, 'not-the-operator-credential', 'Mallory');
      await page.locator('#signin-error').waitFor({ state: 'visible' });
      assert.match(await page.locator('#signin-error').textContent(), /refused/);
      assert.ok(await page.locator('#signin').evaluate((d) => d.open), 'the dialog closed after a refusal');
      assert.equal(await page.locator('#link').getAttribute('data-state'), 'refused');
      assert.deepEqual(await clientsOf(server, 'operator'), [{ name: 'e2e-observer', role: 'operator', verbs: [] }]);

      // The right one: connected, kept in this tab's sessionStorage and never in the URL.
      const token = operatorToken(server);
      await submitCredential(page, token, 'Ada');
      await waitOnline(page);
      const joined = await observer.waitForEvent((e) => e.type === 'client.connected' && e.name === 'Ada');
      assert.equal(joined.role, 'operator');
      assert.equal(sockets.length, 2, `one refused and one accepted connection, not a retry loop: ${sockets}`);
      assert.ok(!page.url().includes(token), page.url());
      assert.ok(sockets.every((url) => !url.includes(token)), 'the credential went into a websocket URL');
      const stored = await page.evaluate(() => ({ session: { ...sessionStorage }, local: { ...localStorage } }));
      assert.equal(stored.session['docent.operator.token'], token);
      assert.ok(!JSON.stringify(stored.local).includes(token), 'the credential is in localStorage');

      // A reload stays signed in (same tab); signing out forgets the credential.
      await page.reload();
      await waitOnline(page);
      assert.equal(await page.locator('#signin').evaluate((d) => d.open), false);
      await page.click('#signout');
      await observer.waitForEvent((e) => e.type === 'client.left' && e.role === 'operator' && e.client !== observer.welcome.client && e.client > joined.client);
      assert.ok(await page.locator('#signin').evaluate((d) => d.open), 'no sign-in form after signing out');
      assert.equal(await page.evaluate(() => sessionStorage.getItem('docent.operator.token')), null);
      assert.deepEqual(problems, [], 'problems in the console');
    });
  } finally {
    removeTemp(bundle);
  }
});

test('a lockout is waited out with a countdown, the credential kept and Stop in reach; a new credential refused again after the wait is asked for again', { timeout: 120_000 }, async () => {
  const bundle = museumTour();
  try {
    // A signed-in console whose computer is locked out by someone else's wrong credentials.
    await withServer(bundle, async ({ server, observer, newPage }) => {
      const page = await newPage();
      const socket = await routeConsoleSocket(page);
      await signIn(page, server, 'Ada');
      const joined = await observer.waitForEvent((e) => e.type === 'client.connected' && e.name === 'Ada');
      let answer;
      for (let i = 0; i < 5; i++) {
        answer = await fetch(`${server.base}/api/stop`, { method: 'POST', headers: { authorization: 'Bearer someone-elses-wrong-guess' } });
      }
      assert.equal(answer.status, 429, 'five wrong credentials did not lock this address out');
      const wait = Number(answer.headers.get('retry-after'));
      // The console's connection drops; signing in again is refused for the rest of the wait.
      socket.closeAll();
      await page.locator('#lockout:not([hidden])').waitFor();
      const refusedAt = Date.now();
      assert.equal(await page.locator('#link').getAttribute('data-state'), 'locked');
      assert.equal(await page.locator('#signin').evaluate((d) => d.open), false, 'a sign-in form covers the console');
      assert.equal(await page.evaluate(() => sessionStorage.getItem('docent.operator.token')), operatorToken(server), 'the credential was forgotten');
      assert.match(await page.locator('#lockout').textContent(), /refuses every sign-in from it for \d+ s more/);
      // The countdown runs, from no more than the server's wait (plus the second it adds).
      const first = Number(await page.locator('#lockout').getAttribute('data-seconds'));
      assert.ok(first >= 1 && first <= wait + 1, `countdown from ${first} s for a wait of ${wait} s`);
      await page.waitForFunction((s) => Number(document.querySelector('#lockout').dataset.seconds) < s, first);
      // Stop is in reach (nothing over it) and still tries the server, which refuses for now.
      await page.click('#stop');
      await page.locator('#notice', { hasText: 'locked out' }).waitFor();
      // After the wait the console signs in again by itself, with the credential it kept.
      const again = await observer.waitForEvent((e) => e.type === 'client.connected' && e.name === 'Ada' && e.client > joined.client, { timeout: (wait + 10) * 1000 });
      await page.locator('#link[data-state="online"]').waitFor();
      await page.locator('#lockout').waitFor({ state: 'hidden' });
      const retried = socket.sockets.at(-1);
      assert.ok(retried.at - refusedAt >= (first - 1) * 1000, `signed in again ${retried.at - refusedAt} ms after the refusal; the wait was ${first} s`);
      assert.ok(again.client > joined.client);
    });

    // Five wrong credentials typed into the form: the fifth is met with the lockout, waited out
    // without the form; refused again right after the wait, the credential is asked for again.
    await withServer(bundle, async ({ server, newPage }) => {
      const page = await newPage();
      const sockets = [];
      page.on('websocket', (ws) => sockets.push(ws));
      await openConsole(page, server);
      for (let attempt = 1; attempt <= 4; attempt++) {
        const closed = new Promise((resolve) => page.once('websocket', (ws) => ws.on('close', resolve)));
        await submitCredential(page, `wrong-credential-number-${attempt}`);
        await closed;
        await page.waitForFunction(() => document.querySelector('#signin').open);
        assert.match(await page.locator('#signin-error').textContent(), /refused/);
      }
      await submitCredential(page, 'wrong-credential-number-5');
      await page.locator('#lockout:not([hidden])').waitFor();
      assert.equal(await page.locator('#signin').evaluate((d) => d.open), false, 'the form came back during the wait');
      assert.equal(await page.locator('#link').getAttribute('data-state'), 'locked');
      const seconds = Number(await page.locator('#lockout').getAttribute('data-seconds'));
      await page.waitForFunction(() => document.querySelector('#signin').open, null, { timeout: (seconds + 10) * 1000 });
      assert.match(await page.locator('#signin-error').textContent(), /Still refused after the wait/);
      assert.equal(sockets.length, 6, 'not one try after the wait');
      assert.equal(await page.locator('#lockout').isVisible(), false);
    });
  } finally {
    removeTemp(bundle);
  }
});

test('an --open development server needs no credential; a restarted server is rejoined with the same one', { timeout: 90_000 }, async () => {
  const bundle = museumTour();
  const context = await newConsoleContext(browser);
  let server = await startDocent(bundle, { args: ['--open'] });
  try {
    const page = await context.newPage();
    const problems = watchProblems(page);
    await page.goto(`${server.base}/operator`);
    await waitOnline(page);
    assert.equal(await page.locator('#signin').evaluate((d) => d.open), false, 'an open server asked for a credential');
    assert.equal(await page.locator('#signout').isVisible(), false);
    assert.deepEqual(problems, [], 'problems in the console');
  } finally {
    await context.close();
    await server.stop();
  }

  // A guarded server restarted on the same port: the console reconnects with the credential
  // it kept, without asking, and works again.
  const port = await freePort();
  const again = await newConsoleContext(browser);
  server = await startDocent(bundle, { port });
  try {
    const page = await again.newPage();
    await signIn(page, server);
    await server.stop();
    await page.locator('#link[data-state="offline"]').waitFor();
    server = await startDocent(bundle, { port });
    await page.locator('#link[data-state="online"]').waitFor({ timeout: 30_000 });
    assert.equal(await page.locator('#signin').evaluate((d) => d.open), false, 'the console asked again after a restart');
    const observer = await connectWithToken(server, 'operator', 'e2e-observer');
    try {
      await page.keyboard.type('bye bye');
      await page.keyboard.press('Enter');
      const fired = await observer.waitForEvent((e) => e.type === 'act.triggered');
      assert.equal(fired.label, 'FAREWELL');
    } finally {
      await observer.close();
    }
  } finally {
    await again.close();
    await server.stop();
    removeTemp(bundle);
  }
});

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

test('Esc stops a long SAY and a running drive; Alt+<Key> fires an act', { timeout: 90_000 }, async () => {
  const words = Array.from({ length: 120 }, (_, i) => `word${i}`).join(' ');
  const bundle = makeBundle({
    'docent.yaml': [
      'home: index.html',
      'speech: {adapter: log, rate: 60}',
      'drive:',
      '  speed: 0.2',
      '  pose_rate: 20',
      '  bounds: { min_x: 0, min_y: 0, max_x: 100, max_y: 100 }',
      '',
    ].join('\n'),
    'acts.yaml': [
      '- Label: LONG_STORY',
      '  Key: L',
      '  Text:',
      `    - ${words}`,
      '- Label: DRIVE_FAR',
      '  Group: Moving',
      '  Key: D',
      '  Cmds:',
      '    - SET_WAYPOINT 90 90',
      '    - DRIVE_START',
      '',
    ].join('\n'),
    'pages/index.html': '<!doctype html><title>home</title><h1>home</h1>\n',
  });
  try {
    const events = await withServer(bundle, async ({ observer, server, newPage }) => {
      const page = await newPage();
      const problems = watchProblems(page);
      await signIn(page, server);
      assert.ok(await page.locator('.act-group h3', { hasText: 'Moving' }).count(), 'no group "Moving"');

      await page.keyboard.press('Alt+KeyD');
      const drive = await observer.waitForEvent((e) => e.type === 'command.started' && e.verb === 'DRIVE_START');
      await observer.waitForEvent((e) => e.type === 'pose' && e.moving);
      await page.keyboard.press('Alt+KeyL');
      const say = await observer.waitForEvent((e) => e.type === 'command.started' && e.verb === 'SAY');
      assert.equal(say.label, 'LONG_STORY');
      await page.locator('#speaking', { hasText: 'word0 word1' }).waitFor();
      await page.locator(`#queue li[data-command="${drive.command}"]`).waitFor();

      // Esc, with the focus in the search field as it usually is.
      await page.focus('#search');
      await page.keyboard.press('Escape');
      const stop = await observer.waitForEvent((e) => e.type === 'stop');
      assert.equal(stop.source, 'operator');
      await observer.waitForEvent((e) => e.type === 'command.cancelled' && e.command === say.command);
      await observer.waitForEvent((e) => e.type === 'command.cancelled' && e.command === drive.command);
      const halted = await observer.waitForEvent((e) => e.type === 'pose' && !e.moving);
      const state = await server.api('/api/state');
      assert.equal(state.pose.moving, false);
      assert.deepEqual([state.pose.x, state.pose.y], [halted.x, halted.y], 'the robot moved on after the stop');
      assert.equal(state.speaking, null);
      assert.ok(halted.x < 90 && halted.y < 90, 'the robot reached its goal before the stop');
      // The console shows it: silence, nothing running.
      await page.locator('#speaking', { hasText: 'silent' }).waitFor();
      await page.locator('#queue', { hasText: 'nothing running' }).waitFor();
      assert.deepEqual(problems, [], 'problems in the console');
    });
    const afterStop = events.slice(events.findIndex((e) => e.type === 'stop'));
    assert.ok(!afterStop.some((e) => e.type === 'pose' && e.moving), 'a moving pose after the stop');
  } finally {
    removeTemp(bundle);
  }
});

test('Esc stops before the first welcome and during an IME composition; a websocket stop unanswered within 500 ms goes over HTTP too', { timeout: 90_000 }, async () => {
  const bundle = museumTour();
  try {
    const events = await withServer(bundle, async ({ server, observer, newPage }) => {
      const page = await newPage();
      const socket = await routeConsoleSocket(page);
      const httpStops = [];
      page.on('request', (request) => {
        if (new URL(request.url()).pathname === '/api/stop') httpStops.push(request);
      });
      const nextHttpStop = () => page.waitForRequest((request) => new URL(request.url()).pathname === '/api/stop');

      // Signed in, but the server never answers the hello: Esc stops over HTTP with the credential.
      socket.mode = 'silent';
      await openConsole(page, server);
      await submitCredential(page, operatorToken(server), 'Ada');
      await socket.waitForSocket(1);
      await page.locator('#link[data-state="connecting"]').waitFor();
      let request = nextHttpStop();
      await page.keyboard.press('Escape');
      const first = await request;
      assert.deepEqual([first.method(), first.headers().authorization], ['POST', `Bearer ${operatorToken(server)}`]);
      const early = await observer.waitForEvent((e) => e.type === 'stop');
      assert.equal(early.source, 'http');
      await page.locator('#notice', { hasText: 'not connected' }).waitFor();

      // A half-open socket: welcomed, but the stop frame is lost on its way. Half a second
      // without the `stopped` answer, the console stops over HTTP as well.
      socket.mode = 'dropStops';
      socket.closeAll();
      await socket.waitForSocket(2);
      await waitOnline(page);
      await page.evaluate(() => addEventListener('keydown', (e) => e.key === 'Escape' && (window.e2eEscapeAt = e.timeStamp), { capture: true }));
      request = nextHttpStop();
      await page.keyboard.press('Escape');
      await request;
      const late = await observer.waitForEvent((e) => e.type === 'stop' && e.seq > early.seq);
      assert.equal(late.source, 'http');
      // The page's own clock: from the key press to the start of the HTTP request.
      const after = await page.evaluate(async () => {
        const stops = () => performance.getEntriesByType('resource').filter((r) => r.name.endsWith('/api/stop'));
        while (stops().length < 2) await new Promise((resolve) => requestAnimationFrame(resolve));
        return Math.round(stops()[1].startTime - window.e2eEscapeAt);
      });
      assert.ok(after >= 450 && after < 5_000, `the HTTP stop came ${after} ms after Esc`);
      assert.ok(socket.sockets[1].sent.some((m) => JSON.parse(m).type === 'stop'), 'the console did not try its websocket first');
      await page.locator('#notice', { hasText: 'did not answer' }).waitFor();

      // A healthy socket whose every event frame arrives twice; Esc while an IME composes
      // a word in the search field stops over the websocket, which answers.
      socket.mode = 'pass';
      socket.duplicate = true;
      socket.closeAll();
      await socket.waitForSocket(3);
      await waitOnline(page);
      await page.keyboard.press('Alt+KeyW');
      const greeting = await observer.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'GREETING');
      await page.focus('#search');
      await page.evaluate(() => {
        window.e2eEscapes = [];
        addEventListener('keydown', (e) => e.key === 'Escape' && window.e2eEscapes.push(e.isComposing), { capture: true });
      });
      const cdp = await page.context().newCDPSession(page);
      await cdp.send('Input.imeSetComposition', { text: 'す', selectionStart: 1, selectionEnd: 1 });
      await page.keyboard.press('Escape');
      const composed = await observer.waitForEvent((e) => e.type === 'stop' && e.seq > late.seq);
      assert.equal(composed.source, 'operator');
      assert.deepEqual(await page.evaluate(() => window.e2eEscapes), [true], 'Esc was not pressed during a composition');
      // Answered (`stopped`): nothing waits for an answer, so no HTTP stop follows.
      await page.locator('#stop[data-pending="0"]').waitFor();
      assert.equal(httpStops.length, 2, 'an answered stop went over HTTP too');
      // Each event once, although every one arrived twice.
      await page.locator(`#history li[data-seq="${composed.seq}"]`).waitFor();
      const seqs = await page.locator('#history li').evaluateAll((items) => items.map((i) => i.dataset.seq));
      assert.equal(new Set(seqs).size, seqs.length, `history shows an event twice: ${seqs}`);
      assert.ok(seqs.includes(String(greeting.seq)), `no GREETING in the history: ${seqs}`);
    });
    const stops = events.filter((e) => e.type === 'stop' && e.source !== 'server'); // not the server's own at shutdown
    assert.deepEqual(stops.map((e) => e.source), ['http', 'http', 'operator']);
  } finally {
    removeTemp(bundle);
  }
});

test('proposals come newest first with their age; F9 accepts the newest, Shift+F9 dismisses the newest; a leaving dialog manager\'s proposal is withdrawn; two consoles see each other', { timeout: 90_000 }, async () => {
  const bundle = museumTour();
  try {
    const events = await withServer(bundle, async ({ server, observer, newPage, cleanup }) => {
      const dm = await connectWithToken(server, 'dm', 'e2e-dm');
      cleanup.unshift(() => dm.close());
      // Two proposals made before any console is open: consoles find them pending when they sign in.
      dm.send({ type: 'propose', label: 'GREETING', context: null, reason: 'visitor smiled', ref: 'p1' });
      const first = await dm.waitFor((f) => f.type === 'proposed' && f.ref === 'p1');
      dm.send({ type: 'propose', label: 'FAREWELL', context: 'TextChild', reason: 'visitor leaving', ref: 'p2' });
      const second = await dm.waitFor((f) => f.type === 'proposed' && f.ref === 'p2');

      const a = await newPage();
      const b = await newPage();
      const problems = [...watchProblems(a), ...watchProblems(b)];
      await signIn(a, server, 'Ada');
      await signIn(b, server, 'Bob');
      const order = (page) => page.locator('#proposal-list li').evaluateAll((items) => items.map((i) => Number(i.dataset.proposal)));
      for (const page of [a, b]) {
        await page.locator(`#proposal-list li[data-proposal="${first.proposal}"]`).waitFor();
        assert.deepEqual(await order(page), [second.proposal, first.proposal], 'not newest first');
        assert.match(await page.locator('#proposal-list li').first().textContent(), /visitor leaving/);
      }
      // Each shows its age, and it counts on.
      const age = a.locator(`#proposal-list li[data-proposal="${first.proposal}"] .proposal-age`);
      const was = await age.textContent();
      assert.match(was, /^(just now|\d+ s ago)$/);
      await a.waitForFunction((t) => document.querySelector('#proposal-list li:last-child .proposal-age').textContent !== t, was);
      assert.match(await age.textContent(), /^\d+ s ago$/);

      // F9: the newest (FAREWELL, the one that just came) is accepted.
      await a.keyboard.press('F9');
      const accepted = await observer.waitForEvent((e) => e.type === 'proposal.accepted');
      assert.equal(accepted.proposal, second.proposal, 'F9 did not accept the newest proposal');
      const fired = await observer.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'FAREWELL');
      assert.equal(fired.source, 'operator');
      assert.equal(fired.trigger, accepted.trigger);
      for (const page of [a, b]) await page.locator(`#proposal-list li[data-proposal="${second.proposal}"]`).waitFor({ state: 'detached' });
      // Bob's history shows Ada's act with its text.
      const line = b.locator(`#history li[data-seq="${fired.seq}"]`);
      await line.waitFor();
      assert.ok((await line.textContent()).includes(fired.text));
      assert.match(await line.textContent(), new RegExp(`operator #${accepted.client}`));
      // Replayed history and live events may overlap: each event is shown once.
      const seqs = await b.locator('#history li').evaluateAll((items) => items.map((i) => i.dataset.seq));
      assert.equal(new Set(seqs).size, seqs.length, `history shows an event twice: ${seqs}`);

      // Shift+F9 on Bob's console: the newest left (GREETING) is dismissed.
      await b.keyboard.press('Shift+F9');
      const dismissed = await observer.waitForEvent((e) => e.type === 'proposal.dismissed');
      assert.equal(dismissed.proposal, first.proposal);
      await a.locator('#proposals').waitFor({ state: 'hidden' });
      await b.locator('#proposals').waitFor({ state: 'hidden' });

      // A dialog manager that leaves takes its waiting proposal with it.
      const planner = await connectWithToken(server, 'dm', 'e2e-planner');
      planner.send({ type: 'propose', label: 'ANY_QUESTIONS', context: null, reason: 'a pause', ref: 'p3' });
      const third = await planner.waitFor((f) => f.type === 'proposed' && f.ref === 'p3');
      await a.locator(`#proposal-list li[data-proposal="${third.proposal}"]`).waitFor();
      await planner.close();
      const withdrawn = await observer.waitForEvent((e) => e.type === 'proposal.withdrawn');
      assert.equal(withdrawn.proposal, third.proposal);
      await a.locator('#proposals').waitFor({ state: 'hidden' });
      const note = a.locator(`#history li[data-seq="${withdrawn.seq}"]`);
      await note.waitFor();
      assert.match(await note.textContent(), /withdrawn proposal \d+: ANY_QUESTIONS/);
      assert.deepEqual(problems, [], 'problems in the consoles');
    });
    const acts = events.filter((e) => e.type === 'act.triggered').map((e) => e.label);
    assert.deepEqual(acts, ['FAREWELL'], 'the dismissed or withdrawn proposal was dispatched');
    assert.deepEqual(events.filter((e) => e.type.startsWith('proposal.')).map((e) => e.type), [
      'proposal.made',
      'proposal.made',
      'proposal.accepted',
      'proposal.dismissed',
      'proposal.made',
      'proposal.withdrawn',
    ]);
  } finally {
    removeTemp(bundle);
  }
});

test('the state fetched after signing in does not undo newer events; /api/state and /api/operator are asked with the credential', { timeout: 60_000 }, async () => {
  const words = Array.from({ length: 120 }, (_, i) => `word${i}`).join(' ');
  const bundle = makeBundle({
    'docent.yaml': 'home: index.html\nspeech: {adapter: log, rate: 60}\n',
    'acts.yaml': [
      '- Label: LONG_STORY',
      '  Text:',
      `    - ${words}`,
      '- Label: SHOW_OTHER',
      '  Cmds:',
      '    - DISPLAY_PAGE other.html',
      '',
    ].join('\n'),
    'pages/index.html': '<!doctype html><title>home</title><h1>home</h1>\n',
    'pages/other.html': '<!doctype html><title>other</title><h1>other</h1>\n',
  });
  try {
    await withServer(bundle, async ({ server, observer, newPage }) => {
      // The robot speaks before the console comes.
      await server.trigger('LONG_STORY');
      await observer.waitForEvent((e) => e.type === 'command.started' && e.verb === 'SAY');
      const page = await newPage();
      const problems = watchProblems(page);
      const credentials = {};
      page.on('request', (request) => {
        const route = new URL(request.url()).pathname;
        if (route === '/api/state' || route === '/api/operator') credentials[route] = request.headers().authorization;
      });
      // The snapshot is taken at once but reaches the console only after newer events.
      let release;
      const held = new Promise((resolve) => (release = resolve));
      let taken;
      const snapshotTaken = new Promise((resolve) => (taken = resolve));
      await page.route('**/api/state', async (route) => {
        const response = await route.fetch();
        taken(await response.json());
        await held;
        await route.fulfill({ response });
      });
      await signIn(page, server);
      const snapshot = await snapshotTaken;
      assert.equal(snapshot.display.page, 'index.html');
      assert.match(snapshot.speaking ?? '', /^word0 word1/);
      // Meanwhile the speech is stopped and the kiosk shows another page.
      await server.api('/api/stop', {});
      await server.trigger('SHOW_OTHER');
      await page.locator('#kiosk-page', { hasText: 'other.html' }).waitFor();
      await observer.waitForEvent((e) => e.type === 'command.done' && e.verb === 'DISPLAY_PAGE');
      await page.locator('#queue', { hasText: 'nothing running' }).waitFor();
      release();
      await page.waitForFunction(() => document.body.dataset.snapshots === '1');
      assert.equal(await page.locator('#kiosk-page').textContent(), 'other.html', 'the snapshot put back the old page');
      assert.equal(await page.locator('#speaking').textContent(), 'silent', 'the snapshot put back the old speech');
      assert.equal(await page.locator('#queue').textContent(), 'nothing running', 'the snapshot put back the old queue');
      const bearer = `Bearer ${operatorToken(server)}`;
      assert.deepEqual(credentials, { '/api/state': bearer, '/api/operator': bearer });
      assert.deepEqual(problems, [], 'problems in the console');
    });
  } finally {
    removeTemp(bundle);
  }
});

test('session, visitor group and situation marks reach the corpus; the children group sets the context', { timeout: 90_000 }, async () => {
  const bundle = museumTour();
  try {
    const events = await withServer(bundle, async ({ server, observer, newPage }) => {
      const page = await newPage();
      const problems = watchProblems(page);
      await signIn(page, server);
      await page.click('#session-start');
      const started = await observer.waitForEvent((e) => e.type === 'session.started');
      await page.locator('#session', { hasText: `session ${started.session}` }).waitFor();
      await page.click('#visitor-groups button[data-group="children"]');
      await observer.waitForEvent((e) => e.type === 'visitor.group' && e.group === 'children');
      await page.waitForFunction(() => document.querySelector('#context').value === 'TextChild');
      await page.keyboard.press('Alt+Shift+Digit1');
      await observer.waitForEvent((e) => e.type === 'situation.marked' && e.situation === 'question');
      await page.click('#situation-buttons button[data-situation="laughter"]');
      await observer.waitForEvent((e) => e.type === 'situation.marked' && e.situation === 'laughter');
      await page.click('#session-end');
      await observer.waitForEvent((e) => e.type === 'session.ended');
      await page.locator('#session', { hasText: 'no session' }).waitFor();
      assert.deepEqual(problems, [], 'problems in the console');
    });
    const marks = events
      .filter((e) => ['session.started', 'visitor.group', 'situation.marked', 'session.ended'].includes(e.type))
      .map((e) => [e.type, e.group ?? e.situation ?? null, e.source]);
    assert.deepEqual(marks, [
      ['session.started', null, 'operator'],
      ['visitor.group', 'children', 'operator'],
      ['situation.marked', 'question', 'operator'],
      ['situation.marked', 'laughter', 'operator'],
      ['session.ended', null, 'operator'],
    ]);
    const group = events.find((e) => e.type === 'visitor.group');
    assert.equal(group.context, 'TextChild');
  } finally {
    removeTemp(bundle);
  }
});

test('screenshot of the console on the museum tour (docs/screenshots/operator.png)', { timeout: 90_000 }, async () => {
  const bundle = museumTour({ speed: 1.5, camera: 'webrtc' });
  try {
    await withServer(bundle, async ({ server, observer, newPage, cleanup }) => {
      const kiosk = await newPage(newTouchContext);
      await openShell(kiosk, server, 'index.html');
      const projector = await newPage();
      await projector.goto(`${server.base}/projector`);
      const page = await newPage();
      const problems = watchProblems(page);
      await signIn(page, server, 'Ada');

      await page.click('#session-start');
      await page.click('#visitor-groups button[data-group="group"]');
      await observer.waitForEvent((e) => e.type === 'context.changed' && e.context === 'TextGroup');
      await page.keyboard.press('Alt+KeyW'); // the museum tour's key for GREETING
      await observer.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'GREETING');
      await page.keyboard.type('first stop');
      await page.keyboard.press('Enter');
      await observer.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'GO_TO_MINICOMPUTER');
      await observer.waitForEvent((e) => e.type === 'pose' && e.x > 2.5);

      const dm = await connectWithToken(server, 'dm', 'tour-planner');
      cleanup.unshift(() => dm.close());
      dm.send({ type: 'propose', label: 'ANY_QUESTIONS', context: null, reason: 'visitors stopped at the exhibit', ref: 'p' });
      await page.locator('#proposal-list li').waitFor();
      // Browsing rather than searching, to show the groups, keys, favourites and recently used:
      // two stars, and Down to the act to show in the preview.
      for (const label of ['ANY_QUESTIONS', 'DONT_KNOW']) await page.click(`.act-row:has(.act[data-label="${label}"]) .star`);
      for (let i = 0; i < 60 && (await chosenLabel(page)) !== 'FOLLOW_ME'; i++) await page.keyboard.press('ArrowDown');
      assert.equal(await chosenLabel(page), 'FOLLOW_ME');
      await page.locator('#map .robot:not([hidden])').waitFor();
      await page.locator('#camera[data-state="live"]').waitFor();
      await page.waitForFunction(() => document.querySelector('#camera video')?.currentTime > 0);

      const file = path.join(REPO, 'docs/screenshots/operator.png');
      fs.mkdirSync(path.dirname(file), { recursive: true });
      await page.screenshot({ path: file });
      assert.ok(fs.statSync(file).size > 20_000, 'the screenshot is suspiciously small');
      assert.deepEqual(problems, [], 'problems in the console');
    });
  } finally {
    removeTemp(bundle);
  }
});
