// Several languages (docs/AUTHORING.md, "Several languages") as a visitor and an operator meet
// them, on the two-language fixture bundle (tests/fixtures/two-languages: English, the default,
// and German) in headless Chromium with touch: a visitor taps the page's `data-language="de"`
// button, the kiosk shows pages/de/, an act then speaks its German text (the corpus's
// `act.triggered` and the SAY's `command.sent` say `de`), a link to a page without a German
// version shows the English one inside the German session, a refused language is shown on the
// kiosk, the operator switches back with the console's language buttons by keyboard, and a
// visitor session's end sets the default language again. Also `/pages/de/` over plain HTTP:
// the German page, the English fallback, 404 for a page in neither, nothing outside the bundle
// through `..`; and axe-core on the German page and on the console with its language
// buttons. Every wait is for an event or an element.

import assert from 'node:assert/strict';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext, watchExceptions } from './lib/browser.mjs';
import { corpusEvents, freePort, REPO, startDocent } from './lib/docent.mjs';
import { openShell, shownPage, waitForShownPage } from './lib/kiosk.mjs';
import { outage, recordConnections } from './lib/outage.mjs';
import { connectWithToken, newConsoleContext, signIn } from './lib/operator.mjs';

const FIXTURE = path.join(REPO, 'tests/fixtures/two-languages');
const AXE = fs.readFileSync(path.join(REPO, 'tests/e2e/node_modules/axe-core/axe.min.js'), 'utf8');

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

/**
 * The serious and critical axe-core violations (WCAG 2.2 A and AA) on `page`, or only inside
 * the element `within` (a CSS selector), one line each.
 */
async function axeViolations(page, within = null) {
  await page.addScriptTag({ content: AXE });
  const values = ['wcag2a', 'wcag2aa', 'wcag21a', 'wcag21aa', 'wcag22aa'];
  const result = await page.evaluate(
    ([tags, scope]) => window.axe.run(scope ? { include: [[scope]] } : document, { runOnly: { type: 'tag', values: tags } }),
    [values, within],
  );
  return result.violations
    .filter((v) => v.impact === 'serious' || v.impact === 'critical')
    .map((v) => `${v.id} at ${v.nodes[0].target.join(' ')}: ${v.nodes[0].failureSummary}`);
}

/** GET `rawPath` exactly as written (no URL normalisation of `..`): status and body. */
function getRaw(server, rawPath) {
  return new Promise((resolve, reject) => {
    const req = http.get({ host: '127.0.0.1', port: server.port, path: rawPath }, (res) => {
      let body = '';
      res.setEncoding('utf8');
      res.on('data', (chunk) => (body += chunk));
      res.on('end', () => resolve({ status: res.statusCode, body }));
    });
    req.on('error', reject);
  });
}

test('a visitor chooses German on the touchscreen; the operator switches back; a session end resets it', { timeout: 120_000 }, async () => {
  const server = await startDocent(FIXTURE);
  const observer = await connectWithToken(server, 'operator', 'e2e-observer');
  const kioskContext = await newTouchContext(browser);
  const consoleContext = await newConsoleContext(browser);
  try {
    const kiosk = await kioskContext.newPage();
    const exceptions = watchExceptions(kiosk);
    let frame = await openShell(kiosk, server, 'index.html');

    // The visitor taps "Deutsch": the kiosk shows the German home page.
    await frame.tap('#deutsch');
    const chosen = await observer.waitForEvent((e) => e.type === 'language.changed' && e.language === 'de');
    assert.equal(chosen.source, 'kiosk');
    frame = await waitForShownPage(kiosk, 'de/index.html');
    assert.equal(await frame.textContent('#title'), 'Willkommen');

    // An act tapped now speaks German.
    await frame.tap('#greet');
    const greeting = await observer.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'GREETING');
    assert.deepEqual([greeting.text, greeting.language], ['Willkommen im Museum!', 'de']);
    const say = await observer.waitForEvent((e) => e.type === 'command.sent' && e.verb === 'SAY' && e.trigger === greeting.trigger);
    assert.deepEqual([say.arg, say.args?.language], ['Willkommen im Museum!', 'de']);

    // The tour page has no German version: the English one, still in the German session,
    // reported as the bundle names it.
    await frame.tap('#next');
    frame = await waitForShownPage(kiosk, 'de/tour.html');
    assert.equal(await frame.textContent('#title'), 'The first room');
    await observer.waitForEvent((e) => e.type === 'display.changed' && e.page === 'tour.html');
    await frame.tap('#bye');
    const bye = await observer.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'GOODBYE');
    assert.deepEqual([bye.text, bye.language], ['Danke für Ihren Besuch.', 'de']);

    // A language this page does not offer is refused, visibly: the shell's notice, the button marked.
    await frame.evaluate(() => document.body.insertAdjacentHTML('beforeend', '<button id="french" data-language="fr">Français</button>'));
    await frame.tap('#french');
    await kiosk.locator('#docent-notice:not([hidden])', { hasText: 'not available' }).waitFor();
    await frame.locator('#french.docent-refused').waitFor();
    assert.equal((await server.api('/api/state')).language, 'de');

    // The operator sees German and switches back to English with the keyboard.
    const console_ = await consoleContext.newPage();
    await signIn(console_, server);
    const english = console_.locator('#language-buttons button[data-language="en"]');
    await console_.locator('#language-buttons button[data-language="de"][aria-pressed="true"]').waitFor();
    assert.equal(await console_.locator('#language-pick').isVisible(), true);
    // The language buttons only: the rest of the console is accessibility.test.mjs's.
    assert.deepEqual(await axeViolations(console_, '#language-pick'), [], 'the console\'s language buttons');
    await english.focus();
    await console_.keyboard.press('Enter');
    const back = await observer.waitForEvent((e) => e.type === 'language.changed' && e.language === 'en');
    assert.equal(back.source, 'operator');
    await console_.locator('#language-buttons button[data-language="en"][aria-pressed="true"]').waitFor();
    await console_.locator('#history li[data-type="language.changed"]', { hasText: 'language → en' }).first().waitFor();
    frame = await waitForShownPage(kiosk, 'tour.html');

    // German again from the home page; a visitor session's end sets English again.
    await frame.tap('#home');
    frame = await waitForShownPage(kiosk, 'index.html');
    await frame.tap('#deutsch');
    await observer.waitForEvent((e) => e.type === 'language.changed' && e.language === 'de');
    await waitForShownPage(kiosk, 'de/index.html');
    observer.send({ type: 'mark', mark: 'session_start', ref: 's1' });
    await observer.waitForEvent((e) => e.type === 'session.started');
    observer.send({ type: 'mark', mark: 'session_end', ref: 's2' });
    const reset = await observer.waitForEvent((e) => e.type === 'language.changed' && e.language === 'en');
    assert.equal(reset.source, 'server');
    frame = await waitForShownPage(kiosk, 'index.html');
    assert.equal(await frame.textContent('#title'), 'Welcome');
    await console_.locator('#language-note', { hasText: 'set by server' }).waitFor();
    assert.deepEqual(exceptions, []);
  } finally {
    await consoleContext.close();
    await kioskContext.close();
    await observer.close();
    await server.stop();
  }
  // The corpus keeps the language of each utterance.
  const said = corpusEvents(server.corpus).filter((e) => e.type === 'act.triggered').map((e) => [e.label, e.language]);
  assert.deepEqual(said, [['GREETING', 'de'], ['GOODBYE', 'de']]);
});

test('a server restarted mid-visit goes on in the visitor\'s language, on the page the visitor was on', { timeout: 90_000 }, async () => {
  let server = await startDocent(FIXTURE, { port: await freePort() });
  const kioskContext = await newTouchContext(browser);
  try {
    const kiosk = await kioskContext.newPage();
    const exceptions = watchExceptions(kiosk);
    let frame = await openShell(kiosk, server, 'index.html');
    await frame.tap('#deutsch');
    frame = await waitForShownPage(kiosk, 'de/index.html');
    await recordConnections(kiosk);
    const during = async () => {
      // The calm notice speaks the page's language.
      const notice = frame.locator('.docent-offline-notice');
      await notice.waitFor({ state: 'visible' });
      assert.equal(await notice.textContent(), 'Einen Moment bitte: Der Roboter ist gleich wieder da.');
    };
    const result = await outage({ server, bundle: FIXTURE, tab: kiosk, lengthMs: 1_500, during });
    server = result.server;
    assert.equal(await shownPage(kiosk), '/pages/de/index.html', 'the visitor lost the German page');
    const state = await server.api('/api/state');
    assert.equal(state.language, 'de', 'the restarted server did not go on in German');
    frame = await waitForShownPage(kiosk, 'de/index.html');
    const observer = await connectWithToken(server, 'operator', 'e2e-observer');
    try {
      await frame.tap('#greet');
      const greeting = await observer.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'GREETING');
      assert.deepEqual([greeting.text, greeting.language], ['Willkommen im Museum!', 'de']);
    } finally {
      await observer.close();
    }
    assert.deepEqual(exceptions, []);
  } finally {
    await kioskContext.close();
    await server.stop();
  }
});

test('/pages/de/ serves the German page, else the English one, 404 for neither, nothing outside the bundle', { timeout: 60_000 }, async () => {
  const server = await startDocent(FIXTURE);
  try {
    const german = await getRaw(server, '/pages/de/index.html');
    assert.equal(german.status, 200);
    assert.match(german.body, /Willkommen/);
    const fallback = await getRaw(server, '/pages/de/tour.html');
    assert.equal(fallback.status, 200);
    assert.match(fallback.body, /The first room/);
    assert.equal((await getRaw(server, '/pages/de/style.css')).status, 200);
    assert.equal((await getRaw(server, '/pages/de/nowhere.html')).status, 404);
    assert.equal((await getRaw(server, '/pages/fr/index.html')).status, 404, 'fr is not one of the languages');
    for (const escape of ['/pages/de/../../docent.yaml', '/pages/de/..%2F..%2Fdocent.yaml', '/pages/de/%2e%2e/%2e%2e/acts.yaml']) {
      const res = await getRaw(server, escape);
      assert.ok(res.status >= 400 && res.status < 500, `${escape}: HTTP ${res.status}`);
      assert.doesNotMatch(res.body, /languages:|Label:/, `${escape} reached a bundle file outside pages/`);
    }
  } finally {
    await server.stop();
  }
});

test('the German page passes axe (WCAG 2.2 AA, serious and critical)', { timeout: 60_000 }, async () => {
  const server = await startDocent(FIXTURE);
  const context = await newTouchContext(browser);
  try {
    const page = await context.newPage();
    const res = await page.goto(`${server.base}/pages/de/index.html`, { waitUntil: 'load' });
    assert.equal(res.status(), 200);
    assert.deepEqual(await axeViolations(page), []);
  } finally {
    await context.close();
    await server.stop();
  }
});
