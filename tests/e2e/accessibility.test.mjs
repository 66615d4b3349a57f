// axe-core (the npm package, pinned) in headless Chromium over every page a visitor or an
// operator sees: each shipped bundle's pages and kiosk shell at the kiosk's size, and Docent's
// own pages (console, preview, projector, sessions, report, and the fleet view on a real
// mosquitto: signed out, listing a robot, and with its broker gone). No violation of serious or
// critical impact against WCAG 2.2 A and AA may remain. The console and Docent's other desktop
// pages may be zoomed; the touchscreen and projector shells may not (a pinch would strand a
// visitor), so their viewports are checked too.

import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext } from './lib/browser.mjs';
import { DEADLINE_MS, freePort, OPERATOR_TOKEN, REPO, removeTemp, startDocent, tempDir } from './lib/docent.mjs';
import { startFleet, startMosquitto } from './lib/fleet.mjs';
import { newConsoleContext, signIn } from './lib/operator.mjs';

const AXE = fs.readFileSync(path.join(REPO, 'tests/e2e/node_modules/axe-core/axe.min.js'), 'utf8');
const TAGS = ['wcag2a', 'wcag2aa', 'wcag21a', 'wcag21aa', 'wcag22aa'];

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

/** The serious and critical violations on `page`, one line each (rule, count, first place, why). */
async function violations(page) {
  await page.addScriptTag({ content: AXE });
  const result = await page.evaluate((tags) => window.axe.run(document, { runOnly: { type: 'tag', values: tags } }), TAGS);
  return result.violations
    .filter((v) => v.impact === 'serious' || v.impact === 'critical')
    .map((v) => `${v.id} (${v.impact}) ×${v.nodes.length} at ${v.nodes[0].target.join(' ')}: ${v.nodes[0].failureSummary.replace(/\s+/g, ' ')}`);
}

const viewport = (page) => page.locator('meta[name="viewport"]').getAttribute('content');

const bundles = fs
  .readdirSync(path.join(REPO, 'dialogs'), { withFileTypes: true })
  .filter((d) => d.isDirectory() && fs.existsSync(path.join(REPO, 'dialogs', d.name, 'docent.yaml')))
  .map((d) => d.name)
  .sort();

for (const name of bundles) {
  test(`every page of ${name} and its kiosk shell pass axe (WCAG 2.2 AA, serious and critical)`, { timeout: 120_000 }, async () => {
    const server = await startDocent(path.join(REPO, 'dialogs', name));
    const context = await newTouchContext(browser);
    try {
      const page = await context.newPage();
      const dir = path.join(REPO, 'dialogs', name, 'pages');
      const pages = fs.existsSync(dir)
        ? fs.readdirSync(dir, { recursive: true }).filter((f) => f.endsWith('.html')).map((f) => f.split(path.sep).join('/')).sort()
        : [];
      assert.ok(pages.length > 0, `${name} has no pages`);
      const found = {};
      for (const file of pages) {
        const res = await page.goto(`${server.base}/pages/${file}`, { waitUntil: 'load' });
        assert.equal(res.status(), 200, file);
        found[file] = await violations(page);
      }
      await page.goto(`${server.base}/`, { waitUntil: 'load' });
      found['kiosk shell'] = await violations(page);
      assert.match(await viewport(page), /user-scalable=no/, 'the touchscreen shell does not zoom');
      for (const [where, list] of Object.entries(found)) assert.deepEqual(list, [], `${name}: ${where}`);
    } finally {
      await context.close();
      await server.stop();
    }
  });
}

test("Docent's own pages pass axe and may be zoomed, except the projector", { timeout: 120_000 }, async () => {
  const server = await startDocent(path.join(REPO, 'dialogs/museum-tour'));
  const context = await newConsoleContext(browser);
  try {
    const page = await context.newPage();
    await signIn(page, server);
    const found = { '/operator': await violations(page) };
    assert.doesNotMatch(await viewport(page), /user-scalable|maximum-scale/, 'the console may be zoomed');
    for (const url of ['/preview', '/sessions', '/report', '/projector']) {
      const res = await page.goto(`${server.base}${url}`, { waitUntil: 'load' });
      assert.equal(res.status(), 200, url);
      found[url] = await violations(page);
      if (url === '/projector') assert.match(await viewport(page), /user-scalable=no/, url);
      else assert.doesNotMatch(await viewport(page), /user-scalable|maximum-scale/, `${url} may be zoomed`);
    }
    for (const [where, list] of Object.entries(found)) assert.deepEqual(list, [], where);
  } finally {
    await context.close();
    await server.stop();
  }
});

test('the fleet view passes axe signed out, listing a robot, and with its broker gone, and may be zoomed', { timeout: 120_000 }, async () => {
  const dir = tempDir('docent-e2e-fleet-axe-');
  const port = await freePort();
  const mqtt = `mqtt://127.0.0.1:${port}`;
  const broker = await startMosquitto(port, dir);
  let robot;
  let fleet;
  const context = await newConsoleContext(browser);
  try {
    robot = await startDocent(path.join(REPO, 'dialogs/info-terminal'), { args: ['--no-watch', '--mqtt', mqtt, '--robot-id', 'axe-1'] });
    fleet = await startFleet(mqtt);
    const page = await context.newPage();
    await page.goto(`${fleet.base}/fleet`);
    await page.locator('#signin[open]').waitFor();
    const found = { 'signed out (sign-in dialog)': await violations(page) };
    assert.doesNotMatch(await viewport(page), /user-scalable|maximum-scale/, 'the fleet view may be zoomed');

    await page.fill('#signin-token', OPERATOR_TOKEN);
    await page.click('#signin-submit');
    await page.locator('tr[data-robot="axe-1"] [data-field="online"]', { hasText: 'online' }).waitFor({ timeout: DEADLINE_MS });
    found['a robot listed'] = await violations(page);

    broker.kill('SIGKILL');
    await page.locator('#link[data-link="down"]').waitFor({ timeout: DEADLINE_MS });
    found['broker gone'] = await violations(page);
    for (const [where, list] of Object.entries(found)) assert.deepEqual(list, [], `/fleet ${where}`);
  } finally {
    await context.close();
    broker.kill('SIGKILL');
    fleet?.child.kill('SIGKILL');
    await robot?.stop();
    removeTemp(dir);
  }
});
