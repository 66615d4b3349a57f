// The author's preview (`docent serve --preview`, GET /preview) in headless Chromium: signing in
// with the operator credential, the act list firing acts as an operator would (a click, and a
// search then Enter), the words being spoken shown under the screens and cleared when done,
// and the notice that this browser has no voice (headless Chromium has none). Also writes
// docs/screenshots/preview.png for docs/AUTHORING.md.

import assert from 'node:assert/strict';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, watchExceptions } from './lib/browser.mjs';
import { copyBundle, DEADLINE_MS, OPERATOR_TOKEN, removeTemp, REPO, startDocent } from './lib/docent.mjs';
import { connectOperator } from './lib/ws-client.mjs';

const SCREENSHOT = path.join(REPO, 'docs/screenshots/preview.png');

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

test('the preview fires acts from its list, shows the words being spoken and says the browser has no voice', { timeout: 90_000 }, async () => {
  const dir = copyBundle('info-terminal');
  // --preview opens the page with xdg-open: BROWSER=true makes that a no-op here.
  const server = await startDocent(dir, { args: ['--preview'], env: { BROWSER: 'true' } });
  const context = await browser.newContext({ viewport: { width: 1600, height: 1000 } });
  const operator = await connectOperator(server.wsUrl);
  try {
    const page = await context.newPage();
    const errors = watchExceptions(page);
    await page.goto(`${server.base}/preview`);

    // A guarded server: the preview asks for the operator credential before it can fire.
    await page.locator('#signin-token').fill(OPERATOR_TOKEN);
    await page.locator('#signin-submit').click();
    await page.locator('#link', { hasText: 'connected' }).waitFor({ timeout: DEADLINE_MS });
    await page.locator('#no-voice').waitFor({ state: 'visible', timeout: DEADLINE_MS });
    assert.equal(await page.locator('#no-voice').textContent(), 'This browser has no voice: speech is shown as text only.');
    // The kiosk frame speaks (here: shows) SAY for the preview.
    await operator.waitForEvent((e) => e.type === 'client.connected' && e.role === 'adapter' && e.verbs?.includes('SAY'));

    // Grouped like the console (WELCOME and GOODBYE under their Group, the rest by file); a
    // click fires as an operator.
    await page.locator('button.act[data-label="WELCOME"]').click();
    const groups = await page.locator('.act-group h3').allTextContents();
    assert.deepEqual(groups.map((g) => g.replace(/ \d+$/, '')), ['Greetings', 'acts']);
    const welcome = await operator.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'WELCOME');
    assert.equal(welcome.source, 'operator');
    const caption = page.locator('#speaking');
    await caption.locator('.said', { hasText: welcome.text }).waitFor({ timeout: DEADLINE_MS });
    await page.screenshot({ path: SCREENSHOT });
    const say = await operator.waitForEvent((e) => e.type === 'command.sent' && e.trigger === welcome.trigger && e.verb === 'SAY');
    // Shown as text for as long as saying it takes, then done: the caption clears.
    await operator.waitForEvent((e) => e.type === 'command.done' && e.command === say.command);
    await caption.locator('.muted', { hasText: 'silent' }).waitFor({ timeout: DEADLINE_MS });

    // Search by text, then Enter fires the best match.
    await page.locator('#search').fill('come back soon');
    assert.equal(await page.locator('#match-count').textContent(), '1 match');
    await page.locator('#search').press('Enter');
    const goodbye = await operator.waitForEvent((e) => e.type === 'act.triggered' && e.label === 'GOODBYE');
    assert.equal(goodbye.source, 'operator');
    await caption.locator('.said', { hasText: goodbye.text }).waitFor({ timeout: DEADLINE_MS });
    assert.deepEqual(errors, [], 'uncaught exceptions in the preview');
  } finally {
    operator.close();
    await context.close();
    await server.stop();
    removeTemp(dir);
  }
});
