// connection.js: the console's websocket. Says hello as an operator with the credential, hands
// every frame on, and reconnects after a network loss or a server restart (backoff 0.5 s
// doubling to 10 s, +-30 % jitter). Unlike the kiosk's socket.js it gives up for good when the
// server says the credential is wrong (`unauthorized`): trying again with it could only lock the
// operator out, so the console asks for it again instead. When this computer is locked out
// (`too-many-attempts`: too many wrong or missing credentials from its address, perhaps from
// another browser on it) the credential may well be right: it is kept and tried again once the
// server's wait is over ("try again in N s" in the error's message).

const FIRST_DELAY_MS = 500;
const MAX_DELAY_MS = 10_000;
const JITTER = 0.3;
/** The wait when the server's message does not say: asking early only gets the real wait. */
const LOCKOUT_S = 10;

/** The seconds to wait that a `too-many-attempts` message gives ("try again in 42 s"). */
export function lockoutSeconds(message) {
  const seconds = Number(/try again in (\d+) ?s\b/.exec(String(message ?? ""))?.[1]);
  return Number.isFinite(seconds) && seconds > 0 ? seconds : LOCKOUT_S;
}

/**
 * Connects and keeps connected until refused or closed.
 * @param {{path: string, token: string|null, name: string|null,
 *          onFrame: (frame: object) => void,
 *          onStatus: (status: {state: "connecting"|"online"|"offline"|"locked"|"refused",
 *                              code?: string, message?: string, retryAt?: number}) => void}}
 *          options `locked`: refused for a while, tried again at `retryAt` (ms, Date.now());
 *          `refused`: the credential is wrong, given up; `offline` carries, in `message`, the
 *          reason Docent gave when it closed the connection itself (a console too slow for
 *          the events, the server shutting down), with its close `code`.
 * @returns {{send: (frame: object) => boolean, close: () => void}} `send` is false when the
 *          console is not connected and welcomed.
 */
export function connect({ path, token, name, onFrame, onStatus }) {
  const url = new URL(path, location.href);
  url.protocol = url.protocol === "https:" ? "wss:" : "ws:";
  let socket = null;
  let welcomed = false;
  let closed = false;
  let delay = FIRST_DELAY_MS;
  let retryTimer = null;

  const open = () => {
    retryTimer = null;
    if (closed) return;
    onStatus({ state: "connecting" });
    const ws = new WebSocket(url);
    socket = ws;
    let refusal = null;
    ws.onopen = () => {
      const hello = { type: "hello", role: "operator", name: name || null };
      if (token) hello.token = token;
      ws.send(JSON.stringify(hello));
    };
    ws.onmessage = (message) => {
      let frame;
      try {
        frame = JSON.parse(message.data);
      } catch {
        return;
      }
      if (!welcomed && frame.type === "error" && (frame.code === "unauthorized" || frame.code === "too-many-attempts")) {
        refusal = frame;
        ws.close();
        return;
      }
      if (frame.type === "welcome") {
        welcomed = true;
        delay = FIRST_DELAY_MS;
        onStatus({ state: "online" });
      }
      onFrame(frame);
    };
    ws.onclose = (event) => {
      if (socket !== ws) return;
      socket = null;
      welcomed = false;
      if (closed) return;
      if (refusal?.code === "unauthorized") {
        closed = true;
        onStatus({ state: "refused", code: refusal.code, message: refusal.message });
        return;
      }
      if (refusal) {
        // Whole seconds, however the server rounds them: one more makes sure the wait is over.
        const wait = (lockoutSeconds(refusal.message) + 1) * 1000;
        delay = FIRST_DELAY_MS;
        retryTimer = setTimeout(open, wait);
        onStatus({ state: "locked", code: refusal.code, message: refusal.message, retryAt: Date.now() + wait });
        return;
      }
      // A close frame Docent sent with a reason says why it ended the connection.
      const closedBy = event.reason ? { code: String(event.code), message: event.reason } : {};
      onStatus({ state: "offline", ...closedBy });
      const wait = delay * (1 + JITTER * (2 * Math.random() - 1));
      delay = Math.min(delay * 2, MAX_DELAY_MS);
      retryTimer = setTimeout(open, wait);
    };
    // An error is always followed by `close`, which decides what comes next.
    ws.onerror = () => {};
  };

  // Leaving on purpose closes with 1000: Docent records the browser's own 1001 (going away) as
  // a page that vanished (a crashed tab; socket.js).
  addEventListener("pagehide", () => socket?.close(1000, "page closed"), { once: true });

  open();
  return {
    send(frame) {
      if (!socket || !welcomed || socket.readyState !== WebSocket.OPEN) return false;
      socket.send(JSON.stringify(frame));
      return true;
    },
    close() {
      closed = true;
      clearTimeout(retryTimer);
      const ws = socket;
      socket = null;
      welcomed = false;
      ws?.close();
    },
  };
}
