// The operator console reads what the robot speaks (issue 28, finding 3): with the visitor's
// language set to German, the act list and the chosen act's preview show the German texts; an
// act without German text shows its English one marked as such; the search finds an act by the
// words of any of its languages, by what it shows and does (its `Keywords`, its commands'
// arguments) and forgives typos ("folow"). Screenshots of the German console at 1366x768 and
// 1024x768 go to target/e2e/operator-language/ (test artefacts, not committed).

import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, watchProblems } from './lib/browser.mjs';
import { makeBundle, REPO, removeTemp } from './lib/docent.mjs';
import { actLabels, chosenLabel, connectWithToken, museumTour, signIn, withConsoleServer } from './lib/operator.mjs';

const OUT = path.join(REPO, 'target/e2e/operator-language');

let browser;
before(async () => {
  browser = await launchBrowser();
  fs.mkdirSync(OUT, { recursive: true });
});
after(() => browser?.close());

/** Presses the console's language button `tag` and waits until the server says it changed. */
async function chooseLanguage(page, observer, tag) {
  await page.locator(`#language-buttons .language[data-language="${tag}"]`).click();
  await observer.waitForEvent((e) => e.type === 'language.changed' && e.language === tag);
  await page.locator(`#language-buttons .language[data-language="${tag}"][aria-pressed="true"]`).waitFor();
}

/** Types `query` into the search as an operator does (Escape-free: the field is refilled). */
async function searchFor(page, query) {
  await page.fill('#search', query);
  await page.dispatchEvent('#search', 'input');
}

/** The text shown on the act button of `label` (the first one listed). */
function buttonText(page, label) {
  return page.locator(`#act-list .act[data-label="${label}"] .act-text`).first().textContent();
}

test('German visitors: the act list and the preview speak German; German words, typos and an act\'s keywords find it', { timeout: 90_000 }, async () => {
  const bundle = museumTour();
  try {
    await withConsoleServer(browser, bundle, async ({ server, observer, newPage, cleanup }) => {
      const page = await newPage();
      const problems = watchProblems(page);
      await signIn(page, server);
      await page.locator('#act-list .act[data-label="FOLLOW_ME"]').first().waitFor();
      assert.match(await buttonText(page, 'FOLLOW_ME'), /Please follow me/);

      await chooseLanguage(page, observer, 'de');
      await page.locator('#act-list .act[data-label="FOLLOW_ME"] .act-text', { hasText: 'Bitte folgen Sie mir' }).first().waitFor();
      assert.match(await buttonText(page, 'GREETING'), /Hallo! Willkommen/);
      // A dialog manager's proposal names what the act would say, in German too.
      const dm = await connectWithToken(server, 'dm', 'e2e-planner');
      cleanup.unshift(() => dm.close());
      dm.send({ type: 'propose', label: 'FAREWELL', reason: 'the visitors turned to the exit', ref: 'p1' });
      await page.locator('#proposal-list', { hasText: 'Auf Wiedersehen!' }).waitFor();

      // A German word finds its act, and the preview shows the German texts.
      await searchFor(page, 'Kartenlocher');
      const found = await actLabels(page);
      assert.ok(found.includes('EXPLAIN_CARD_PUNCH'), `"Kartenlocher" found ${found.join(', ')}`);
      await searchFor(page, 'Bandspulen');
      assert.equal(await chosenLabel(page), 'EXPLAIN_MINICOMPUTER');
      const preview = await page.locator('#preview').textContent();
      assert.match(preview, /Das ist der Meridian M-16/);
      assert.doesNotMatch(preview, /This is the Meridian M-16/);
      assert.doesNotMatch(preview, /null/, 'no stray "null" where no language note is due');

      // An English word still finds its act while the visitor hears German.
      await searchFor(page, 'wardrobe');
      assert.equal(await chosenLabel(page), 'GO_TO_MINICOMPUTER');

      // A typo is forgiven, the act whose label says it first.
      await searchFor(page, 'folow');
      assert.equal(await chosenLabel(page), 'FOLLOW_ME');
      // The meaning of an act that its texts do not name: the video is a film.
      await searchFor(page, 'film');
      assert.equal(await chosenLabel(page), 'VIDEO_CARD_PUNCH');
      await searchFor(page, 'webm');
      assert.equal(await chosenLabel(page), 'VIDEO_CARD_PUNCH', 'a command argument (the media file) finds its act');

      await searchFor(page, '');
      for (const size of [{ width: 1366, height: 768 }, { width: 1024, height: 768 }]) {
        await page.setViewportSize(size);
        await searchFor(page, 'Kartenlocher');
        await page.screenshot({ path: path.join(OUT, `de-${size.width}x${size.height}.png`) });
        await searchFor(page, '');
        await page.screenshot({ path: path.join(OUT, `de-list-${size.width}x${size.height}.png`) });
      }
      assert.deepEqual(problems, []);
    });
  } finally {
    removeTemp(bundle);
  }
});

test('an act without a text in the visitor\'s language shows its English one, marked so, in the list and the preview', { timeout: 60_000 }, async () => {
  const bundle = makeBundle({
    'docent.yaml': 'home: index.html\nlanguages: [en, de]\nspeech: {adapter: log}\n',
    'acts.yaml': [
      '- Label: HELLO',
      '  Text:',
      '    - Hello there.',
      '  Text@de:',
      '    - Guten Tag.',
      '- Label: WEATHER',
      '  Text:',
      '    - Lovely weather today.',
      '',
    ].join('\n'),
    'pages/index.html': '<!doctype html><title>home</title><h1>home</h1>\n',
  });
  try {
    await withConsoleServer(browser, bundle, async ({ server, observer, newPage }) => {
      const page = await newPage();
      await signIn(page, server);
      await page.locator('#act-list .act[data-label="WEATHER"]').first().waitFor();
      await chooseLanguage(page, observer, 'de');
      await page.locator('#act-list .act[data-label="HELLO"] .act-text', { hasText: 'Guten Tag.' }).first().waitFor();
      const weather = page.locator('#act-list .act[data-label="WEATHER"]').first();
      assert.match(await weather.textContent(), /Lovely weather today\./);
      assert.match(await weather.textContent(), /English: no German text/);
      await searchFor(page, 'weather');
      assert.equal(await chosenLabel(page), 'WEATHER');
      const preview = await page.locator('#preview').textContent();
      assert.match(preview, /English: no German text/);
      assert.match(preview, /Lovely weather today\./);
      await searchFor(page, 'guten');
      assert.equal(await chosenLabel(page), 'HELLO');
      assert.doesNotMatch(await page.locator('#preview').textContent(), /no German text/);
    });
  } finally {
    removeTemp(bundle);
  }
});
