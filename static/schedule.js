// schedule.js: the kiosk's opening hours. Docent reads `schedule:` once, when the bundle loads
// (server/content/schedule.rs), and hands the kiosk its parsed form: each weekday's open ranges
// (minutes from midnight, Monday first), the special days by date, and the closed page. This
// file only looks up the range the kiosk's own clock is in, so the kiosk switches on time with
// no message from the server. Times are the kiosk's local wall-clock time.

const MINUTE_MS = 60_000;

/** "2025-12-24" for `date`'s local day. */
function localDay(date) {
  const two = (n) => String(n).padStart(2, "0");
  return `${date.getFullYear()}-${two(date.getMonth() + 1)}-${two(date.getDate())}`;
}

/**
 * What the touchscreen should show at `date`: `{open: true, home, attract}` or
 * `{open: false, page}`. `defaults` are the bundle's `home` and `kiosk: attract` (or null).
 */
export function showingAt(schedule, defaults, date) {
  if (!schedule) return { open: true, home: defaults.home, attract: defaults.attract };
  const special = schedule.special_days?.[localDay(date)];
  const hours = special ?? schedule.week[(date.getDay() + 6) % 7] ?? [];
  const minute = date.getHours() * 60 + date.getMinutes();
  const range = hours.find((h) => h.from <= minute && minute < h.to);
  if (!range) return { open: false, page: schedule.closed_page };
  return { open: true, home: range.home ?? defaults.home, attract: range.attract ?? defaults.attract };
}

/**
 * Calls `onChange(showing)` now and whenever what the schedule says changes, checked at every
 * minute of the kiosk's clock.
 */
export function followSchedule(schedule, defaults, onChange) {
  let last = null;
  const check = () => {
    const showing = showingAt(schedule, defaults, new Date());
    const key = JSON.stringify(showing);
    if (key !== last) {
      last = key;
      onChange(showing);
    }
    setTimeout(check, MINUTE_MS - (Date.now() % MINUTE_MS) + 5);
  };
  check();
}
