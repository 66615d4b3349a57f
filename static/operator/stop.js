// stop.js: Stop (the button and Esc), which never waits. Over the websocket when the console is
// connected and welcomed; without the websocket (offline, not welcomed yet) over HTTP at once
// (POST /api/stop with the credential): stopping must not wait for a reconnect. A socket that
// looks open may be dead (half-open): when its `stopped` answer does not come within
// STOP_ANSWER_MS, Stop goes over HTTP too (stopping twice is harmless). The button's
// data-pending says how many websocket stops wait for their answer; a notice says how an HTTP
// stop went.

import { authHeaders, retryAfter } from "./api.js";

/** How long a websocket stop may wait for its `stopped` answer before Stop goes over HTTP. */
const STOP_ANSWER_MS = 500;

/**
 * @param {{button: HTMLElement, send: (frame: object) => boolean, ref: (kind: string) => string,
 *          token: () => string|null, open: boolean, notice: (message: string) => void}} options
 *          `send`: over the websocket, false when not connected; `token`: the credential of
 *          the moment; `open`: an `--open` server, which needs none.
 * @returns {{stop: () => void, settle: (ref: string) => void}} `settle`: the websocket stop
 *          `ref` is answered (`stopped`).
 */
export function createStop({ button, send, ref, token, open, notice }) {
  const pending = new Map(); // ref -> timer: websocket stops not answered yet

  function stop() {
    const id = ref("stop");
    if (send({ type: "stop", ref: id })) {
      const timer = setTimeout(() => {
        settle(id);
        httpStop(`the websocket did not answer within ${STOP_ANSWER_MS} ms`);
      }, STOP_ANSWER_MS);
      pending.set(id, timer);
      button.dataset.pending = String(pending.size);
    } else {
      httpStop("the console is not connected");
    }
    button.classList.remove("pressed");
    void button.offsetWidth;
    button.classList.add("pressed");
  }

  /** A websocket stop is answered (or given up on): no HTTP stop for it. */
  function settle(id) {
    clearTimeout(pending.get(id));
    pending.delete(id);
    button.dataset.pending = String(pending.size); // how many wait for their answer
  }

  /** POST /api/stop with the credential; says how it went. */
  function httpStop(why) {
    const credential = token();
    if (!credential && !open) {
      notice("Not signed in: Stop needs the operator credential.");
      return;
    }
    fetch("/api/stop", { method: "POST", headers: authHeaders(credential) })
      .then((res) => {
        if (res.ok) notice(`Stopped over HTTP (${why}).`);
        else if (res.status === 429) notice(`Stop refused: this computer is locked out for ${retryAfter(res)} s (too many wrong credentials).`);
        else notice(`Stop failed: HTTP ${res.status}`);
      })
      .catch(() => notice(`Stop could not reach Docent (${why}).`));
  }

  button.addEventListener("click", stop);
  return { stop, settle };
}
