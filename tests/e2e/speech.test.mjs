// Browser speech (`speech: {adapter: browser}`): the kiosk shell speaks SAY commands with the
// Web Speech API and reports their end or error. Headless Debian Chromium has no voices (its
// `speak()` fails with `synthesis-failed`), so one test replaces `speechSynthesis` with a fake
// that speaks in a few milliseconds, to check the protocol; the other uses the real one and
// checks that its failure becomes `command.failed`.

import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext } from './lib/browser.mjs';
import { makeBundle, removeTemp, startDocent } from './lib/docent.mjs';
import { openShell } from './lib/kiosk.mjs';
import { connectOperator } from './lib/ws-client.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

const bundle = () =>
  makeBundle({
    'acts.yaml': '- Label: HELLO\n  Text: [Hello there]\n- Label: BYE\n  Text: [Goodbye now]\n',
    'docent.yaml': 'speech: {adapter: browser, voice: en-us, rate: 170}\n',
    'pages/index.html': '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>home</title></head><body><p>home</p></body></html>',
  });

/**
 * A stand-in for speechSynthesis that records each utterance and "speaks" it at once: start and
 * end fire asynchronously (after the caller returns), as a real synthesizer's do.
 */
function fakeSpeech() {
  window.__spoken = [];
  const later = (fn) => Promise.resolve().then(fn);
  const synth = {
    getVoices: () => [],
    cancel() {},
    speak(u) {
      later(() => {
        u.onstart?.();
        later(() => {
          window.__spoken.push({ text: u.text, lang: u.lang, rate: u.rate });
          u.onend?.();
        });
      });
    },
  };
  Object.defineProperty(window, 'speechSynthesis', { value: synth, configurable: true });
}

async function withSpeakingKiosk({ fake }, body) {
  const dir = bundle();
  const server = await startDocent(dir);
  const context = await newTouchContext(browser);
  try {
    const page = await context.newPage();
    if (fake) await page.addInitScript(fakeSpeech);
    const operator = await connectOperator(server.wsUrl);
    try {
      await openShell(page, server, 'index.html');
      await operator.waitForEvent((e) => e.type === 'client.connected' && e.role === 'adapter' && e.verbs?.includes('SAY'));
      await body({ server, page, operator });
    } finally {
      operator.close();
    }
  } finally {
    await context.close();
    await server.stop();
    removeTemp(dir);
  }
}

test('the kiosk speaks SAY itself, one utterance after another, and reports each end', { timeout: 60_000 }, async () => {
  await withSpeakingKiosk({ fake: true }, async ({ server, page, operator }) => {
    const first = await server.trigger('HELLO', {});
    const second = await server.trigger('BYE', {});
    const ids = [first.commands[0].id, second.commands[0].id];
    const done = [];
    while (done.length < 2) {
      const e = await operator.waitForEvent((ev) => ev.type === 'command.done' && ids.includes(ev.command) && !done.includes(ev.command));
      done.push(e.command);
    }
    assert.deepEqual(done, ids, 'in trigger order');
    const spoken = await page.evaluate(() => window.__spoken);
    assert.deepEqual(spoken.map((s) => s.text), ['Hello there', 'Goodbye now']);
    assert.equal(spoken[0].lang, 'en-us');
    assert.equal(spoken[0].rate, 1);
  });
});

test('a browser that cannot speak makes the SAY fail with its reason', { timeout: 60_000 }, async () => {
  await withSpeakingKiosk({ fake: false }, async ({ server, operator }) => {
    const t = await server.trigger('HELLO', {});
    const failed = await operator.waitForEvent((e) => e.command === t.commands[0].id && e.type === 'command.failed');
    assert.match(failed.reason, /^browser speech failed: /);
  });
});
