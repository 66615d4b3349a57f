// The fleet view in headless Chromium: a real mosquitto on a free loopback port, two
// `docent serve --mqtt` robots on it and `docent fleet --mqtt` serving the view alone. Signed
// in, the page lists both robots online with their page and a console link; Stop (by keyboard)
// stops the right robot, whose corpus logs it while the other's does not; its targets are at
// least 44 px; and when the broker dies the page, and a robot's console, say the link is down
// at once. It writes docs/screenshots/fleet.png. Every wait is for a message or an element, with a deadline; nothing sleeps.

import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, watchExceptions } from './lib/browser.mjs';
import { newConsoleContext, signIn } from './lib/operator.mjs';
import { corpusEvents, DEADLINE_MS, docentBin, freePort, OPERATOR_TOKEN, REPO, removeTemp, startDocent, tempDir } from './lib/docent.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

/** Resolves when `stream` prints a line matching `pattern` (its match), within the deadline. */
function awaitLine(child, stream, pattern, what) {
  return new Promise((resolve, reject) => {
    let seen = '';
    const timer = setTimeout(() => reject(new Error(`${what} within ${DEADLINE_MS} ms; saw:\n${seen}`)), DEADLINE_MS);
    child[stream].setEncoding('utf8');
    child[stream].on('data', (chunk) => {
      seen += chunk;
      const found = pattern.exec(seen);
      if (found) {
        clearTimeout(timer);
        resolve(found);
      }
    });
    child.once('exit', (code) => {
      clearTimeout(timer);
      reject(new Error(`${what}: exited (${code}):\n${seen}`));
    });
  });
}

/** mosquitto on 127.0.0.1:`port`, once it listens. */
async function startMosquitto(port, dir) {
  const conf = path.join(dir, 'mosquitto.conf');
  fs.writeFileSync(conf, `listener ${port} 127.0.0.1\nallow_anonymous true\npersistence false\nlog_dest stderr\nlog_type all\n`);
  const binary = ['/usr/sbin/mosquitto', '/usr/bin/mosquitto'].find((p) => fs.existsSync(p));
  assert.ok(binary, 'mosquitto is installed (scripts/install-test-deps.sh)');
  const child = spawn(binary, ['-c', conf], { stdio: ['ignore', 'ignore', 'pipe'] });
  await awaitLine(child, 'stderr', /Opening ipv4 listen socket/, 'mosquitto listens');
  return child;
}

/** `docent fleet --mqtt URL` on a free port; its base URL once it serves. */
async function startFleet(url) {
  const port = await freePort();
  const child = spawn(docentBin(), ['fleet', '--mqtt', url, '--listen', `127.0.0.1:${port}`], {
    stdio: ['ignore', 'pipe', 'ignore'],
    env: { ...process.env, RUST_LOG: 'docent=warn', DOCENT_OPERATOR_TOKEN: OPERATOR_TOKEN },
  });
  const [, base] = await awaitLine(child, 'stdout', /fleet:\s+(http:\/\/\S+)\/fleet/, 'docent fleet prints its address');
  return { child, base };
}

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
