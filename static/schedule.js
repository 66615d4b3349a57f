// schedule.js: the kiosk's opening hours, applied, never evaluated. Docent evaluates
// `schedule:` (server/content/schedule.rs) from the kiosk's own wall-clock time
// (`GET /api/schedule/{at}`) and answers with what the touchscreen shows now and each change
// over the next days. This file applies each change when the kiosk's clock reaches it (checked
// every minute, so it switches on time with no message from the server) and asks again after
// each change it applies; while the server is away it keeps to the changes it holds. Times are
// the kiosk's local wall-clock time, `YYYY-MM-DDTHH:MM`, which compare as text as in time.

const MINUTE_MS = 60_000;
const ANSWER_TIMEOUT_MS = 5_000;

/** `date` as the kiosk's local wall-clock time: `2025-12-01T08:59`. */
export function wallTime(date) {
  const two = (n) => String(n).padStart(2, "0");
  const day = `${date.getFullYear()}-${two(date.getMonth() + 1)}-${two(date.getDate())}`;
  return `${day}T${two(date.getHours())}:${two(date.getMinutes())}`;
}

/**
 * What the server's `table` says the touchscreen shows at wall time `now`: its last change at
 * or before `now`, else its `showing`. Either `{state: "open", home, attract}` or
 * `{state: "closed", page}`.
 */
export function showingIn(table, now) {
  let showing = table.showing;
  for (const change of table.changes) {
    if (change.at > now) break;
    showing = change.showing;
  }
  return showing;
}

/** The server's timetable from the kiosk's time now; null when it cannot be had. */
export async function askSchedule() {
  try {
    const answer = fetch(`/api/schedule/${wallTime(new Date())}`, { cache: "no-store" }).then((r) => {
      if (!r.ok) throw new Error(`HTTP ${r.status}`);
      return r.json();
    });
    const late = new Promise((_, reject) => setTimeout(() => reject(new Error("no answer")), ANSWER_TIMEOUT_MS));
    return await Promise.race([answer, late]);
  } catch (error) {
    console.warn("docent: the opening hours could not be asked for", error);
    return null;
  }
}

/**
 * Calls `onChange(showing)` now (from `first`, a timetable already asked for, or null) and
 * whenever what the timetable says changes, checked at every minute of the kiosk's clock.
 */
export function followSchedule(first, onChange) {
  let table = first;
  let last = null;
  let asking = false;
  const apply = () => {
    if (!table) return;
    const showing = showingIn(table, wallTime(new Date()));
    const key = JSON.stringify(showing);
    if (key !== last) {
      last = key;
      onChange(showing);
    }
  };
  const ask = async () => {
    if (asking) return;
    asking = true;
    table = (await askSchedule()) ?? table;
    asking = false;
    apply();
  };
  const check = () => {
    setTimeout(check, MINUTE_MS - (Date.now() % MINUTE_MS) + 5);
    const now = wallTime(new Date());
    // A change reached (or the end of the evaluated time, or none held yet): ask again. The
    // change it holds is applied first, so the switch is on time even when no answer comes.
    const due = !table || now >= table.until || (table.changes[0] && table.changes[0].at <= now);
    apply();
    if (due) ask();
  };
  apply();
  setTimeout(check, MINUTE_MS - (Date.now() % MINUTE_MS) + 5);
}
