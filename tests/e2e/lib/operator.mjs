// Driving the operator console (`GET /operator`) as an operator would: sign in through its form,
// wait until it is connected and shows the acts, and read what it shows; and standing between
// the console and its websocket to make the network misbehave. Also what the console's test
// files (operator-*.test.mjs) share: the museum tour with the console's settings and
// `withConsoleServer`, a server with an observer and console pages that are closed afterwards.
// Servers started by `startDocent` have the credentials OPERATOR_TOKEN and DM_TOKEN
// (lib/docent.mjs).

import { copyBundle, corpusEvents, DEADLINE_MS, DM_TOKEN, OPERATOR_TOKEN, startDocent, withDeadline } from './docent.mjs';
import { DocentClient } from './ws-client.mjs';

/** Chromium's fake camera, granted without a prompt, on loopback: the kiosk's camera in the screenshot. */
export const FAKE_MEDIA = ['--use-fake-device-for-media-stream', '--use-fake-ui-for-media-stream', '--allow-loopback-in-peer-connection'];

/** The console's size in the tests and the screenshot: a common desktop screen. */
export const CONSOLE_VIEWPORT = { width: 1440, height: 900 };

/** A new browser context of the console's size. */
export function newConsoleContext(browser) {
  return browser.newContext({ viewport: CONSOLE_VIEWPORT });
}

/** The operator credential of a server started by `startDocent`. */
export function operatorToken() {
  return OPERATOR_TOKEN;
}

/** A websocket client with `role` (operator or dm) presenting that role's credential. */
export function connectWithToken(server, role, name = `e2e-${role}`) {
  const token = role === 'dm' ? DM_TOKEN : OPERATOR_TOKEN;
  return DocentClient.connect(server.wsUrl, { role, name, token });
}

/** Opens the console in `page`; resolves once the sign-in form is shown. */
export async function openConsole(page, server) {
  const res = await page.goto(`${server.base}/operator`);
  if (res.status() !== 200) throw new Error(`no console at ${server.base}/operator: HTTP ${res.status()}`);
  await page.locator('#signin-token').waitFor({ state: 'visible', timeout: DEADLINE_MS });
}

/** Fills the sign-in form and submits it with Enter (nothing else is awaited). */
export async function submitCredential(page, token, name = null) {
  if (name !== null) await page.fill('#signin-name', name);
  await page.fill('#signin-token', token);
  await page.press('#signin-token', 'Enter');
}

/** Waits until the console is connected (welcomed) and shows its act buttons. */
export async function waitOnline(page) {
  await page.locator('#link[data-state="online"]').waitFor({ timeout: DEADLINE_MS });
  await page.locator('#act-list .act').first().waitFor({ timeout: DEADLINE_MS });
}

/** Opens the console and signs in with the server's operator credential. */
export async function signIn(page, server, name = 'e2e-console') {
  await openConsole(page, server);
  await submitCredential(page, operatorToken(server), name);
  await waitOnline(page);
}

/** The labels of the act buttons in screen order (search matches when searching). */
export function actLabels(page) {
  return page.locator('#act-list .act').evaluateAll((buttons) => buttons.map((b) => b.dataset.label));
}

/** The label of the chosen act (what Enter fires), or null. */
export function chosenLabel(page) {
  return page.evaluate(() => document.querySelector('#act-list .act.chosen')?.dataset.label ?? null);
}

/**
 * Puts the test between the console in `page` and Docent's websocket (Playwright's
 * routeWebSocket), to make the network misbehave. Each new connection gets the `mode` of the
 * moment: `pass` (frames go through; with `duplicate` every event frame reaches the page twice),
 * `dropStops` (a half-open socket as far as Stop goes: `stop` frames are lost on the way),
 * `silent` (the hello is never answered, so the console is never welcomed), or `lockout` (the
 * hello is answered with a `too-many-attempts` error carrying `lockoutMessage`, then closed).
 * `closeAll()` drops every connection (the console reconnects by itself); `waitForSocket(n)`
 * resolves once the console opened `n` connections. `sockets`: `{mode, at, sent}` per
 * connection, `sent` the frames the page sent.
 */
export async function routeConsoleSocket(page) {
  const waiters = [];
  const control = {
    mode: 'pass',
    duplicate: false,
    lockoutMessage: 'too many wrong credentials from this address; try again in 2 s',
    sockets: [],
    routes: [],
    closeAll() {
      for (const route of control.routes.splice(0)) {
        route.server?.close();
        route.ws.close();
      }
    },
    waitForSocket(n) {
      return withDeadline(
        new Promise((resolve) => {
          const check = () => control.sockets.length >= n && (resolve(), true);
          if (!check()) waiters.push(check);
        }),
        DEADLINE_MS,
        () => `the console opened ${control.sockets.length} websocket connections, not ${n}`,
      );
    },
  };
  await page.routeWebSocket(
    (url) => url.pathname === '/ws',
    (ws) => {
      const entry = { mode: control.mode, at: Date.now(), sent: [] };
      const route = { ws, server: null };
      control.sockets.push(entry);
      control.routes.push(route);
      for (const check of [...waiters]) if (check()) waiters.splice(waiters.indexOf(check), 1);
      if (entry.mode === 'silent') {
        ws.onMessage((message) => entry.sent.push(message));
        return;
      }
      if (entry.mode === 'lockout') {
        ws.onMessage((message) => {
          entry.sent.push(message);
          ws.send(JSON.stringify({ type: 'error', code: 'too-many-attempts', message: control.lockoutMessage, ref: null, suggestion: null }));
          ws.close();
        });
        return;
      }
      const server = ws.connectToServer();
      route.server = server;
      ws.onMessage((message) => {
        entry.sent.push(message);
        if (entry.mode === 'dropStops' && JSON.parse(message).type === 'stop') return;
        server.send(message);
      });
      server.onMessage((message) => {
        ws.send(message);
        if (control.duplicate && JSON.parse(message).type === 'event') ws.send(message);
      });
    },
  );
  return control;
}

/** The museum tour with the console's settings, logged speech and a drive of `speed` m/s. */
export function museumTour({ speed = 0.5, camera = 'none' } = {}) {
  return copyBundle('museum-tour', {
    'docent.yaml': [
      'home: index.html',
      'contexts: [TextGroup, TextChild]',
      'languages: [en, de]',
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
 * Runs `body` with a server on `bundle`, an observing operator client and fresh console
 * contexts of `browser` (`newPage`); closes everything afterwards and returns the corpus events
 * of the run.
 */
export async function withConsoleServer(browser, bundle, body) {
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
  return corpusEvents(server.corpus);
}
