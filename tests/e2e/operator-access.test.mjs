// The operator console (`GET /operator`) in headless Chromium: who may use it. Signing in (and
// being refused, without retrying), the credential kept for the tab and never put in a URL,
// signing out, someone else's wrong credentials never keeping a signed-in console from Stop, a
// wrong credential's wait counted down, an `--open`
// development server and a restarted one, and the state fetched after signing in, asked with the
// credential and never undoing newer events. Each test runs the real `docent` binary with
// operator and dialog-manager credentials; observers on the websocket read the server's events,
// so every wait is for an event or an element, with a deadline only. Keys and search are in
// operator-keys.test.mjs, Stop, proposals, marks and the screenshot in operator-control.test.mjs.

import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';

import { launchBrowser, watchProblems } from './lib/browser.mjs';
import { freePort, makeBundle, removeTemp, startDocent } from './lib/docent.mjs';
import {
  connectWithToken,
  FAKE_MEDIA,
  museumTour,
  newConsoleContext,
  openConsole,
  operatorToken,
  routeConsoleSocket,
  signIn,
  submitCredential,
  waitOnline,
  withConsoleServer,
} from './lib/operator.mjs';

let browser;
before(async () => {
  browser = await launchBrowser(FAKE_MEDIA);
});
after(() => browser?.close());

/** lib/operator.mjs's `withConsoleServer` with this file's browser. */
const withServer = (bundle, body) => withConsoleServer(browser, bundle, body);

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
      // (The reload cancels the requests the console had under way: no problem of its own.)
      const aborted = (p) => /^request failed: .*\(net::ERR_ABORTED\)$/.test(p);
      assert.deepEqual(problems.filter((p) => !aborted(p)), [], 'problems in the console');
    });
  } finally {
    removeTemp(bundle);
  }
});

test('someone else\'s wrong credentials never lock a signed-in console out of Stop; a new credential met with the wait is waited out with a countdown and, refused again after it, asked for again', { timeout: 120_000 }, async () => {
  const bundle = museumTour();
  try {
    // A signed-in console on a computer from which someone sends five wrong credentials: the
    // server always takes the right one, so the console signs in again at once and stops.
    await withServer(bundle, async ({ server, observer, newPage }) => {
      const page = await newPage();
      const socket = await routeConsoleSocket(page);
      await signIn(page, server, 'Ada');
      const joined = await observer.waitForEvent((e) => e.type === 'client.connected' && e.name === 'Ada');
      let answer;
      for (let i = 0; i < 5; i++) {
        answer = await fetch(`${server.base}/api/stop`, { method: 'POST', headers: { authorization: 'Bearer someone-elses-wrong-guess' } });
      }
      assert.equal(answer.status, 429, 'five wrong credentials did not make this address wait');
      // The console's connection drops; it signs in again with the credential it kept.
      socket.closeAll();
      const again = await observer.waitForEvent((e) => e.type === 'client.connected' && e.name === 'Ada' && e.client > joined.client);
      await page.locator('#link[data-state="online"]').waitFor();
      assert.equal(await page.locator('#lockout').isVisible(), false, 'the console was told to wait');
      await page.click('#stop');
      const stopped = await observer.waitForEvent((e) => e.type === 'stop');
      assert.equal(stopped.source, 'operator');
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
    // Docent said why it closed the connection, and the console says it.
    assert.match(
      await page.locator('#notice').textContent(),
      /^Docent closed this console's connection \(server shutting down\); reconnecting\./,
    );
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

test('the state fetched after signing in does not undo newer events; /api/state and /api/operator are asked with the credential', { timeout: 60_000 }, async () => {
  const words = Array.from({ length: 120 }, (_, i) => `word${i}`).join(' ');
  const bundle = makeBundle({
    // A two-minute story on purpose, so allowed up to 150 s (the default 30 s refuses it).
    'docent.yaml': 'home: index.html\nspeech: {adapter: log, rate: 60, max_seconds: 150}\n',
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
      // No touchscreen is connected: the DISPLAY_PAGE ends failed at once (the state keeps the page).
      await observer.waitForEvent((e) => e.type === 'command.failed' && e.verb === 'DISPLAY_PAGE');
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
