// acts.js: the bundle's acts as the console sees them (from GET /api/acts): each act's group
// (its `Group`, else its acts file without extension), its key, and the texts it would say in
// a context, looked up in the act's `speaks` (the variant the server chose for each context).
// Pure functions on plain data, no DOM: tests import this module in Node too.

/**
 * The console's view of one act from /api/acts.
 * @typedef {{label: string, group: string, key: string|null, file: string,
 *            variants: Map<string, string[]>, speaks: Map<string, string|null>,
 *            commands: {verb: string, arg: string|null}[], order: number}} ConsoleAct
 */

/** The acts of a GET /api/acts answer, in load order. */
export function readActs(answer) {
  return (answer.acts ?? []).map((act, order) => {
    const file = act.file ?? act.at?.file ?? "";
    const base = file.split("/").pop().replace(/\.[^.]*$/, "");
    const variants = new Map();
    for (const variant of act.variants ?? []) {
      variants.set(variant.name, (variant.alternatives ?? []).map((a) => a.text));
    }
    return {
      label: act.label,
      group: act.group || base || "acts",
      key: act.key ? String(act.key).toUpperCase() : null,
      file,
      variants,
      speaks: new Map(Object.entries(act.speaks ?? {})),
      commands: (act.commands ?? []).map((c) => ({ verb: c.verb, arg: c.arg ?? null })),
      order,
    };
  });
}

/**
 * What `act` would say in `context`: `{variant, texts, fallback}`. `variant` is the variant
 * the server chose (null when the act says nothing, or the context is not the bundle's),
 * `fallback` whether that variant stands in for a context the act has no variant of.
 */
export function textsFor(act, context) {
  const variant = act.speaks.get(context) ?? null;
  if (variant === null) return { variant: null, texts: [], fallback: false };
  return { variant, texts: act.variants.get(variant) ?? [], fallback: variant !== context };
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
