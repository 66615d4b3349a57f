// The operator console shows the link to the robot's rosbridge (static/operator/robotlink.js):
// "robot linked" while a real rosbridge-server-rs (tests/ros/.venv, made by
// scripts/install-test-deps.sh, run through tests/ros/run.sh in its own ROS domain) is up;
// "robot link down, retrying", with the address and the reason on hover, once it is killed;
// linked again when it returns on its port, by itself. Hidden on a site without rosbridge.

import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser } from './lib/browser.mjs';
import { DEADLINE_MS, freePort, makeBundle, removeTemp, REPO } from './lib/docent.mjs';
import { signIn, withConsoleServer } from './lib/operator.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

/** rosbridge-server-rs on `port`, in a ROS domain of its own. */
function startRosbridge(port) {
  const run = path.join(REPO, 'tests/ros/run.sh');
  const env = { ...process.env, ROS_DOMAIN_ID: String(90 + (process.pid % 10)) };
  return spawn(run, ['rosbridge-server-rs', '--bind', `127.0.0.1:${port}`, '--no-rosapi'], { env, stdio: 'ignore' });
}

const bundleWith = (yaml) =>
  makeBundle({
    'docent.yaml': yaml,
    'acts.yaml': '- Label: HELLO\n  Text: [Hello.]\n',
    'pages/index.html': '<!doctype html><title>home</title><h1>home</h1>\n',
  });

test('the console shows the robot link going down and coming back', { timeout: 90_000 }, async () => {
  const port = await freePort();
  let rosbridge = startRosbridge(port);
  const bundle = bundleWith(`speech: {adapter: log}\nrosbridge: {url: "ws://127.0.0.1:${port}"}\n`);
  try {
    await withConsoleServer(browser, bundle, async ({ server, newPage }) => {
      const page = await newPage();
      await signIn(page, server);
      const link = page.locator('#robot-link');
      await page.locator('#robot-link[data-state="online"]').waitFor({ timeout: DEADLINE_MS });
      assert.equal((await link.textContent()).trim(), 'robot linked');
      assert.equal(await link.getAttribute('title'), `ws://127.0.0.1:${port}`);

      rosbridge.kill('SIGKILL');
      await page.locator('#robot-link[data-state="offline"]').waitFor({ timeout: DEADLINE_MS });
      assert.equal((await link.textContent()).trim(), 'robot link down, retrying');
      const title = await link.getAttribute('title');
      assert.ok(title.startsWith(`ws://127.0.0.1:${port}: `) && title.length > `ws://127.0.0.1:${port}: `.length, title);

      rosbridge = startRosbridge(port);
      await page.locator('#robot-link[data-state="online"]').waitFor({ timeout: DEADLINE_MS });
    });
  } finally {
    rosbridge.kill('SIGKILL');
    removeTemp(bundle);
  }
});

test('a site without rosbridge shows no robot link', { timeout: 60_000 }, async () => {
  const bundle = bundleWith('speech: {adapter: log}\n');
  try {
    await withConsoleServer(browser, bundle, async ({ server, newPage }) => {
      const page = await newPage();
      await signIn(page, server);
      assert.equal(await page.locator('#robot-link').isHidden(), true);
    });
  } finally {
    removeTemp(bundle);
  }
});
