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

test('after five wrong credentials the console says to wait instead of trying again', { timeout: 90_000 }, async () => {
  const bundle = museumTour();
  try {
    await withServer(bundle, async ({ server, newPage }) => {
      const page = await newPage();
      const sockets = [];
      page.on('websocket', (ws) => sockets.push(ws));
      await openConsole(page, server);
      let message = '';
      for (let attempt = 1; attempt <= 6; attempt++) {
        // Each refusal closes its socket; then the form is open again with the reason.
        const closed = new Promise((resolve) => page.once('websocket', (ws) => ws.on('close', resolve)));
        await submitCredential(page, `wrong-credential-number-${attempt}`);
        await closed;
        await page.waitForFunction(() => document.querySelector('#signin').open);
        message = await page.locator('#signin-error').textContent();
      }
      assert.match(message, /Too many failed attempts/);
      assert.equal(sockets.length, 6, 'the console retried by itself');
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

test('a dialog manager\'s proposal accepted with F9 is dispatched, one dismissed with Shift+F9 is not; two consoles see each other', { timeout: 90_000 }, async () => {
  const bundle = museumTour();
  try {
    const events = await withServer(bundle, async ({ server, observer, newPage, cleanup }) => {
      const dm = await connectWithToken(server, 'dm', 'e2e-dm');
      cleanup.unshift(() => dm.close());
      // A proposal made before any console is open: consoles find it pending when they sign in.
      dm.send({ type: 'propose', label: 'GREETING', context: null, reason: 'visitor smiled', ref: 'p1' });
      const first = await dm.waitFor((f) => f.type === 'proposed' && f.ref === 'p1');

      const a = await newPage();
      const b = await newPage();
      const problems = [...watchProblems(a), ...watchProblems(b)];
      await signIn(a, server, 'Ada');
      await signIn(b, server, 'Bob');
      for (const page of [a, b]) {
        const item = page.locator(`#proposal-list li[data-proposal="${first.proposal}"]`);
        await item.waitFor();
        assert.match(await item.textContent(), /visitor smiled/);
      }

      await a.keyboard.press('F9');
      const accepted = await observer.waitForEvent((e) => e.type === 'proposal.accepted' && e.proposal === first.proposal);
      const fired = await observer.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'GREETING');
      assert.equal(fired.source, 'operator');
      assert.equal(fired.trigger, accepted.trigger);
      // Gone from both consoles; Bob's history shows Ada's act with its text.
      for (const page of [a, b]) await page.locator('#proposals').waitFor({ state: 'hidden' });
      const line = b.locator(`#history li[data-seq="${fired.seq}"]`);
      await line.waitFor();
      assert.ok((await line.textContent()).includes(fired.text));
      assert.match(await line.textContent(), new RegExp(`operator #${accepted.client}`));
      // Replayed history and live events may overlap: each event is shown once.
      const seqs = await b.locator('#history li').evaluateAll((items) => items.map((i) => i.dataset.seq));
      assert.equal(new Set(seqs).size, seqs.length, `history shows an event twice: ${seqs}`);

      dm.send({ type: 'propose', label: 'FAREWELL', context: 'TextChild', reason: 'visitor leaving', ref: 'p2' });
      const second = await dm.waitFor((f) => f.type === 'proposed' && f.ref === 'p2');
      await a.locator(`#proposal-list li[data-proposal="${second.proposal}"]`).waitFor();
      await b.locator(`#proposal-list li[data-proposal="${second.proposal}"]`).waitFor();
      await b.keyboard.press('Shift+F9');
      await observer.waitForEvent((e) => e.type === 'proposal.dismissed' && e.proposal === second.proposal);
      await a.locator('#proposals').waitFor({ state: 'hidden' });
      await b.locator('#proposals').waitFor({ state: 'hidden' });
      assert.deepEqual(problems, [], 'problems in the consoles');
    });
    const acts = events.filter((e) => e.type === 'act.triggered').map((e) => e.label);
    assert.deepEqual(acts, ['GREETING'], 'the dismissed proposal was dispatched');
    assert.deepEqual(events.filter((e) => e.type.startsWith('proposal.')).map((e) => e.type), ['proposal.made', 'proposal.accepted', 'proposal.made', 'proposal.dismissed']);
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
