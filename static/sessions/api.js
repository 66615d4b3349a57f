// api.js: the /sessions page's requests, with the operator credential as a Bearer header (none
// on an `--open` server; never in a URL). Every failure becomes an ApiError that says what
// happened in words a researcher can act on: its HTTP status, Docent's error code and message.

import { authHeaders, retryAfter } from "../operator/api.js";

/** A request Docent refused or did not answer. */
export class ApiError extends Error {
  /**
   * @param {number} status the HTTP status (0: no answer at all)
   * @param {string} code Docent's error code (`unknown-code`, `unauthorized`, ...)
   * @param {string} message what went wrong, for people
   * @param {number} retryAfterS for a 429, the seconds to wait
   */
  constructor(status, code, message, retryAfterS = 0) {
    super(message);
    this.status = status;
    this.code = code;
    this.retryAfterS = retryAfterS;
  }
}

/**
 * Sends `method path` (with `body` as JSON) and returns the answer's JSON.
 * @param {string} path
 * @param {string|null} token
 * @param {{method?: string, body?: object}} options
 */
export async function request(path, token, { method = "GET", body } = {}) {
  const headers = { ...authHeaders(token) };
  if (body !== undefined) headers["Content-Type"] = "application/json";
  let res;
  try {
    res = await fetch(path, { method, headers, body: body === undefined ? undefined : JSON.stringify(body) });
  } catch {
    throw new ApiError(0, "no-answer", "Docent did not answer. Is it running?");
  }
  let json = null;
  try {
    json = await res.json();
  } catch {
    // An answer without a JSON body: said below by its status.
  }
  if (!res.ok) {
    const code = json?.code ?? "http-" + res.status;
    const message = json?.error ?? `Docent answered ${res.status}.`;
    throw new ApiError(res.status, code, message, res.status === 429 ? retryAfter(res) : 0);
  }
  return json;
}

/** The corpus's sessions. */
export const listSessions = (token) => request("/api/sessions", token);

/** One session: manifest, media, timeline, codebook, annotations. */
export const getSession = (token, name) => request(`/api/sessions/${encodeURIComponent(name)}`, token);

/** Adds, changes or deletes an annotation (`edit.action`); the line saved. */
export const saveAnnotation = (token, name, edit) =>
  request(`/api/sessions/${encodeURIComponent(name)}/annotations`, token, { method: "POST", body: edit });

/** A media ticket for the session's recordings: `{ticket, base}`. */
export const mediaTicket = (token, name) =>
  request(`/api/sessions/${encodeURIComponent(name)}/media-ticket`, token, { method: "POST" });
