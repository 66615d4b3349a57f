// The content report (`GET /report`) in headless Chromium: signing in with the operator
// credential shows a museum-tour act with its text, a page with the acts it offers, and the
// live bundle's warnings and note; printing hides the controls and keeps every act; a generated bundle of
// 10,000 acts renders completely (the time is printed as a test diagnostic). Every wait is for
// an element or the page's `data-state`, with a deadline only.

import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, watchProblems } from './lib/browser.mjs';
import { copyBundle, DEADLINE_MS, makeBundle, OPERATOR_TOKEN, removeTemp, startDocent } from './lib/docent.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

/** Runs `body({server, page, problems})` with a server on `bundle` and a fresh page. */
async function withReport(bundle, body) {
  const server = await startDocent(bundle);
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  try {
    const page = await context.newPage();
    const problems = watchProblems(page);
    await body({ server, page, problems });
  } finally {
    await context.close();
    await server.stop();
    removeTemp(bundle);
  }
}

/** Opens /report, signs in and waits until every act is rendered. */
async function signInAndWait(page, server, timeout = DEADLINE_MS) {
  await page.goto(`${server.base}/report`);
  await page.locator('#signin[open]').waitFor({ timeout });
  assert.equal(await page.locator('#acts .act').count(), 0, 'nothing before sign-in');
  await page.fill('#signin-token', OPERATOR_TOKEN);
  const started = Date.now();
  await page.click('#signin-submit');
  await page.locator('body[data-state="ready"]').waitFor({ timeout });
  return Date.now() - started;
}

test('signed in, the report shows acts with their texts, pages with their acts, the warnings and a note', { timeout: 60_000 }, async () => {
  // One warning in the live bundle: an unquoted `yes` (kept as text, worth quoting). And a
  // Mac's `.DS_Store`, ignored with a note (no mistake).
  const bundle = copyBundle('museum-tour', {
    'spare.yaml': '- Label: SPARE\n  Group: Spare\n  Text: yes\n',
    '.DS_Store': '\0\0\0\u0001Bud1\0\0\u0010\0',
  });
  await withReport(bundle, async ({ server, page, problems }) => {
    const urls = [];
    page.on('request', (req) => urls.push(req.url()));
    await signInAndWait(page, server);

    const act = page.locator('#act-ABOUT_TOUR');
    await assert.doesNotReject(act.waitFor());
    assert.equal(await act.locator('.place').textContent(), 'tour.yaml:17');
    assert.match(await act.textContent(), /On this tour I show you three machines/);
    assert.match(await act.textContent(), /TextChild/);
    assert.match(await act.textContent(), /DISPLAY_PAGE index\.html/);
    assert.match(await act.locator('.key').textContent(), /Alt\+A/);

    const index = page.locator('#pages tr[data-page="index.html"]');
    const offers = await index.locator('.offers li').allInnerTexts();
    for (const label of ['ABOUT_TOUR', 'GO_TO_MINICOMPUTER', 'GO_TO_CARD_PUNCH', 'GO_TO_HOME_COMPUTER']) {
      assert.ok(offers.some((o) => o.startsWith(label)), `${label} in ${offers}`);
    }
    assert.match(await index.innerText(), /home/);

    const warning = page.locator('#problems .problem:not(.note)');
    // The spare act has only English, in a bundle that speaks German too.
    const warnings = await warning.allInnerTexts();
    assert.equal(warnings.length, 2, warnings.join('\n'));
    assert.match(warnings.join('\n'), /spare\.yaml:3:9 warning\[unquoted-scalar\]/);
    assert.match(warnings.join('\n'), /spare\.yaml:\d+:\d+ warning\[missing-translation\]/);
    const notes = await page.locator('#problems .problem.note').allInnerTexts();
    assert.equal(notes.length, 1, notes.join('\n'));
    assert.match(notes[0], /^\.DS_Store:1:1 note\[ignored-files\] Docent ignored 1 file/);
    assert.match(await page.locator('#summary').textContent(), /2 problems, 1 note\./);

    // The filter narrows the acts to those mentioning a word.
    await page.fill('#filter', 'card punch');
    const shown = await page.locator('#acts .act:not([hidden])').count();
    assert.ok(shown > 0 && shown < (await page.locator('#acts .act').count()), `${shown} shown`);

    // The credential travelled in a header only, never in a URL.
    assert.ok(urls.every((u) => !u.includes(OPERATOR_TOKEN)), urls.join('\n'));
    assert.deepEqual(problems, []);
  });
});

test('printing hides the controls and shows every act, even those a search hid', { timeout: 60_000 }, async () => {
  await withReport(copyBundle('museum-tour'), async ({ server, page, problems }) => {
    await signInAndWait(page, server);
    await page.fill('#filter', 'card punch');
    const all = await page.locator('#acts .act').count();
    assert.ok((await page.locator('#acts .act:not([hidden])').count()) < all);
    await page.evaluate(() => window.dispatchEvent(new Event('beforeprint')));
    await page.emulateMedia({ media: 'print' });
    for (const selector of ['#print', '#filter', '#signout', '.controls', '.contents']) {
      assert.equal(await page.locator(selector).first().isVisible(), false, `${selector} printed`);
    }
    assert.equal(await page.locator('#acts .act:visible').count(), all);
    const breakInside = await page.locator('#acts .act').first().evaluate((el) => getComputedStyle(el).breakInside);
    assert.equal(breakInside, 'avoid');
    const pdf = await page.pdf({ format: 'A4' });
    assert.ok(pdf.length > 10_000 && pdf.subarray(0, 5).toString() === '%PDF-', `${pdf.length} bytes`);
    assert.deepEqual(problems, []);
  });
});

test('a report of 10,000 acts renders completely', { timeout: 180_000 }, async (t) => {
  const files = {};
  const acts = 10_000;
  const perFile = 1_000;
  for (let f = 0; f < acts / perFile; f += 1) {
    const lines = [];
    for (let i = f * perFile; i < (f + 1) * perFile; i += 1) {
      lines.push(`- Label: ACT_${i}`, '  Text:', `    - This is act number ${i}, with a sentence of ordinary length to read aloud.`, `    - Another way to say act ${i}.`, `  TextChild: Act ${i} for children.`, '  Cmds:', `    - DISPLAY_PAGE page${i % 100}.html`, '    - WAIT 1s');
    }
    files[`acts${String(f).padStart(2, '0')}.yaml`] = `${lines.join('\n')}\n`;
  }
  for (let p = 0; p < 100; p += 1) {
    const buttons = Array.from({ length: 10 }, (_, b) => `<button data-act="ACT_${p * 10 + b}">Act ${p * 10 + b}</button>`).join('\n');
    files[`pages/page${p}.html`] = `<!doctype html><title>Page ${p}</title>\n${buttons}\n`;
  }
  files['pages/index.html'] = '<!doctype html><title>Home</title><button data-act="ACT_0">Start</button>\n';
  const bundle = makeBundle(files);
  await withReport(bundle, async ({ server, page, problems }) => {
    const total = await signInAndWait(page, server, 120_000);
    assert.equal(await page.locator('#acts .act').count(), acts);
    assert.equal(await page.locator('#pages tr').count(), 101);
    const renderMs = Number(await page.locator('body').getAttribute('data-render-ms'));
    t.diagnostic(`10,000 acts: sign-in to fully rendered ${total} ms (rendering alone ${renderMs} ms)`);
    assert.deepEqual(problems, []);
  });
});
