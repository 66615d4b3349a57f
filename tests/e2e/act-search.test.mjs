// The console's act search rules (static/operator/search.js, docs/OPERATOR.md "Finding an
// act") on plain data shaped like GET /api/acts, in Node without a browser: every language's
// words, keywords and commands' arguments are found; typos within the documented limits are
// forgiven and none beyond; the ranking tiers (label or key, the texts said now, the group,
// keywords and commands, other languages, typos); and the language a text is shown in, with the
// fallback named (static/operator/acts.js).

import assert from 'node:assert/strict';
import { test } from 'node:test';

import { languageNote, readActs, textsFor } from '../../static/operator/acts.js';
import { editDistance, indexActs, search, typosAllowed } from '../../static/operator/search.js';

/** An act of a GET /api/acts answer for a bundle of languages `en` (default) and `de`. */
function act(label, { text = [], de = null, child = null, keywords = [], commands = [], group = 'acts', key = null } = {}) {
  const variant = (name, en, german) => ({
    name,
    alternatives: en.map((t) => ({ text: t })),
    languages: { en: { language: 'en', texts: en }, de: german ? { language: 'de', texts: german } : { language: 'en', texts: en } },
  });
  const variants = [];
  if (text.length) variants.push(variant('Text', text, de));
  if (child) variants.push(variant('TextChild', child, null));
  const speaks = { Text: text.length ? 'Text' : null, TextChild: child ? 'TextChild' : text.length ? 'Text' : null };
  return { label, group, key, file: 'acts.yaml', variants, speaks, keywords, commands: commands.map(([verb, arg]) => ({ verb, arg })) };
}

const ANSWER = {
  contexts: ['Text', 'TextChild'],
  languages: ['en', 'de'],
  acts: [
    act('GO_TO_PUNCH', { text: ['Please follow me to the card punch.'], de: ['Bitte folgen Sie mir zum Kartenlocher.'], commands: [['SET_WAYPOINT', '12 3.5 270'], ['DISPLAY_PAGE', 'card-punch.html']] }),
    act('FOLLOW_ME', { text: ['Please come along.'], de: ['Kommen Sie mit!'], key: 'F' }),
    act('VIDEO_PUNCH', { text: ['Let me show you how it punches.'], de: ['Ich zeige Ihnen, wie sie locht.'], keywords: ['film'], commands: [['PROJECT', 'card-punch.webm']] }),
    act('CORE', { text: ['Its memory was made of tiny magnetic rings.'], de: ['Sein Speicher bestand aus Magnetringen.'], child: ['Tiny rings, threaded by hand!'] }),
    act('WEATHER', { text: ['Lovely weather today.'] }),
  ],
};
const acts = readActs(ANSWER);
const index = indexActs(acts);
const labels = (query, context = 'Text', language = 'en') => search(index, query, context, language).map((m) => m.act.label);

test('typo limits: none below 4 letters, one edit from 4, two from 8; a swap is one edit', () => {
  assert.deepEqual([1, 3, 4, 7, 8, 12].map((n) => typosAllowed('x'.repeat(n))), [0, 0, 1, 1, 2, 2]);
  assert.equal(editDistance('folow', 'follow', 2), 1);
  assert.equal(editDistance('meomry', 'memory', 2), 1, 'two neighbours swapped');
  assert.equal(editDistance('abc', 'xyz', 1), 2, 'beyond the limit: limit + 1');
});

test('words of every language, keywords and commands\' arguments find their act', () => {
  assert.deepEqual(labels('kartenlocher'), ['GO_TO_PUNCH']);
  assert.deepEqual(labels('Kartenlocher', 'Text', 'de'), ['GO_TO_PUNCH']);
  assert.deepEqual(labels('film'), ['VIDEO_PUNCH']);
  assert.deepEqual(labels('webm'), ['VIDEO_PUNCH']);
  assert.equal(labels('card punch')[0], 'GO_TO_PUNCH');
  assert.ok(labels('card punch').includes('VIDEO_PUNCH'), 'the file name card-punch.webm says "card punch" too');
  assert.deepEqual(labels('threaded'), ['CORE'], 'another context\'s text');
});

test('typos are forgiven within the limits, at the start of a word, and only then', () => {
  assert.deepEqual(labels('folow'), ['FOLLOW_ME', 'GO_TO_PUNCH'], 'a label typo before a text typo');
  assert.deepEqual(labels('memroy'), ['CORE']);
  assert.deepEqual(labels('magnetirngs'), ['CORE'], 'two edits (a swap and a change) in an 11-letter word, in another language');
  assert.deepEqual(labels('Magnetirngen', 'Text', 'de'), ['CORE']);
  assert.deepEqual(labels('fol'), ['FOLLOW_ME', 'GO_TO_PUNCH'], 'a prefix');
  assert.deepEqual(labels('fxl'), [], 'no typo in a 3-letter word');
  assert.deepEqual(labels('wether'), ['WEATHER']);
  assert.deepEqual(labels('wxxther'), [], 'two edits in a 7-letter word');
});

test('ranking: the key or label, then the texts said now, then other languages, then typos', () => {
  assert.equal(labels('f')[0], 'FOLLOW_ME', 'the key typed alone');
  // Equal scores keep the bundle's order.
  assert.deepEqual(labels('punch'), ['GO_TO_PUNCH', 'VIDEO_PUNCH']);
  const de = search(index, 'zeige', 'Text', 'de');
  assert.equal(de[0].act.label, 'VIDEO_PUNCH');
  assert.equal(de[0].text, 'Ich zeige Ihnen, wie sie locht.', 'the text shown is the German one that matched');
  // An exact word in another language beats a typo in the language said now.
  const mixed = indexActs(readActs({ ...ANSWER, acts: [act('A', { text: ['The house.'] }), act('B', { text: ['Start.'], de: ['Das Haus.'] }), act('C', { text: ['Das Boot is a film.'] })] }));
  // A word in a text said now ranks before the same word in another language's text (C has no
  // German: in German it says its English text, so that is said now in both).
  assert.deepEqual(search(mixed, 'das', 'Text', 'en').map((m) => m.act.label), ['C', 'B']);
  assert.deepEqual(search(mixed, 'das', 'Text', 'de').map((m) => m.act.label), ['B', 'C']);
  assert.deepEqual(search(mixed, 'haus', 'Text', 'en').map((m) => m.act.label), ['B', 'A'], 'B exactly (German), A by a typo (house)');
  assert.deepEqual(search(mixed, 'hous', 'Text', 'de').map((m) => m.act.label), ['A', 'B'], 'A exactly (English, said in German too), B by a typo (Haus)');
});

test('the texts shown are in the visitor\'s language, and a fallback is named', () => {
  const weather = acts.find((a) => a.label === 'WEATHER');
  const said = textsFor(weather, 'Text', 'de');
  assert.deepEqual(said.texts, ['Lovely weather today.']);
  assert.equal(languageNote(said), 'English: no German text');
  const follow = acts.find((a) => a.label === 'FOLLOW_ME');
  assert.deepEqual(textsFor(follow, 'Text', 'de').texts, ['Kommen Sie mit!']);
  assert.equal(languageNote(textsFor(follow, 'Text', 'de')), null);
  assert.deepEqual(textsFor(follow, 'Text').texts, ['Please come along.'], 'no language: the default');
});
