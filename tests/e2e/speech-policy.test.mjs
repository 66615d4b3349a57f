// Who speaks when, seen from the touchscreen in headless Chromium: a second tap on "Read this
// page aloud" while it speaks is answered (a notice, a class on the button) and not queued
// again; following a link to another page ends the speech the old page started; while the robot
// speaks the page's <html> carries `data-docent-speaking`, and the shell's "Stop speaking"
// button shows for visitors' speech only and ends it.

import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext, watchExceptions } from './lib/browser.mjs';
import { DEADLINE_MS, makeBundle, removeTemp, startDocent } from './lib/docent.mjs';
import { openShell, waitForShownPage } from './lib/kiosk.mjs';
import { connectOperator } from './lib/ws-client.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

const LONG = 'This description goes on for a long while, ' + 'and on and on, '.repeat(40) + 'until the end.';
const ACTS =
  `- Label: READ_SCHEDULE\n  Text: ["${LONG}"]\n` +
  `- Label: READ_MAP\n  Text: ["The map shows every room."]\n` +
  `- Label: ANNOUNCE\n  Text: ["${LONG} The operator speaks."]\n`;

const page = (title, body) =>
  `<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>${title}</title></head>` +
  `<body><h1>${title}</h1>${body}</body></html>\n`;

async function withKiosk(body) {
  const dir = makeBundle({
    'acts.yaml': ACTS,
    'docent.yaml': 'speech: {adapter: log, rate: 120}\n',
    // Two buttons for one act (top and bottom of a long page): the page's own 400 ms guard
    // against a double tap is per element, so the second tap reaches Docent at once.
    'pages/index.html': page('Schedule', '<button id="read" data-act="READ_SCHEDULE">Read this page aloud</button><a id="map" href="map.html">Map</a><button id="read-again" data-act="READ_SCHEDULE">Read aloud</button>'),
    'pages/map.html': page('Map', '<button id="read" data-act="READ_MAP">Read this page aloud</button>'),
  });
  const server = await startDocent(dir);
  const context = await newTouchContext(browser);
  const operator = await connectOperator(server.wsUrl);
  try {
    const tab = await context.newPage();
    const errors = watchExceptions(tab);
    const content = await openShell(tab, server, 'index.html');
    await body({ tab, content, operator });
    assert.deepEqual(errors, [], 'uncaught exceptions in the kiosk');
  } finally {
    operator.close();
    await context.close();
    await server.stop();
    removeTemp(dir);
  }
}

const outcome = (label) => (e) =>
  e.label === label && e.verb === 'SAY' && ['command.done', 'command.failed', 'command.cancelled'].includes(e.type);

test('a second tap on an act already speaking is answered and not queued again', { timeout: 60_000 }, async () => {
  await withKiosk(async ({ tab, content, operator }) => {
    await content.tap('#read');
    await operator.waitForEvent((e) => e.type === 'command.started' && e.label === 'READ_SCHEDULE');
    await content.waitForFunction(() => document.documentElement.dataset.docentSpeaking === 'kiosk', null, { timeout: DEADLINE_MS });
    await content.tap('#read-again');
    await operator.waitForEvent((e) => e.type === 'trigger.refused' && e.code === 'already-speaking');
    await content.waitForFunction(() => document.querySelector('#read-again').classList.contains('docent-already-speaking'), null, { timeout: DEADLINE_MS });
    await tab.waitForSelector('#docent-notice:not([hidden])', { timeout: DEADLINE_MS });
    const says = operator.events().filter((e) => e.type === 'command.sent' && e.verb === 'SAY');
    assert.equal(says.length, 1, 'the description was queued once');
  });
});

test('following a link ends the speech the old page started, and the new page speaks at once', { timeout: 60_000 }, async () => {
  await withKiosk(async ({ tab, content, operator }) => {
    await content.tap('#read');
    await operator.waitForEvent((e) => e.type === 'command.started' && e.label === 'READ_SCHEDULE');
    await content.tap('#map');
    const map = await waitForShownPage(tab, 'map.html');
    const ended = await operator.waitForEvent(outcome('READ_SCHEDULE'));
    assert.equal(ended.type, 'command.cancelled');
    assert.equal(ended.reason, 'the visitor left the page for map.html');
    await map.tap('#read');
    const started = await operator.waitForEvent((e) => e.type === 'command.started' && e.label === 'READ_MAP');
    assert.ok(started, 'the map is described without waiting for the schedule');
  });
});

test('the stop button shows for visitors\' speech only and ends it', { timeout: 60_000 }, async () => {
  await withKiosk(async ({ tab, content, operator }) => {
    await content.tap('#read');
    await tab.waitForSelector('#docent-stop-speech:not([hidden])', { timeout: DEADLINE_MS });
    await tab.tap('#docent-stop-speech');
    const ended = await operator.waitForEvent(outcome('READ_SCHEDULE'));
    assert.equal(ended.type, 'command.cancelled');
    assert.equal(ended.reason, 'a visitor stopped the speech at the touchscreen');
    await tab.waitForSelector('#docent-stop-speech', { state: 'hidden', timeout: DEADLINE_MS });
    await content.waitForFunction(() => !('docentSpeaking' in document.documentElement.dataset), null, { timeout: DEADLINE_MS });
    // The operator's speech: the page shows it, but visitors get no button to end it.
    operator.send({ type: 'trigger', label: 'ANNOUNCE', ref: 'op' });
    await content.waitForFunction(() => document.documentElement.dataset.docentSpeaking === 'operator', null, { timeout: DEADLINE_MS });
    assert.equal(await tab.isHidden('#docent-stop-speech'), true);
    operator.send({ type: 'stop' });
    await operator.waitForEvent(outcome('ANNOUNCE'));
  });
});
