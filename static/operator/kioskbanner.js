// kioskbanner.js: the kiosk banner. A touchscreen or projector page whose connection was lost
// (its tab crashed, its browser was killed, the network failed) is named here at once, with
// when it went, how long it has been gone and what happens next; when a page of that role and
// name connects again its line goes and the history says it is back after how long. Whether a
// connection was lost or closed on purpose is the server's word (`client.left` `ended`), not a
// rule here. Time gone is counted on monotonic clocks, never the wall clock: the server's
// `mono_us` between events, and performance.now() since the last event.

const ROLES = { kiosk: "Kiosk", projector: "Projector" };
const TICK_MS = 1_000;

/** "9.4 s", "2 min 5 s". */
export function duration(ms) {
  const s = Math.max(0, ms) / 1000;
  if (s < 60) return `${s.toFixed(1)} s`;
  const whole = Math.floor(s);
  return `${Math.floor(whole / 60)} min ${whole % 60} s`;
}

/**
 * @param {{element: HTMLElement, clock: (time: string) => string,
 *          onBack: (event: object, text: string) => void}} options `element`: the banner
 *          (hidden when no page is gone); `clock`: an event's time as the operator's clock;
 *          `onBack`: a lost page's role and name connected again (for the history)
 * @returns {{welcome: () => void, event: (e: object) => void}}
 */
export function createKioskBanner({ element, clock, onBack }) {
  const clients = new Map(); // client id -> {role, name} of kiosks and projectors connected
  const lost = new Map(); // "role name" -> {role, name, client, time, mono}
  let anchor = null; // {mono, at}: the newest server mono_us seen, and performance.now() then
  let timer = null;

  const key = (role, name) => `${role} ${name ?? ""}`;
  /** The server's monotonic clock now, in µs, as far as the events tell. */
  const monoNow = () => (anchor ? anchor.mono + (performance.now() - anchor.at) * 1000 : null);
  const label = (entry) =>
    `${ROLES[entry.role]} ${entry.name === null ? `#${entry.client}` : `“${entry.name}”`}`;

  function render() {
    const now = monoNow();
    element.replaceChildren(
      ...[...lost.values()].map((entry) => {
        const p = document.createElement("p");
        p.dataset.role = entry.role;
        p.dataset.name = entry.name ?? "";
        p.textContent =
          `${label(entry)} lost its connection at ${clock(entry.time)} without closing it ` +
          `(its browser crashed, was killed, or the network failed). Its watchdog restarts the ` +
          `browser; if it is not back within a minute, check the kiosk PC (docs/DEVICE.md). `;
        const gone = document.createElement("span");
        gone.className = "kiosk-gone";
        gone.setAttribute("aria-live", "off"); // read once with the line, not every second
        gone.textContent = now === null ? "" : `Gone for ${duration((now - entry.mono) / 1000)}.`;
        p.append(gone);
        return p;
      }),
    );
    element.hidden = lost.size === 0;
    if (lost.size > 0 && timer === null) timer = setInterval(render, TICK_MS);
    if (lost.size === 0 && timer !== null) {
      clearInterval(timer);
      timer = null;
    }
  }

  function event(e) {
    if (typeof e?.mono_us === "number" && (anchor === null || e.mono_us >= anchor.mono)) {
      anchor = { mono: e.mono_us, at: performance.now() };
    }
    if (!(e?.role in ROLES)) return;
    if (e.type === "client.connected") {
      const name = e.name ?? null;
      clients.set(e.client, { role: e.role, name });
      const entry = lost.get(key(e.role, name));
      if (!entry) return;
      lost.delete(key(e.role, name));
      onBack(e, `${label(entry)} is back after ${duration((e.mono_us - entry.mono) / 1000)}`);
      render();
    } else if (e.type === "client.left") {
      const known = clients.get(e.client);
      clients.delete(e.client);
      if (e.ended !== "lost") return;
      const name = e.name ?? known?.name ?? null;
      // Another page of that name is connected already: nothing is missing.
      if ([...clients.values()].some((c) => c.role === e.role && c.name === name)) return;
      const k = key(e.role, name);
      if (!lost.has(k)) lost.set(k, { role: e.role, name, client: e.client, time: e.time, mono: e.mono_us });
      render();
    }
  }

  /** A new connection: its replayed events tell the story again (a new server run restarts mono_us). */
  function welcome() {
    clients.clear();
    lost.clear();
    anchor = null;
    render();
  }

  render();
  return { welcome, event };
}
