// client-name.js: the name a touchscreen or projector page says hello with, taken from its
// address (`/?kiosk=entrance`, `/projector?projector=hall`; kiosk/launch.sh's --kiosk-name
// puts it there), so that the operator console can say which kiosk lost its connection and a
// kiosk PC's watchdog can ask Docent whether its own page is connected
// (GET /healthz?role=kiosk&name=entrance). Without one the name is the role, as before.

/** Letters or digits first, then letters, digits, spaces, `.`, `_` or `-`: at most 40. */
const NAME = /^[\p{L}\p{N}][\p{L}\p{N} ._-]{0,39}$/u;

/**
 * The name for `role` from the address's query (`?kiosk=NAME`), or `role` itself when there is
 * none or it is not a short printable name (said on the browser console, for a technician).
 */
export function clientName(role, search = location.search) {
  const asked = new URLSearchParams(search).get(role);
  if (asked === null) return role;
  if (NAME.test(asked)) return asked;
  console.warn(
    `docent: the ${role} name ${JSON.stringify(asked)} in the address is not 1 to 40 letters, digits, ` +
      `spaces, ".", "_" or "-" (starting with a letter or digit); saying hello as "${role}"`,
  );
  return role;
}
