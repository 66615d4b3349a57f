// acts.js: the bundle's acts as the console sees them (from GET /api/acts): each act's group
// (its `Group`, else its acts file without extension), its key, its keywords, and the texts it
// would say in a context and the visitor's language, looked up in the act's `speaks` (the
// variant the server chose for each context) and each variant's `languages` (the texts the
// server says in each language, with the language they are really in: the server's fallback,
// looked up, never re-derived here). Pure functions on plain data, no DOM: tests import this
// module in Node too.

/**
 * The console's view of one act from /api/acts.
 * @typedef {{label: string, group: string, key: string|null, file: string,
 *            variants: Map<string, string[]>, speaks: Map<string, string|null>,
 *            languages: Map<string, Map<string, {language: string, texts: string[]}>>,
 *            keywords: string[], defaultLanguage: string|null, commands: {verb: string, arg: string|null}[],
 *            order: number}} ConsoleAct `variants`: the default language's texts;
 *            `languages`: per variant, per bundle language, what the robot says then
 */

/** The acts of a GET /api/acts answer, in load order. */
export function readActs(answer) {
  const defaultLanguage = answer.languages?.[0] ?? null;
  return (answer.acts ?? []).map((act, order) => {
    const file = act.file ?? act.at?.file ?? "";
    const base = file.split("/").pop().replace(/\.[^.]*$/, "");
    const variants = new Map();
    const languages = new Map();
    for (const variant of act.variants ?? []) {
      variants.set(variant.name, (variant.alternatives ?? []).map((a) => a.text));
      languages.set(variant.name, new Map(Object.entries(variant.languages ?? {})));
    }
    return {
      label: act.label,
      group: act.group || base || "acts",
      key: act.key ? String(act.key).toUpperCase() : null,
      file,
      variants,
      speaks: new Map(Object.entries(act.speaks ?? {})),
      languages,
      keywords: (act.keywords ?? []).map(String),
      defaultLanguage,
      commands: (act.commands ?? []).map((c) => ({ verb: c.verb, arg: c.arg ?? null })),
      order,
    };
  });
}

/**
 * What `act` would say in `context` when the visitor's language is `language` (null: the
 * default language's texts): `{variant, texts, fallback, language, missing}`. `variant` is the
 * variant the server chose (null when the act says nothing, or the context is not the
 * bundle's), `fallback` whether that variant stands in for a context the act has no variant
 * of, `language` the language `texts` are in (null when unknown), `missing` the visitor's
 * language when the act has no text in it and says `language`'s instead (else null).
 */
export function textsFor(act, context, language = null) {
  const variant = act.speaks.get(context) ?? null;
  if (variant === null) return { variant: null, texts: [], fallback: false, language: null, missing: null };
  const said = act.languages?.get(variant)?.get(language ?? act.defaultLanguage);
  return {
    variant,
    texts: said?.texts ?? act.variants.get(variant) ?? [],
    fallback: variant !== context,
    language: said?.language ?? null,
    missing: language && said && said.language !== language ? language : null,
  };
}

/** The language's English name (`de` → German), else its tag. */
export function languageName(tag) {
  try {
    return new Intl.DisplayNames(["en"], { type: "language" }).of(tag) ?? tag;
  } catch {
    return tag;
  }
}

/** The mark of texts said in another language than the visitor's, e.g. `English: no German
 * text`; null when the texts are in the visitor's language. */
export function languageNote(said) {
  if (!said.missing || !said.language) return null;
  return `${languageName(said.language)}: no ${languageName(said.missing)} text`;
}

/** Groups in first-appearance order: `[[group, acts], ...]`. */
export function groupActs(acts) {
  const groups = new Map();
  for (const act of acts) {
    if (!groups.has(act.group)) groups.set(act.group, []);
    groups.get(act.group).push(act);
  }
  return [...groups];
}

/** A command as written: `VERB arg`. */
export function commandText(command) {
  return command.arg === null || command.arg === undefined ? command.verb : `${command.verb} ${command.arg}`;
}
