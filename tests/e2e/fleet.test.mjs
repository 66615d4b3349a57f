// The fleet view in headless Chromium: a real mosquitto on a free loopback port, two
// `docent serve --mqtt` robots on it and `docent fleet --mqtt` serving the view alone. Signed
// in, the page lists both robots online with their page and a console link; Stop (by keyboard)
// stops the right robot, whose corpus logs it while the other's does not; its targets are at
// least 44 px; and when the broker dies the page, and a robot's console, say the link is down
// at once. It writes docs/screenshots/fleet.png. Every wait is for a message or an element, with a deadline; nothing sleeps.

import assert from 'node:assert/strict';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, watchExceptions } from './lib/browser.mjs';
import { newConsoleContext, signIn } from './lib/operator.mjs';
import { corpusEvents, DEADLINE_MS, freePort, OPERATOR_TOKEN, REPO, removeTemp, startDocent, tempDir } from './lib/docent.mjs';
import { startFleet, startMosquitto } from './lib/fleet.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

test('the fleet view lists two robots on one broker, stops the right one and shows a lost broker', async () => {
  const dir = tempDir('docent-e2e-fleet-');
  const port = await freePort();
  const mqtt = `mqtt://127.0.0.1:${port}`;
  let broker = await startMosquitto(port, dir);
  const bundle = path.join(REPO, 'dialogs/info-terminal');
  const robots = [];
  let fleet;
  try {
    for (const id of ['e2e-1', 'e2e-2']) {
      robots.push(await startDocent(bundle, { args: ['--no-watch', '--corpus-sync', '10ms', '--mqtt', mqtt, '--robot-id', id] }));
    }
    fleet = await startFleet(mqtt);
    const page = await browser.newPage();
    const errors = watchExceptions(page);
    await page.goto(`${fleet.base}/fleet`);
    await page.locator('#signin[open]').waitFor();
    await page.fill('#signin-token', OPERATOR_TOKEN);
    await page.click('#signin-submit');

    const row = (id) => page.locator(`tr[data-robot="${id}"]`);
    for (const [i, id] of ['e2e-1', 'e2e-2'].entries()) {
      await row(id).locator('[data-field="online"]', { hasText: 'online' }).waitFor({ timeout: DEADLINE_MS });
      assert.equal(await row(id).locator('[data-field="page"]').textContent(), 'index.html');
      const console = row(id).getByRole('link', { name: `Open ${id}'s console` });
      assert.equal(await console.getAttribute('href'), `${robots[i].base}/operator`);
    }
    assert.match(await page.locator('#link').textContent(), /connected/);

    const stop = row('e2e-2').getByRole('button', { name: 'Stop e2e-2' });
    const box = await stop.boundingBox();
    assert.ok(box.width >= 44 && box.height >= 44, `Stop is ${box.width}×${box.height}`);
    await stop.focus();
    await page.keyboard.press('Enter');
    await row('e2e-2').locator('.outcome', { hasText: 'Stopped (e2e-2 confirmed).' }).waitFor({ timeout: DEADLINE_MS });
    await page.setViewportSize({ width: 1280, height: 560 });
    await page.screenshot({ path: path.join(REPO, 'docs/screenshots/fleet.png') });
    const stops = (robot) => corpusEvents(robot.corpus).filter((e) => e.type === 'stop');
    assert.equal(stops(robots[1]).length, 1);
    assert.equal(stops(robots[0]).length, 0);

    // The broker dies: the fleet page says so at once, and so does each robot's console.
    const consoleContext = await newConsoleContext(browser);
    const consolePage = await consoleContext.newPage();
    await signIn(consolePage, robots[0]);
    broker.kill('SIGKILL');
    await page.locator('#link[data-link="down"]').waitFor({ timeout: DEADLINE_MS });
    assert.match(await page.locator('#link').textContent(), /link down/);
    await consolePage.locator('#history li', { hasText: `fleet broker ${mqtt}: link down` }).waitFor({ timeout: DEADLINE_MS });
    await consoleContext.close();
    assert.deepEqual(errors, []);
  } finally {
    broker.kill('SIGKILL');
    fleet?.child.kill('SIGKILL');
    for (const robot of robots) await robot.stop();
    removeTemp(dir);
  }
});
