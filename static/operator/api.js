// api.js: the console's HTTP requests with the operator credential (a Bearer header; none on an
// `--open` server), and how they wait out a lockout: a 429 answer's Retry-After. Used for
// GET /api/state and /api/operator (getJson) and for Stop over HTTP (stop.js).

/** The headers that carry `token`, when there is one. */
export const authHeaders = (token) => (token ? { Authorization: `Bearer ${token}` } : {});

/** The seconds of a 429 answer's `Retry-After` (10 when it has none: asking early is harmless). */
export function retryAfter(res) {
  const seconds = Number(res.headers.get("Retry-After"));
  return Number.isFinite(seconds) && seconds > 0 ? seconds : 10;
}

/**
 * GET `path` with the credential while `wanted()`: JSON, or null when it failed or is no longer
 * wanted (signed out, a newer connection). A lockout (429) is waited out, shown by `lockout`
 * (the time it ends, ms on this computer's clock; null when it is over), and the request made
 * again.
 * @param {string} path
 * @param {{wanted: () => boolean, token: () => string|null,
 *          lockout: (retryAt: number|null) => void}} options `token`: the credential of the moment
 */
export async function getJson(path, { wanted, token, lockout }) {
  while (wanted()) {
    let res;
    try {
      res = await fetch(path, { headers: authHeaders(token()) });
    } catch (error) {
      console.warn(`docent console: no ${path}`, error);
      return null;
    }
    if (res.status === 429) {
      const seconds = retryAfter(res);
      lockout(Date.now() + seconds * 1000);
      await new Promise((resolve) => setTimeout(resolve, (seconds + 1) * 1000));
      lockout(null);
      continue;
    }
    if (!res.ok) {
      console.warn(`docent console: ${path} answered ${res.status}`);
      return null;
    }
    return wanted() ? res.json() : null;
  }
  return null;
}
