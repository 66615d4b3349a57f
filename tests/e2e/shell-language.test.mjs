// The kiosk shell speaks the page's language (issue 28, finding 5), in headless Chromium against
// the real binary: on a German page the "Stop speaking" button, the notice for a tap on an act
// already speaking and the notice for speech the robot cannot say are German, on an English
// page English; and every string of the shell's table has every language dialogs/museum-tour
// declares.

import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext, watchExceptions } from './lib/browser.mjs';
import { copyBundle, DEADLINE_MS, makeBundle, removeTemp, startDocent } from './lib/docent.mjs';
import { openShell, waitForShownPage } from './lib/kiosk.mjs';
import { connectOperator } from './lib/ws-client.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

const LONG = 'This description goes on for a long while, ' + 'and on and on, '.repeat(40) + 'until the end.';
const LANG = 'Diese Beschreibung dauert lange, ' + 'und weiter und weiter, '.repeat(40) + 'bis zum Ende.';
const ACTS = `- Label: READ\n  Text: ["${LONG}"]\n  Text@de: ["${LANG}"]\n`;

const page = (lang, title, body) =>
  `<!DOCTYPE html>\n<html lang="${lang}"><head><meta charset="utf-8"><title>${title}</title></head>` +
  `<body><h1>${title}</h1>${body}</body></html>\n`;
const BUTTONS = '<button id="read" data-act="READ">Read</button><button id="again" data-act="READ">Again</button>';

/** What the shell says, in each language (the built-in table's words). */
const SAID = {
  en: { stop: 'Stop speaking', already: 'Already speaking about this.', cannot: 'The robot cannot say this now.' },
  de: { stop: 'Nicht mehr sprechen', already: 'Darüber spreche ich schon.', cannot: 'Das kann der Roboter gerade nicht sagen.' },
};

const ended = (e) => e.label === 'READ' && e.verb === 'SAY' && ['command.done', 'command.failed', 'command.cancelled'].includes(e.type);

async function speaksIn(language) {
  const dir = makeBundle({
    'acts.yaml': ACTS,
    'docent.yaml': 'languages: [en, de]\nspeech: {adapter: log, rate: 120}\n',
    'pages/index.html': page('en', 'Hall', `${BUTTONS}<button id="de" data-language="de">Deutsch</button>`),
    'pages/de/index.html': page('de', 'Halle', BUTTONS),
  });
  const server = await startDocent(dir);
  const context = await newTouchContext(browser);
  const operator = await connectOperator(server.wsUrl);
  try {
    const tab = await context.newPage();
    const errors = watchExceptions(tab);
    let content = await openShell(tab, server, 'index.html');
    if (language === 'de') {
      await content.tap('#de');
      content = await waitForShownPage(tab, 'de/index.html');
    }
    const want = SAID[language];
    const notice = tab.locator('#docent-notice');

    await content.tap('#read');
    await operator.waitForEvent((e) => e.type === 'command.started' && e.label === 'READ');
    const stop = tab.locator('#docent-stop-speech');
    await stop.waitFor({ state: 'visible', timeout: DEADLINE_MS });
    assert.equal((await stop.textContent()).trim(), want.stop);

    await content.tap('#again');
    await operator.waitForEvent((e) => e.type === 'trigger.refused' && e.code === 'already-speaking');
    await tab.locator('#docent-notice', { hasText: want.already }).waitFor({ timeout: DEADLINE_MS });

    // The operator takes over: the visitor's speech will not be said.
    operator.send({ type: 'stop' });
    await operator.waitForEvent(ended);
    await tab.locator('#docent-notice', { hasText: want.cannot }).waitFor({ timeout: DEADLINE_MS });
    assert.equal(await notice.getAttribute('lang'), language);
    assert.deepEqual(errors, [], 'uncaught exceptions in the kiosk');
  } finally {
    operator.close();
    await context.close();
    await server.stop();
    removeTemp(dir);
  }
}

test('on a German page the shell speaks German', { timeout: 60_000 }, () => speaksIn('de'));

test('on an English page the shell speaks English', { timeout: 60_000 }, () => speaksIn('en'));

test('every shell string has every language dialogs/museum-tour declares', { timeout: 60_000 }, async () => {
  const dir = copyBundle('museum-tour');
  const server = await startDocent(dir);
  const context = await browser.newContext();
  try {
    const tab = await context.newPage();
    await tab.goto(`${server.base}/`);
    const table = JSON.parse(await tab.evaluate(() => document.body.dataset.strings ?? 'null'));
    assert.ok(table, 'the shell carries its table of strings');
    const keys = Object.keys(table);
    assert.ok(keys.length >= 7, `the shell's strings: ${keys}`);
    for (const key of keys) {
      for (const language of ['en', 'de']) {
        assert.ok(table[key][language]?.trim(), `${key} has no ${language} text`);
      }
    }
  } finally {
    await context.close();
    await server.stop();
    removeTemp(dir);
  }
});
