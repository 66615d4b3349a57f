// The projector tests' shared harness: a Docent server on a bundle, a browser page and an
// operator websocket client that reads the server's events; and opening `/projector` until the
// server knows a projector is connected.

import assert from 'node:assert/strict';

import { newTouchContext } from './browser.mjs';
import { startDocent } from './docent.mjs';
import { connectOperator } from './ws-client.mjs';

/** Runs `body(ctx)` with a server on `bundle`, a page of `viewport` in `browser` and an operator. */
export async function withProjectorServer(browser, bundle, body, { viewport = { width: 1000, height: 500 }, touch = false } = {}) {
  const server = await startDocent(bundle);
  const context = touch ? await newTouchContext(browser) : await browser.newContext({ viewport });
  const cleanup = [() => context.close(), () => server.stop()];
  try {
    const operator = await connectOperator(server.wsUrl);
    cleanup.unshift(() => operator.close());
    const page = await context.newPage();
    await body({ server, page, operator });
  } finally {
    for (const step of cleanup) await step();
  }
}

/** Opens /projector and waits until the server knows a projector is connected. */
export async function openProjector(page, server, operator) {
  const res = await page.goto(`${server.base}/projector`);
  assert.equal(res.status(), 200);
  await operator.waitForEvent((e) => e.type === 'client.connected' && e.role === 'projector');
}

/** The ids of the commands a `triggered` answer lists, in order. */
export const commandIds = (triggered) => triggered.commands.map((c) => c.id);
