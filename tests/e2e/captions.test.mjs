// Captions of what the robot says (docs/AUTHORING.md, "Captions"), in headless Chromium: a SAY
// is captioned in the kiosk's page from the speech device's `started` to its `done` (a test
// adapter on the websocket plays the speech device, so every step waits for an event, never a
// pause), styled by the bundle's CSS and placed over no button; off per bundle and per page;
// on the projector when the bundle asks; and as a line in the operator console, which follows
// the same events.

import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext, watchProblems } from './lib/browser.mjs';
import { makeBundle, removeTemp, startDocent } from './lib/docent.mjs';
import { openShell } from './lib/kiosk.mjs';
import { newConsoleContext, signIn } from './lib/operator.mjs';
import { openProjector } from './lib/projector.mjs';
import { DocentClient, connectOperator } from './lib/ws-client.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

const SAID = 'Welcome to the harbour museum. The lighthouse lab is upstairs.';
const ACTS = `- Label: HELLO\n  Text: ["${SAID}"]\n- Label: NEXT\n  Cmds: [DISPLAY_PAGE index.html]\n`;

// Buttons at the foot and at the head of the page: the caption must find the band between.
const page = (head = '') =>
  '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>Captions</title>' +
  `<link rel="stylesheet" href="style.css">${head}</head>\n<body>` +
  '<header><button id="top" data-act="HELLO">Say hello</button></header>' +
  '<main><h1>Harbour museum</h1><p>Touch a button.</p></main>' +
  '<footer><button id="bottom" data-act="NEXT">Next</button></footer></body></html>\n';
const STYLE =
  'body { margin: 0; font: 20px sans-serif; }\n' +
  'header { position: fixed; top: 0; left: 0; right: 0; height: 90px; }\n' +
  'footer { position: fixed; bottom: 0; left: 0; right: 0; height: 110px; }\n' +
  'header button, footer button { width: 100%; height: 100%; }\n' +
  '.docent-caption { background: rgb(10, 20, 30); }\n';

/** A bundle whose speech goes to a websocket adapter; `yaml` adds to docent.yaml. */
function bundle(yaml = '', head = '') {
  return makeBundle({
    'acts.yaml': ACTS,
    'docent.yaml': `home: index.html\nspeech: {adapter: ws}\n${yaml}`,
    'pages/index.html': page(head),
    'pages/style.css': STYLE,
  });
}

/** A speech device on the websocket that answers only when the test says so. */
async function speechDevice(server) {
  const device = await DocentClient.connect(server.wsUrl, { role: 'adapter', name: 'e2e-speech', verbs: ['SAY'] });
  return {
    device,
    /** Waits for the next SAY; returns functions that report its start and its end. */
    async nextSay() {
      const say = await device.waitFor((f) => f.type === 'command' && f.verb === 'SAY');
      return {
        say,
        started: () => device.send({ type: 'started', id: say.id }),
        done: () => device.send({ type: 'done', id: say.id }),
      };
    },
  };
}

/** Runs `body` with a server on `dir`, a kiosk tab, an operator and a speech device. */
async function withKiosk(dir, body) {
  const server = await startDocent(dir);
  const context = await newTouchContext(browser);
  const operator = await connectOperator(server.wsUrl);
  const { device, nextSay } = await speechDevice(server);
  try {
    const tab = await context.newPage();
    const problems = watchProblems(tab);
    const frame = await openShell(tab, server, 'index.html');
    // Every caption frame the page is handed, after the shell has shown it.
    await frame.evaluate(() => {
      window.e2eCaptions = [];
      window.docent.on('caption', (f) => window.e2eCaptions.push(f.text));
    });
    await body({ server, tab, frame, operator, nextSay });
    assert.deepEqual(problems, [], 'problems in the kiosk');
  } finally {
    await device.close();
    await operator.close();
    await context.close();
    await server.stop();
    removeTemp(dir);
  }
}

/** Whether two client rectangles overlap. */
const overlap = (a, b) => a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height && b.y < a.y + a.height;

test('a SAY is captioned in the page from the speech device\'s start to its end, in the bundle\'s style, over no button', { timeout: 60_000 }, async () => {
  await withKiosk(bundle(), async ({ server, frame, operator, nextSay }) => {
    await server.trigger('HELLO');
    const say = await nextSay();
    assert.equal(say.say.arg, SAID);
    // Sent to the speech device, not begun: nothing is said yet, so nothing is shown yet.
    assert.equal(await frame.locator('.docent-caption').count(), 0, 'a caption before the speech started');

    say.started();
    await operator.waitForEvent((e) => e.type === 'command.started' && e.command === say.say.id);
    const caption = frame.locator('.docent-caption');
    await caption.waitFor({ state: 'visible' });
    assert.equal(await caption.textContent(), SAID);
    assert.equal(await caption.getAttribute('aria-live'), 'polite');
    assert.equal(await caption.evaluate((el) => getComputedStyle(el).backgroundColor), 'rgb(10, 20, 30)', 'the bundle\'s CSS does not style it');
    const box = await caption.boundingBox();
    for (const button of await frame.locator('[data-act]').all()) {
      const hidden = await button.boundingBox();
      assert.ok(!overlap(box, hidden), `the caption ${JSON.stringify(box)} covers ${await button.textContent()} ${JSON.stringify(hidden)}`);
    }
    assert.equal(await caption.getAttribute('data-docent-place'), 'between');

    say.done();
    await caption.waitFor({ state: 'hidden' });
    assert.deepEqual(await frame.evaluate(() => window.e2eCaptions), [SAID, null]);
  });
});

test('a bundle turns the touchscreen\'s captions off, and a page opts out of them', { timeout: 60_000 }, async () => {
  // Turned off in docent.yaml, Docent sends the touchscreen no text at all.
  await withKiosk(bundle('captions: {kiosk: false}\n'), async ({ server, frame, operator, nextSay }) => {
    await server.trigger('HELLO');
    const say = await nextSay();
    say.started();
    // The shell has handled the caption frame once the page is handed it.
    await frame.waitForFunction(() => window.e2eCaptions.length > 0);
    assert.deepEqual(await frame.evaluate(() => window.e2eCaptions), [null]);
    assert.equal(await frame.locator('.docent-caption').count(), 0, 'a caption despite captions: kiosk: false');
    say.done();
    await operator.waitForEvent((e) => e.type === 'command.done' && e.command === say.say.id);
  });
  // A page that opts out gets the text (a page script may use it) but shows no caption.
  const optOut = bundle('', '<meta name="docent-captions" content="off">');
  await withKiosk(optOut, async ({ server, frame, nextSay }) => {
    await server.trigger('HELLO');
    const say = await nextSay();
    say.started();
    await frame.waitForFunction(() => window.e2eCaptions.length > 0);
    assert.deepEqual(await frame.evaluate(() => window.e2eCaptions), [SAID]);
    assert.equal(await frame.locator('.docent-caption').count(), 0, 'a caption on a page that opted out');
    say.done();
    await frame.waitForFunction(() => window.e2eCaptions.length > 1);
    assert.equal(await frame.locator('.docent-caption').count(), 0);
  });
});

test('the projector shows captions when the bundle asks for them', { timeout: 60_000 }, async () => {
  const dir = bundle('captions: {projector: true}\n');
  const server = await startDocent(dir);
  const context = await browser.newContext({ viewport: { width: 1000, height: 500 } });
  const operator = await connectOperator(server.wsUrl);
  const { device, nextSay } = await speechDevice(server);
  try {
    const wall = await context.newPage();
    await openProjector(wall, server, operator);
    await server.trigger('HELLO');
    const say = await nextSay();
    say.started();
    const caption = wall.locator('#docent-caption');
    await caption.waitFor({ state: 'visible' });
    assert.equal(await caption.textContent(), SAID);
    say.done();
    await caption.waitFor({ state: 'detached' });
  } finally {
    await device.close();
    await operator.close();
    await context.close();
    await server.stop();
    removeTemp(dir);
  }
});

test('the operator console shows the caption of what is being said beside Stop', { timeout: 60_000 }, async () => {
  const dir = bundle('captions: {kiosk: false}\n');
  const server = await startDocent(dir);
  const context = await newConsoleContext(browser);
  const { device, nextSay } = await speechDevice(server);
  try {
    const consolePage = await context.newPage();
    await signIn(consolePage, server);
    const line = consolePage.locator('#caption-line');
    assert.equal(await line.getAttribute('data-state'), 'silent');
    await server.trigger('HELLO');
    const say = await nextSay();
    say.started();
    await consolePage.locator('#caption-line[data-state="speaking"]').waitFor();
    assert.equal(await line.textContent(), `“${SAID}”`);
    say.done();
    await consolePage.locator('#caption-line[data-state="silent"]').waitFor();
  } finally {
    await device.close();
    await context.close();
    await server.stop();
    removeTemp(dir);
  }
});
