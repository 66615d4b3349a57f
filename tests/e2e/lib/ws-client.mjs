// A small websocket client for Docent's protocol (docs/PROTOCOL.md), to act as an operator or a
// device adapter in browser tests. Node 20 has no global WebSocket, so it uses the `ws` package.
//
// Every received frame is kept in order; `waitFor(predicate)` returns the first frame not taken
// yet that matches, waiting for it if it has not arrived (with a deadline, never a pause).

import WebSocket from 'ws';

import { DEADLINE_MS, DM_TOKEN, OPERATOR_TOKEN, withDeadline } from './docent.mjs';

/** The test credential of a role that needs one. */
const TOKENS = { operator: OPERATOR_TOKEN, dm: DM_TOKEN };

export class DocentClient {
  /**
   * Connects to `wsUrl` and says hello (operators and dialog managers with their test
   * credential unless `hello.token` is given); resolves once `welcome` arrived.
   */
  static async connect(wsUrl, hello) {
    if (TOKENS[hello.role] && !('token' in hello)) hello = { ...hello, token: TOKENS[hello.role] };
    const client = new DocentClient(new WebSocket(wsUrl));
    await withDeadline(
      new Promise((resolve, reject) => {
        client.ws.once('open', resolve);
        client.ws.once('error', reject);
      }),
      DEADLINE_MS,
      `no websocket connection to ${wsUrl}`,
    );
    client.send({ type: 'hello', ...hello });
    client.welcome = await client.waitFor((f) => f.type === 'welcome' || f.type === 'error');
    if (client.welcome.type !== 'welcome') {
      throw new Error(`hello refused: ${JSON.stringify(client.welcome)}`);
    }
    return client;
  }

  constructor(ws) {
    this.ws = ws;
    this.frames = [];
    this.taken = new Set();
    this.waiters = [];
    this.closed = new Promise((resolve) => ws.once('close', resolve));
    ws.on('message', (data) => {
      const frame = JSON.parse(data.toString());
      this.frames.push(frame);
      this.onFrame?.(frame);
      for (const waiter of [...this.waiters]) waiter();
    });
  }

  /** Sends one frame. */
  send(frame) {
    this.ws.send(JSON.stringify(frame));
  }

  /** The first frame not taken yet that matches `predicate`; waits for it up to `timeout` ms. */
  waitFor(predicate, { timeout = DEADLINE_MS, what = predicate.toString() } = {}) {
    let remove = () => {};
    const found = new Promise((resolve) => {
      const check = () => {
        for (const [i, frame] of this.frames.entries()) {
          if (!this.taken.has(i) && predicate(frame)) {
            this.taken.add(i);
            remove();
            resolve(frame);
            return;
          }
        }
      };
      remove = () => {
        this.waiters = this.waiters.filter((w) => w !== check);
      };
      this.waiters.push(check);
      check();
    });
    return withDeadline(found, timeout, () => {
      remove();
      return `no frame within ${timeout} ms matching ${what}; received:\n${this.frames.map((f) => JSON.stringify(f)).join('\n')}`;
    });
  }

  /** The next `event` frame whose event matches `predicate`; resolves with the event object. */
  async waitForEvent(predicate, options = {}) {
    const frame = await this.waitFor((f) => f.type === 'event' && predicate(f.event), {
      what: predicate.toString(),
      ...options,
    });
    return frame.event;
  }

  /** Every event received so far, in order. */
  events() {
    return this.frames.filter((f) => f.type === 'event').map((f) => f.event);
  }

  /** Closes the connection and waits until it is closed. */
  async close() {
    if (this.ws.readyState !== WebSocket.CLOSED) this.ws.close();
    await withDeadline(this.closed, DEADLINE_MS, 'the websocket did not close');
  }
}

/** An operator: receives every event. */
export function connectOperator(wsUrl, name = 'e2e-operator') {
  return DocentClient.connect(wsUrl, { role: 'operator', name });
}

/**
 * An external device adapter serving `verbs` that answers every command with `started` and
 * `done` as soon as it arrives. Its `commands` are the command frames received, in order.
 */
export async function connectAutoAdapter(wsUrl, verbs, name = 'e2e-adapter') {
  const client = await DocentClient.connect(wsUrl, { role: 'adapter', name, verbs });
  client.commands = [];
  const answer = (frame) => {
    if (frame.type !== 'command') return;
    client.commands.push(frame);
    client.send({ type: 'started', id: frame.id });
    client.send({ type: 'done', id: frame.id });
  };
  client.frames.forEach(answer);
  client.onFrame = answer;
  return client;
}
