// search.js: instant search over acts: labels (GO_TO_MINICOMPUTER also matches "go to"),
// groups and every text of every variant, ignoring case and diacritics ("cafe" finds "Café").
// Every word typed must occur somewhere in the act. Ranking, per word: in the label, then in
// the current context's texts, the group, other variants' texts; at the start of a word
// before inside one; a little more the more of the act's texts say it; then the bundle's order.
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

/** A search index over `acts` (from acts.js `readActs`). */
export function indexActs(acts) {
  return acts.map((act) => ({
    act,
    label: fold(act.label.replace(/_/g, " ")),
    group: fold(act.group),
    texts: [...act.variants].flatMap(([variant, texts]) =>
      texts.map((text) => ({ variant, text, folded: fold(text) })),
    ),
  }));
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
 * The acts matching `query`, best first: `[{act, score, text, variant}]` where `text` is the
 * text to show for the match (the context's own when it matches, else the best matching one;
 * null when only the label or group matched). An empty query matches nothing.
 */
export function search(index, query, context) {
  const words = queryWords(query);
  if (words.length === 0) return [];
  const whole = words.join(" ");
  const results = [];
  for (const entry of index) {
    const own = textsFor(entry.act, context).variant;
    let score = 0;
    let matched = true;
    for (const word of words) {
      const inLabel = place(entry.label, word);
      const inGroup = place(entry.group, word);
      let inOwn = -1;
      let inOther = -1;
      let hits = 0; // texts containing the word
      for (const t of entry.texts) {
        const p = place(t.folded, word);
        if (p > 0) hits++;
        if (t.variant === own) inOwn = Math.max(inOwn, p);
        else inOther = Math.max(inOther, p);
      }
      const best = Math.max(inLabel * 50, inOwn * 15, inGroup * 12, inOther * 10);
      if (best < 0) {
        matched = false;
        break;
      }
      // A word many of the act's texts say is more typical of it than one said once.
      score += best + (hits ? (4 * hits) / entry.texts.length : 0);
    }
    if (!matched) continue;
    if (entry.label === whole) score += 1000;
    else if (entry.label.startsWith(whole)) score += 300;
    const shown = bestText(entry, words, own);
    results.push({ act: entry.act, score, text: shown?.text ?? null, variant: shown?.variant ?? null });
  }
  results.sort((a, b) => b.score - a.score || a.act.order - b.act.order);
  return results;
}

/** The text that matches most words, the context's own variant first on a tie. */
function bestText(entry, words, own) {
  let best = null;
  let bestCount = 0;
  for (const t of entry.texts) {
    const count = words.filter((w) => t.folded.includes(w)).length + (t.variant === own ? 0.5 : 0);
    if (count > bestCount && count >= 1) {
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
