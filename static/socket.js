// socket.js: the one websocket a shell (kiosk or projector) keeps to Docent. Says hello with
// its role (and what the shell adds, e.g. the page a kiosk shows), hands every frame to the
// shell and reconnects after a server restart or network loss. The retries stay quick so a
// returning server finds the kiosk again within about a second: 0.25 s doubling to 1 s, each
// +-20 % at random so that many screens do not knock in step; at most one attempt a second
// once the server has been away a while, a polite rate for a server starting up.
// What a lost connection looks like to visitors is the shell's business (outage.js).
// A page leaving on purpose (a reload, a navigation, its window closed) closes the socket with
// 1000: the browser's own 1001 ("going away"), which Chromium also sends for a tab that
// crashed, is then what tells Docent that a page vanished (`client.left` `ended: "lost"`).

const FIRST_DELAY_MS = 250;
const MAX_DELAY_MS = 1_000;
const JITTER = 0.2;

/**
 * Opens the socket and keeps it open.
 * @param {{path: string, role: string, name?: string,
 *          hello?: object | (() => object), onFrame: (frame: object) => void,
 *          onOnline?: (online: boolean) => void}} options `hello`: extra fields of the hello
 *          frame (e.g. verbs), or a function giving them at each connection; `onOnline(true)`
 *          on each welcome, `onOnline(false)` when a welcomed connection is lost.
 * @returns {{send: (frame: object) => boolean, online: () => boolean}} `send` is false when
 *          not connected.
 */
export function keepConnected({ path, role, name = null, hello = {}, onFrame, onOnline = () => {} }) {
  const url = new URL(path, location.href);
  url.protocol = url.protocol === "https:" ? "wss:" : "ws:";
  let socket = null;
  let welcomed = false;
  let delay = FIRST_DELAY_MS;

  const open = () => {
    const ws = new WebSocket(url);
    socket = ws;
    ws.onopen = () => {
      const extra = typeof hello === "function" ? hello() : hello;
      ws.send(JSON.stringify({ ...extra, type: "hello", role, name }));
    };
    ws.onmessage = (message) => {
      let frame;
      try {
        frame = JSON.parse(message.data);
      } catch {
        return;
      }
      if (frame.type === "welcome") {
        // Back off again from the start only once the server really answered.
        welcomed = true;
        delay = FIRST_DELAY_MS;
        onFrame(frame);
        onOnline(true);
        return;
      }
      onFrame(frame);
    };
    ws.onclose = () => {
      if (socket !== ws) return;
      socket = null;
      if (welcomed) onOnline(false);
      welcomed = false;
      const wait = delay * (1 + JITTER * (2 * Math.random() - 1));
      delay = Math.min(delay * 2, MAX_DELAY_MS);
      setTimeout(open, wait);
    };
    // An error is always followed by `close`, which schedules the retry.
    ws.onerror = () => {};
  };

  addEventListener("pagehide", () => {
    const ws = socket;
    socket = null; // no reconnecting from a page on its way out
    ws?.close(1000, "page closed");
  });
  // Back from the back-forward cache: connect again.
  addEventListener("pageshow", (event) => {
    if (event.persisted && socket === null) open();
  });

  open();
  return {
    send(frame) {
      if (!socket || !welcomed || socket.readyState !== WebSocket.OPEN) return false;
      socket.send(JSON.stringify(frame));
      return true;
    },
    online: () => welcomed && socket?.readyState === WebSocket.OPEN,
  };
}

/** A path under `pages/` or `media/` as a URL path: each segment percent-encoded. */
export function encodePath(path) {
  return path.split("/").map(encodeURIComponent).join("/");
}
