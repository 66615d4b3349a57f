// store.js: what the console remembers in this browser (localStorage): the operator's
// favourite acts and the acts this console fired lately, newest first. Labels of acts the
// bundle no longer has are kept but not shown, so switching bundles loses nothing.

const FAVOURITES = "docent.operator.favourites";
const RECENT = "docent.operator.recent";
const RECENT_MAX = 8;

function read(key) {
  try {
    const value = JSON.parse(localStorage.getItem(key) ?? "[]");
    return Array.isArray(value) ? value.filter((v) => typeof v === "string") : [];
  } catch {
    return [];
  }
}

function write(key, list) {
  try {
    localStorage.setItem(key, JSON.stringify(list));
  } catch {
    // Private mode or full storage: the console works on without remembering.
  }
}

/** The favourite labels, in the order starred. */
export function favourites() {
  return read(FAVOURITES);
}

/** Whether `label` is a favourite. */
export function isFavourite(label) {
  return read(FAVOURITES).includes(label);
}

/** Stars or unstars `label`; returns whether it is a favourite now. */
export function toggleFavourite(label) {
  const list = read(FAVOURITES);
  const at = list.indexOf(label);
  if (at === -1) list.push(label);
  else list.splice(at, 1);
  write(FAVOURITES, list);
  return at === -1;
}

/** The labels fired lately, newest first. */
export function recent() {
  return read(RECENT);
}

/** Notes that `label` was fired. */
export function noteFired(label) {
  const list = [label, ...read(RECENT).filter((l) => l !== label)].slice(0, RECENT_MAX);
  write(RECENT, list);
}
