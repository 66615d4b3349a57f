// The author sees every refusal and every change where they are looking (issue 28, finding 4),
// in headless Chromium against the real binary: a save with an error shows in the open
// preview at once (each problem at its file, line and column, and that the last good bundle
// still runs), a fixed save clears it and a newly added act appears in the preview's list
// without a reload; while the save is refused, `/report` lists the same problems as
// `docent check` run on the same files (the real binary, compared field by field).

import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, watchExceptions } from './lib/browser.mjs';
import { DEADLINE_MS, docentBin, makeBundle, OPERATOR_TOKEN, removeTemp, startDocent } from './lib/docent.mjs';
import { connectOperator } from './lib/ws-client.mjs';

/** A refusal or a change shows within this long of its event: the author is looking. */
const SHOWN_WITHIN_MS = 1_000;

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

const PAGE =
  '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>Hall</title></head>\n' +
  '<body><h1>Hall</h1><button data-act="GREET">Hello</button></body></html>\n';
const GOOD = '- Label: GREET\n  Text:\n    - Hello\n';
const BROKEN = '- Label: GREET\n  Text:\n    - Hello\n  Cmds:\n    - FLY_AWAY now\n';
const WITH_FAREWELL = `${GOOD}- Label: FAREWELL\n  Text:\n    - Goodbye, come back soon.\n`;

/** `docent check --format json` on `bundle`: its exit status and problems. */
function check(bundle) {
  const run = spawnSync(docentBin(), ['check', '--format', 'json', bundle], { encoding: 'utf8' });
  return { status: run.status, problems: JSON.parse(run.stdout) };
}

/** A problem as both sides must agree on it, every field. */
const said = (d) => `${d.severity} ${d.code} ${d.file}:${d.line}:${d.column} ${d.message}`;

async function withPreview(body) {
  const bundle = makeBundle({ 'acts.yaml': GOOD, 'pages/index.html': PAGE });
  // --preview opens the page with xdg-open: BROWSER=true makes that a no-op here.
  const server = await startDocent(bundle, { args: ['--preview'], env: { BROWSER: 'true' } });
  const operator = await connectOperator(server.wsUrl);
  const context = await browser.newContext({ viewport: { width: 1366, height: 768 } });
  try {
    const page = await context.newPage();
    const errors = watchExceptions(page);
    await page.goto(`${server.base}/preview`);
    await page.locator('#signin-token').fill(OPERATOR_TOKEN);
    await page.locator('#signin-submit').click();
    await page.locator('#link', { hasText: 'connected' }).waitFor({ timeout: DEADLINE_MS });
    await page.locator('button.act[data-label="GREET"]').waitFor({ timeout: DEADLINE_MS });
    await body({ bundle, server, operator, page, context });
    assert.deepEqual(errors, [], 'uncaught exceptions in the preview');
  } finally {
    operator.close();
    await context.close();
    await server.stop();
    removeTemp(bundle);
  }
}

test('the preview shows a refused save at once, clears it when fixed and lists a new act without a reload', { timeout: 90_000 }, async () => {
  await withPreview(async ({ bundle, operator, page }) => {
    const banner = page.locator('#reload-banner');
    assert.equal(await banner.isHidden(), true, 'nothing to say before the broken save');

    fs.writeFileSync(path.join(bundle, 'acts.yaml'), BROKEN);
    await operator.waitForEvent((e) => e.type === 'bundle.refused');
    const problem = banner.locator('li[data-code="unknown-verb"]');
    await problem.waitFor({ timeout: SHOWN_WITHIN_MS });
    assert.match(await problem.textContent(), /^acts\.yaml, line 5, column 7: .*FLY_AWAY/);
    assert.match(await banner.textContent(), /still running the last good bundle/);
    // The last good bundle's acts stay listed (and fire): it is what runs.
    assert.equal(await page.locator('button.act[data-label="GREET"]').count(), 1);

    fs.writeFileSync(path.join(bundle, 'acts.yaml'), WITH_FAREWELL);
    await operator.waitForEvent((e) => e.type === 'bundle.reloaded');
    await banner.waitFor({ state: 'hidden', timeout: SHOWN_WITHIN_MS });
    await page.locator('button.act[data-label="FAREWELL"]').waitFor({ timeout: SHOWN_WITHIN_MS });
  });
});

test('during a refused save /report lists the same problems as docent check on the same files', { timeout: 90_000 }, async () => {
  await withPreview(async ({ bundle, server, operator, context }) => {
    fs.writeFileSync(path.join(bundle, 'acts.yaml'), BROKEN);
    await operator.waitForEvent((e) => e.type === 'bundle.refused');
    const checked = check(bundle);
    assert.equal(checked.status, 1, 'docent check fails on the broken files');

    // The data behind the page.
    const res = await fetch(`${server.base}/api/report`, { headers: { Authorization: `Bearer ${OPERATOR_TOKEN}` } });
    assert.equal(res.status, 200);
    const report = await res.json();
    assert.deepEqual(report.problems.map(said), checked.problems.map(said));

    // The page: the same problems, and the state said in words.
    const page = await context.newPage();
    await page.goto(`${server.base}/report`);
    await page.locator('#signin[open]').waitFor({ timeout: DEADLINE_MS });
    await page.fill('#signin-token', OPERATOR_TOKEN);
    await page.click('#signin-submit');
    await page.locator('body[data-state="ready"]').waitFor({ timeout: DEADLINE_MS });
    const summary = await page.locator('#summary').textContent();
    assert.match(summary, /The files on disk have 1 error; the running bundle is the last good one from \d\d:\d\d\./);
    assert.doesNotMatch(summary, /\b0 problems\b/);
    const listed = await page.locator('#problems li').count();
    assert.equal(listed, checked.problems.length);
    await page.locator('#problems li[data-code="unknown-verb"]').waitFor({ timeout: DEADLINE_MS });
    await page.close();
  });
});
