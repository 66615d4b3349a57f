// search.js: instant search over acts, by everything the operator may remember of one: its
// label (GO_TO_MINICOMPUTER also matches "go to"), key, group, every text of every variant in
// every language, its `Keywords`, and what it shows and does (its commands' arguments: page and
// media file names, waypoints). Case and diacritics are ignored ("cafe" finds "Café"). Every
// word typed must occur in the act, at the start of a word or inside one, or, when it does not,
// within a typo of one: a word of 4-7 letters may be one edit (a letter added, left out,
// changed, or two swapped) from the start of a word of the act, a word of 8 or more letters two.
// Ranking (docs/OPERATOR.md, "Finding an act"): the query that is the label or the key first,
// then, per word, the label, the texts the robot says now (the current context's variant in
// the visitor's language first), the group, keywords and commands, the texts of other
// languages, and last the typo matches; at the start of a word before inside one; a little more
// the more of the act's current texts say it; then the bundle's order.
// Pure functions, no DOM: tests import this module in Node too.

import { textsFor } from "./acts.js";

/** Lower case without diacritics, so that comparisons ignore both. */
export function fold(text) {
  return String(text ?? "").normalize("NFD").replace(/\p{M}/gu, "").toLowerCase();
}

/** The words of a query, folded. */
export function queryWords(query) {
  return fold(query).split(/[\s_]+/).filter(Boolean);
}

/** The words of a folded text (letters and digits). */
function wordsOf(folded) {
  return folded.match(/[\p{L}\p{N}]+/gu) ?? [];
}

/** Scores of a word found in each place (at the start of a word; inside one is half). */
const SCORE = { label: 50, own: 15, said: 12, group: 12, meaning: 12, other: 8 };
/** Scores of a typo match, below every exact one. */
const TYPO = { label: 6, said: 4, other: 3 };

/** The edits a query word may be away from a word of the act (0: none). */
export function typosAllowed(word) {
  return word.length >= 8 ? 2 : word.length >= 4 ? 1 : 0;
}

/**
 * Edits (insert, delete, change, swap two neighbours) from `a` to `b`, or `limit + 1` when more
 * than `limit`.
 */
export function editDistance(a, b, limit) {
  if (Math.abs(a.length - b.length) > limit) return limit + 1;
  let before = null;
  let previous = Array.from({ length: b.length + 1 }, (_, j) => j);
  for (let i = 1; i <= a.length; i++) {
    const row = [i];
    let least = i;
    for (let j = 1; j <= b.length; j++) {
      let d = Math.min(previous[j] + 1, row[j - 1] + 1, previous[j - 1] + (a[i - 1] === b[j - 1] ? 0 : 1));
      if (before && i > 1 && j > 1 && a[i - 1] === b[j - 2] && a[i - 2] === b[j - 1]) d = Math.min(d, before[j - 2] + 1);
      row.push(d);
      least = Math.min(least, d);
    }
    if (least > limit) return limit + 1;
    before = previous;
    previous = row;
  }
  return previous[b.length];
}

/** Whether `word` is within its allowed typos of the start of one of `words` (`seen` caches). */
function typoIn(words, word, seen) {
  const k = typosAllowed(word);
  if (k === 0) return false;
  for (const candidate of words) {
    const key = `${word} ${candidate}`;
    let near = seen.get(key);
    if (near === undefined) {
      near = false;
      for (let n = Math.max(1, word.length - k); n <= Math.min(candidate.length, word.length + k) && !near; n++) {
        near = editDistance(word, candidate.slice(0, n), k) <= k;
      }
      seen.set(key, near);
    }
    if (near) return true;
  }
  return false;
}

/** A searchable text: `{variant, language, text, folded, words}`. */
function entryText(variant, language, text) {
  const folded = fold(text);
  return { variant, language, text, folded, words: wordsOf(folded) };
}

/**
 * A search index over `acts` (from acts.js `readActs`): per act its folded label, group,
 * keywords and command arguments, and every text of every variant in every language it is
 * written in (a language that falls back to another's texts adds none).
 */
export function indexActs(acts) {
  return acts.map((act) => {
    const texts = [];
    for (const [variant, defaults] of act.variants) {
      const languages = act.languages?.get(variant);
      if (!languages?.size) {
        for (const text of defaults) texts.push(entryText(variant, null, text));
        continue;
      }
      for (const [tag, said] of languages) {
        if (said.language !== tag) continue; // the default's texts, indexed under their own tag
        for (const text of said.texts) texts.push(entryText(variant, tag, text));
      }
    }
    const meaning = fold([...(act.keywords ?? []), ...act.commands.map((c) => c.arg ?? "")].join(" "));
    const label = fold(act.label.replace(/_/g, " "));
    const group = fold(act.group);
    return {
      act,
      label,
      labelWords: wordsOf(label),
      group,
      meaning,
      otherWords: [...wordsOf(group), ...wordsOf(meaning)],
      key: act.key ? fold(act.key) : null,
      texts,
    };
  });
}

/** Where `word` occurs in `haystack`: -1 none, 1 inside a word, 2 at the start of a word. */
function place(haystack, word) {
  let at = haystack.indexOf(word);
  let best = -1;
  while (at !== -1) {
    if (at === 0 || !/[\p{L}\p{N}]/u.test(haystack[at - 1])) return 2;
    best = 1;
    at = haystack.indexOf(word, at + 1);
  }
  return best;
}

/**
 * Whether text `t` of `entry` is what the robot says now in its variant: in the language the
 * server says that variant in for the visitor's `language` (null: the default's, untagged).
 */
function saidNow(entry, t, language) {
  if (t.language === null) return true;
  const said = entry.act.languages?.get(t.variant)?.get(language ?? entry.act.defaultLanguage);
  return said?.language === t.language;
}

/** The score of one query word in `entry` (0: not found), and whether a current text has it. */
function scoreWord(entry, word, own, language, seen) {
  let best = Math.max(place(entry.label, word) * SCORE.label, place(entry.group, word) * SCORE.group, place(entry.meaning, word) * SCORE.meaning);
  let hits = 0;
  let current = 0;
  for (const t of entry.texts) {
    const now = saidNow(entry, t, language);
    if (now) current++;
    const p = place(t.folded, word);
    if (p < 0) continue;
    if (now) hits++;
    best = Math.max(best, p * (!now ? SCORE.other : t.variant === own ? SCORE.own : SCORE.said));
  }
  if (best > 0) return best + (hits ? (4 * hits) / Math.max(current, 1) : 0);
  if (typoIn(entry.labelWords, word, seen)) return TYPO.label;
  let typo = typoIn(entry.otherWords, word, seen) ? TYPO.other : 0;
  for (const t of entry.texts) {
    if (typo >= TYPO.said) break;
    if (typoIn(t.words, word, seen)) typo = Math.max(typo, saidNow(entry, t, language) ? TYPO.said : TYPO.other);
  }
  return typo;
}

/**
 * The acts matching `query` for `context` and the visitor's `language`, best first:
 * `[{act, score, text, variant}]` where `text` is the text to show for the match (one the robot
 * says now when it matches, else the best matching one; null when no text matched as typed). An
 * empty query matches nothing.
 */
export function search(index, query, context, language = null) {
  const words = queryWords(query);
  if (words.length === 0) return [];
  const whole = words.join(" ");
  const seen = new Map();
  const results = [];
  for (const entry of index) {
    const own = textsFor(entry.act, context).variant;
    let score = 0;
    for (const word of words) {
      const got = scoreWord(entry, word, own, language, seen);
      if (!got) {
        score = 0;
        break;
      }
      score += got;
    }
    if (!score) continue;
    if (entry.label === whole || entry.key === whole) score += 1000;
    else if (entry.label.startsWith(whole)) score += 300;
    const shown = bestText(entry, words, own, language);
    results.push({ act: entry.act, score, text: shown?.text ?? null, variant: shown?.variant ?? null });
  }
  results.sort((a, b) => b.score - a.score || a.act.order - b.act.order);
  return results;
}

/** The text that matches most words, one said now first, the context's own variant next. */
function bestText(entry, words, own, language) {
  let best = null;
  let bestCount = 0;
  for (const t of entry.texts) {
    const found = words.filter((w) => t.folded.includes(w)).length;
    if (!found) continue;
    const count = found + (saidNow(entry, t, language) ? 0.5 : 0) + (t.variant === own ? 0.25 : 0);
    if (count > bestCount) {
      best = t;
      bestCount = count;
    }
  }
  return best;
}

/**
 * `text` cut into `[{text, hit}]` pieces where `hit` marks the query's words, for highlighting.
 * Folding keeps one character per character for most scripts; when it does not, no highlight.
 */
export function highlight(text, query) {
  const words = queryWords(query);
  const folded = fold(text);
  if (words.length === 0 || folded.length !== text.length) return [{ text, hit: false }];
  const marks = new Array(text.length).fill(false);
  for (const word of words) {
    for (let at = folded.indexOf(word); at !== -1; at = folded.indexOf(word, at + 1)) {
      marks.fill(true, at, at + word.length);
    }
  }
  const pieces = [];
  for (let i = 0; i < text.length; i++) {
    const last = pieces.at(-1);
    if (last && last.hit === marks[i]) last.text += text[i];
    else pieces.push({ text: text[i], hit: marks[i] });
  }
  return pieces;
}
