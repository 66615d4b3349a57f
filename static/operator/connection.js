// connection.js: the console's websocket. Says hello as an operator with the credential, hands
// every frame on, and reconnects after a network loss or a server restart (backoff 0.5 s
// doubling to 10 s, +-30 % jitter). Unlike the kiosk's socket.js it gives up for good when the
// server refuses the credential (`unauthorized`, `too-many-attempts`): trying again with the
// same credential could only lock the operator out, so the console asks for it again instead.

const FIRST_DELAY_MS = 500;
const MAX_DELAY_MS = 10_000;
const JITTER = 0.3;
/** Error codes that end the connection for good: the credential is wrong or locked out. */
const REFUSALS = new Set(["unauthorized", "too-many-attempts"]);

/**
 * Connects and keeps connected until refused or closed.
 * @param {{path: string, token: string|null, name: string|null,
 *          onFrame: (frame: object) => void,
 *          onStatus: (status: {state: "connecting"|"online"|"offline"|"refused",
 *                              code?: string, message?: string}) => void}} options
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
      if (!welcomed && frame.type === "error" && REFUSALS.has(frame.code)) {
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
    ws.onclose = () => {
      if (socket !== ws) return;
      socket = null;
      welcomed = false;
      if (refusal) {
        closed = true;
        onStatus({ state: "refused", code: refusal.code, message: refusal.message });
        return;
      }
      if (closed) return;
      onStatus({ state: "offline" });
      const wait = delay * (1 + JITTER * (2 * Math.random() - 1));
      delay = Math.min(delay * 2, MAX_DELAY_MS);
      retryTimer = setTimeout(open, wait);
    };
    // An error is always followed by `close`, which decides what comes next.
    ws.onerror = () => {};
  };

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
