// shell-text.js: the words the kiosk shell shows visitors (its "Stop speaking" button, its
// notices, the outage notice), in the language of the page on show. They come from one table
// the server hands the shell (`data-strings`: by key, by language, for every language the
// bundle declares; built in for en, de, fr, es, it, nl, and a site adds its own in
// `docent.yaml`, `kiosk: strings:`, docs/CONFIG.md). No visitor's word is written in the
// shell's scripts: they ask this module by key.

/**
 * @param {{table: Object<string, Object<string, string>>|null, languages: string,
 *          current: () => string|null}} options `table`: the shell's `data-strings`;
 *          `languages`: the bundle's tags separated by spaces, the default first; `current`:
 *          the language in force when a page says none
 * @returns {(key: string, doc?: Document|null) => {text: string, lang: string}} the words for
 *          `key` in `doc`'s language (its `<html lang>`), or in the language in force
 */
export function shellWords({ table, languages, current }) {
  const all = String(languages || "en").toLowerCase().split(/\s+/).filter(Boolean);
  const fallback = all[0] ?? "en";

  /** The declared language that `tag` reads (`de-CH` reads `de`), else the default. */
  function resolve(tag) {
    const wanted = String(tag ?? "").toLowerCase();
    if (!wanted) return null;
    if (all.includes(wanted)) return wanted;
    const primary = wanted.split("-")[0];
    return all.find((language) => language === primary || language.split("-")[0] === primary) ?? null;
  }

  return (key, doc = null) => {
    let lang = null;
    try {
      lang = resolve(doc?.documentElement?.lang);
    } catch {
      lang = null; // a page of another origin
    }
    lang ??= resolve(current()) ?? fallback;
    const texts = table?.[key] ?? {};
    const text = texts[lang] ?? texts[fallback] ?? "";
    if (!text) console.warn(`docent: the shell has no words for "${key}"`);
    return { text, lang: texts[lang] ? lang : fallback };
  };
}
