// The kiosk launcher for real: kiosk/launch.sh runs Debian's Chromium (headless, with a debugging
// port) under kiosk/watchdog.sh against the real docent binary, with short page-check settings.
// Its tab is crashed over CDP (the browser process lives on): the watchdog's probe
// (`launch.sh --page-connected`, GET /healthz?role=kiosk&name=lobby) says dead, the watchdog
// logs why and restarts the browser, and the kiosk connects again. With Docent stopped the
// probe cannot tell, and the browser is left alone however many probes pass; once Docent is back
// the page reconnects by itself. SIGTERM stops the launcher and leaves no process of it. Every
// wait is for an event, a log line or a probe, with a deadline only.

import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { randomUUID } from 'node:crypto';
import fs from 'node:fs';
import net from 'node:net';
import path from 'node:path';
import { test } from 'node:test';

import { chromium } from 'playwright-core';

import { DEADLINE_MS, freePort, makeBundle, REPO, removeTemp, startDocent, tempDir, withDeadline } from './lib/docent.mjs';
import { connectOperator } from './lib/ws-client.mjs';

const CHROMIUM = process.env.CHROMIUM_BIN ?? '/usr/bin/chromium';
const PAGE = '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>home</title></head><body><p>Welcome</p></body></html>\n';
const RESTARTING = /the page is not connected to Docent: its tab crashed or hung; restarting the browser/g;
const FAILS = 2;

/** Starts `launch.sh ARGS` in its own process group; `log()` is its stderr so far. */
function startLauncher(args, env) {
  const child = spawn('bash', [path.join(REPO, 'kiosk/launch.sh'), ...args], {
    env,
    stdio: ['ignore', 'ignore', 'pipe'],
    detached: true,
  });
  let log = '';
  const waiters = new Set();
  child.stderr.setEncoding('utf8');
  child.stderr.on('data', (chunk) => {
    log += chunk;
    for (const check of [...waiters]) check();
  });
  const exited = new Promise((resolve) => child.once('exit', (code, signal) => resolve({ code, signal })));
  return {
    child,
    exited,
    log: () => log,
    /** Resolves once the log matches `pattern` at least `times` times. */
    waitForLog(pattern, times = 1) {
      const global = new RegExp(pattern.source, 'g');
      return withDeadline(
        new Promise((resolve) => {
          const check = () => {
            if ((log.match(global) ?? []).length < times) return;
            waiters.delete(check);
            resolve(log);
          };
          waiters.add(check);
          check();
        }),
        DEADLINE_MS,
        () => `the launcher never logged ${pattern} ${times} time(s):\n${log}`,
      );
    },
  };
}

/** The ids of the processes whose environment holds `mark` (the launcher and all it started). */
function marked(mark) {
  const found = [];
  for (const pid of fs.readdirSync('/proc').filter((n) => /^\d+$/.test(n))) {
    try {
      if (fs.readFileSync(`/proc/${pid}/environ`, 'latin1').includes(mark)) found.push(Number(pid));
    } catch {
      // gone meanwhile, or not ours to read
    }
  }
  return found;
}

/** Resolves once no process holds `mark`; polls /proc, within the deadline. */
function noneLeft(mark) {
  return withDeadline(
    new Promise((resolve) => {
      const look = () => (marked(mark).length === 0 ? resolve() : setTimeout(look, 50));
      look();
    }),
    DEADLINE_MS,
    () => `processes of the launcher are left: ${marked(mark).join(', ')}`,
  );
}

/**
 * Docent unreachable on `port`: a listener that answers nothing (each connection is closed
 * at once, as a crashed server's port would), counting the watchdog's probes.
 */
async function unreachable(port) {
  let probes = 0;
  const waiters = new Set();
  const server = net.createServer((socket) => {
    socket.once('data', (data) => {
      if (data.toString('latin1').startsWith('GET /healthz?role=kiosk&name=lobby ')) {
        probes += 1;
        for (const check of [...waiters]) check();
      }
      socket.destroy();
    });
    socket.on('error', () => {});
  });
  await new Promise((resolve, reject) => server.once('error', reject).listen(port, '127.0.0.1', resolve));
  return {
    /** Resolves once `n` probes came. */
    probes: (n) =>
      withDeadline(
        new Promise((resolve) => {
          const check = () => {
            if (probes < n) return;
            waiters.delete(check);
            resolve(probes);
          };
          waiters.add(check);
          check();
        }),
        DEADLINE_MS,
        () => `only ${probes} probe(s) came`,
      ),
    close: () => new Promise((resolve) => server.close(resolve)),
  };
}

test('the watchdog restarts a browser whose kiosk tab crashed, and not while Docent is away', { timeout: 150_000 }, async () => {
  const bundle = makeBundle({
    'acts.yaml': '- Label: OK\n  Cmds: [DISPLAY_PAGE index.html]\n',
    'pages/index.html': PAGE,
  });
  const port = await freePort();
  const debugging = await freePort();
  const state = tempDir('docent-e2e-kiosk-state-');
  // Every process the launcher starts inherits this variable: how the test finds them all.
  const markValue = randomUUID();
  const mark = `DOCENT_E2E_LAUNCHER=${markValue}`;
  let server = await startDocent(bundle, { port });
  let operator = await connectOperator(server.wsUrl);
  const env = { ...process.env, DOCENT_E2E_LAUNCHER: markValue };
  delete env.DISPLAY;
  delete env.WAYLAND_DISPLAY;
  Object.assign(env, {
    // As root (the tests are) Chromium runs only without its sandbox.
    CHROMIUM_FLAGS: `--headless=new --remote-debugging-port=${debugging} --no-sandbox --disable-gpu`,
    WATCHDOG_ALIVE_GRACE: '2',
    WATCHDOG_ALIVE_EVERY: '1',
    WATCHDOG_ALIVE_FAILS: String(FAILS),
    WATCHDOG_KILL_AFTER: '3',
  });
  const args = ['--no-projector', '--url', `http://127.0.0.1:${port}`, '--chromium', CHROMIUM, '--kiosk-name', 'lobby', '--state-dir', state];
  const launcher = startLauncher(args, env);
  let cdp = null;
  let away = null;
  try {
    const first = await operator.waitForEvent((e) => e.type === 'client.connected' && e.role === 'kiosk');
    assert.equal(first.name, 'lobby');

    // Crash the tab over the browser's debugging port; the browser process lives on.
    cdp = await chromium.connectOverCDP(`http://127.0.0.1:${debugging}`);
    const tab = cdp.contexts().flatMap((c) => c.pages()).find((p) => p.url().includes('?kiosk=lobby'));
    assert.ok(tab, `no kiosk tab among ${cdp.contexts().flatMap((c) => c.pages()).map((p) => p.url())}`);
    const session = await tab.context().newCDPSession(tab);
    session.send('Page.crash').catch(() => {}); // never answered: the page is gone
    const lost = await operator.waitForEvent((e) => e.type === 'client.left' && e.client === first.client);
    assert.equal(lost.ended, 'lost');

    await launcher.waitForLog(RESTARTING);
    const second = await operator.waitForEvent((e) => e.type === 'client.connected' && e.name === 'lobby');
    assert.notEqual(second.client, first.client);
    assert.equal(launcher.log().match(/watchdog\[touch\]: starting: /g).length, 2, launcher.log());
    await cdp.close().catch(() => {});
    cdp = null;

    // Docent stopped: the probe cannot tell, and the browser stays, probe after probe.
    await operator.close();
    await server.stop();
    away = await unreachable(port);
    await launcher.waitForLog(/--alive cannot tell whether the page is connected/);
    await away.probes(FAILS + 2);
    assert.equal(launcher.log().match(RESTARTING).length, 1, launcher.log());
    assert.equal(launcher.log().match(/watchdog\[touch\]: starting: /g).length, 2, launcher.log());
    await away.close();
    away = null;

    // Docent back on its port: the same page reconnects by itself.
    server = await startDocent(bundle, { port });
    operator = await connectOperator(server.wsUrl);
    await operator.waitForEvent((e) => e.type === 'client.connected' && e.name === 'lobby');
    await launcher.waitForLog(/--alive answers again/);
    assert.equal(launcher.log().match(/watchdog\[touch\]: starting: /g).length, 2, launcher.log());

    // SIGTERM stops the launcher, its watchdog and the browser.
    launcher.child.kill('SIGTERM');
    const { code, signal } = await withDeadline(launcher.exited, DEADLINE_MS, () => `launch.sh did not exit:\n${launcher.log()}`);
    assert.equal(code, 0, `launch.sh exited with ${code ?? signal}:\n${launcher.log()}`);
    await noneLeft(mark);
  } finally {
    await cdp?.close().catch(() => {});
    await away?.close();
    if (launcher.child.exitCode === null && launcher.child.signalCode === null) {
      launcher.child.kill('SIGTERM');
      await withDeadline(launcher.exited, DEADLINE_MS, 'launch.sh did not exit').catch(() => {
        for (const pid of marked(mark)) process.kill(pid, 'SIGKILL');
      });
    }
    await operator.close();
    await server.stop();
    removeTemp(state);
    removeTemp(bundle);
  }
});
