#!/usr/bin/env node
// act-search: the keyboard task of issue 28, finding 3. An operator finds twelve acts of
// dialogs/museum-tour by what they remember of their content (a word the robot says, what the
// act shows, sometimes misspelt) and fires each with Enter, keyboard only, once with the
// visitor's language English and once German.
//
//   cargo build --locked --bin docent && DOCENT_BIN=target/debug/docent node bench/act-search.mjs [--tag NAME]
//
// One Docent, one headless Chromium with the console at 1440x900 signed in (lib/operator.mjs).
// Per task the operator tries its words in order: types a word letter by letter until the act
// is the chosen one (the first match), then Enter; when the whole word is typed and the act is
// listed but not first, Down until it is chosen; when it is not listed at all, Ctrl+A (one key)
// and the next word. Keystrokes = letters + Down + Ctrl+A + Enter. Time: from just before the
// first key to the server's `act.triggered` for the act (an observer on the websocket), so it
// includes Playwright's per-key round trip, the same on every run. An act never found counts as
// "not found" (its keys and time are left out of the median and max, and the count is printed).
// Prints a table and the summary, and writes bench/results/act-search-TAG.json.

import fs from 'node:fs';
import path from 'node:path';

import { launchBrowser } from '../tests/e2e/lib/browser.mjs';
import { REPO, removeTemp } from '../tests/e2e/lib/docent.mjs';
import { actLabels, chosenLabel, museumTour, signIn, withConsoleServer } from '../tests/e2e/lib/operator.mjs';

/** What an operator remembers of each act, in the order they try it. */
const TASKS = {
  en: [
    ['VIDEO_CARD_PUNCH', ['film', 'video']],
    ['FOLLOW_ME', ['folow', 'follow me']],
    ['EXPLAIN_MINICOMPUTER', ['swiches', 'switches']],
    ['MORE_MINICOMPUTER', ['core memory']],
    ['EXPLAIN_CARD_PUNCH', ['cardboard']],
    ['MORE_CARD_PUNCH', ['golden rule']],
    ['EXPLAIN_HOME_COMPUTER', ['television']],
    ['MORE_HOME_COMPUTER', ['basic']],
    ['EXCUSE_ME', ['let me pass', 'pass']],
    ['DONT_KNOW', ['museum staff']],
    ['END_TOUR', ['entrance']],
    ['GREETING', ['welcome']],
  ],
  de: [
    ['VIDEO_CARD_PUNCH', ['Film', 'Projektion']],
    ['FOLLOW_ME', ['folgen', 'mir nach']],
    ['EXPLAIN_MINICOMPUTER', ['Schalter']],
    ['MORE_MINICOMPUTER', ['Kernspeicher']],
    ['EXPLAIN_CARD_PUNCH', ['Pappe']],
    ['MORE_CARD_PUNCH', ['goldene Regel']],
    ['EXPLAIN_HOME_COMPUTER', ['Wohnzimmer']],
    ['MORE_HOME_COMPUTER', ['Programmiersprache']],
    ['EXCUSE_ME', ['vorbei']],
    ['DONT_KNOW', ['Information']],
    ['END_TOUR', ['Eingang']],
    ['GREETING', ['Willkommen']],
  ],
};

const tag = process.argv.includes('--tag') ? process.argv[process.argv.indexOf('--tag') + 1] : 'latest';

/** Finds and fires `label` by `words`; returns {keys, ms, word} or {found: false}. */
async function findAndFire(page, observer, label, words) {
  let keys = 0;
  const started = Date.now();
  for (const [i, word] of words.entries()) {
    if (i > 0) {
      await page.keyboard.press('Control+A');
      keys += 1;
    }
    let down = -1;
    for (let n = 1; n <= word.length; n++) {
      await page.keyboard.type(word[n - 1]);
      keys += 1;
      if ((await chosenLabel(page)) === label) {
        down = 0;
        break;
      }
      if (n === word.length) down = (await actLabels(page)).indexOf(label);
    }
    if (down === -1) continue;
    for (let d = 0; d < down; d++) await page.keyboard.press('ArrowDown');
    keys += down;
    const fired = observer.waitForEvent((e) => e.type === 'act.triggered' && e.label === label);
    await page.keyboard.press('Enter');
    keys += 1;
    await fired;
    return { found: true, keys, ms: Date.now() - started, word };
  }
  await page.keyboard.press('Control+A');
  await page.keyboard.press('Backspace');
  return { found: false, keys, ms: Date.now() - started };
}

const browser = await launchBrowser();
const bundle = museumTour();
const rows = [];
try {
  await withConsoleServer(browser, bundle, async ({ server, observer, newPage }) => {
    const page = await newPage();
    await signIn(page, server);
    await page.locator('#act-list .act').first().waitFor();
    for (const [language, tasks] of Object.entries(TASKS)) {
      const button = page.locator(`#language-buttons .language[data-language="${language}"]`);
      if (!(await button.getAttribute('aria-pressed'))?.includes('true')) {
        await button.click();
        await observer.waitForEvent((e) => e.type === 'language.changed' && e.language === language);
      }
      await page.locator('#search').focus();
      for (const [label, words] of tasks) {
        const result = await findAndFire(page, observer, label, words);
        rows.push({ language, label, words, ...result });
      }
    }
  });
} finally {
  await browser.close();
  removeTemp(bundle);
}

const stat = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length ? { median: s[Math.floor((s.length - 1) / 2)], max: s.at(-1) } : { median: null, max: null };
};
for (const r of rows) {
  console.log(`${r.language}  ${r.label.padEnd(22)} ${r.found ? `${String(r.keys).padStart(3)} keys ${String(r.ms).padStart(5)} ms  "${r.word}"` : `not found after ${r.keys} keys (${r.words.join(', ')})`}`);
}
const summary = {};
for (const language of Object.keys(TASKS)) {
  const mine = rows.filter((r) => r.language === language);
  const found = mine.filter((r) => r.found);
  summary[language] = { tasks: mine.length, found: found.length, keys: stat(found.map((r) => r.keys)), ms: stat(found.map((r) => r.ms)) };
  const s = summary[language];
  console.log(`${language}: found ${s.found} of ${s.tasks}; keys median ${s.keys.median}, max ${s.keys.max}; time median ${s.ms.median} ms, max ${s.ms.max} ms`);
}
const out = path.join(REPO, 'bench/results', `act-search-${tag}.json`);
fs.writeFileSync(out, `${JSON.stringify({ tag, summary, rows }, null, 2)}\n`);
console.log(`written ${path.relative(REPO, out)}`);
