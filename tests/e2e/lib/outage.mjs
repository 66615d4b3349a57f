// Server outages as a kiosk lives through them: the `docent` process killed (SIGKILL, as a
// crash or a power cut) and, after the outage, started again on the same port. Shared by
// tests/e2e/outage.test.mjs and bench/outage.mjs.
//
// The figure is the time from "the server accepts connections again" to "the kiosk is live":
// its welcome handled and the page tappable (the shell's `connection` event, which comes after
// the welcome's state is shown and the outage notice and busy marks are gone). "Accepting" is
// taken by a probe that connects to the port every 10 ms while the server starts (at most
// 10 ms late); "live" by the shell itself (Date.now() on the same machine).

import net from 'node:net';

import { DEADLINE_MS, startDocent, withDeadline } from './docent.mjs';

const PROBE_MS = 10;

/** Records the kiosk shell's connection events in `tab` (call once, after it is welcomed). */
export async function recordConnections(tab) {
  await tab.evaluate(() => {
    window.e2eConnections = [];
    window.docentShell.on('connection', ({ online }) => window.e2eConnections.push({ online, at: Date.now() }));
  });
}

/** Kills `server` at once (no graceful stop) and waits until the process is gone. */
export async function killServer(server) {
  server.process.kill('SIGKILL');
  await server.stop();
}

/** When `port` on 127.0.0.1 first accepts a connection, polling every 10 ms. */
export function acceptingAt(port) {
  return withDeadline(
    new Promise((resolve) => {
      const attempt = () => {
        const socket = net.connect({ port, host: '127.0.0.1' });
        socket.once('connect', () => {
          const at = Date.now();
          socket.destroy();
          resolve(at);
        });
        socket.once('error', () => {
          socket.destroy();
          setTimeout(attempt, PROBE_MS);
        });
      };
      attempt();
    }),
    DEADLINE_MS,
    `nothing accepted connections on port ${port}`,
  );
}

/**
 * One outage of `lengthMs` for the kiosk in `tab` (recordConnections called): kills `server`,
 * waits until the kiosk saw it go, then `during(lengthMs)` (what the test does meanwhile; by
 * default nothing but the wait), starts a server on the same port and waits until the kiosk
 * is live. Returns {server, liveMs}: the new server and accepting-to-live in ms.
 */
export async function outage({ server, bundle, tab, lengthMs, during, options = {} }) {
  const port = server.port;
  const before = await tab.evaluate(() => window.e2eConnections.length);
  await killServer(server);
  await tab.waitForFunction((n) => window.e2eConnections.slice(n).some((c) => !c.online), before, { timeout: DEADLINE_MS });
  const wentAt = Date.now();
  await (during ?? (() => {}))(lengthMs);
  const left = lengthMs - (Date.now() - wentAt);
  // The outage's own length: the experiment's parameter, not a wait for something to happen.
  if (left > 0) await new Promise((resolve) => setTimeout(resolve, left));
  const accepting = acceptingAt(port);
  const next = await startDocent(bundle, { ...options, port });
  const acceptedAt = await accepting;
  const handle = await tab.waitForFunction(
    (n) => window.e2eConnections.slice(n).find((c) => c.online)?.at,
    before,
    { timeout: DEADLINE_MS, polling: 'raf' },
  );
  const liveAt = await handle.jsonValue();
  return { server: next, liveMs: liveAt - acceptedAt };
}

/** The p-th percentile (0..100) of `values`, nearest rank. */
export function percentile(values, p) {
  const sorted = [...values].sort((a, b) => a - b);
  const rank = Math.max(1, Math.ceil((p / 100) * sorted.length));
  return sorted[rank - 1];
}
