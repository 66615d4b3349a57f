// socket.js: the one websocket a shell (kiosk or projector) keeps to Docent. Says hello with
// its role, hands every frame to the shell, reconnects after a server restart or network loss
// with exponential backoff and jitter (0.5 s doubling to 10 s, +-30 %), and shows the
// element #docent-offline only after 3 s without a welcomed connection.

const FIRST_DELAY_MS = 500;
const MAX_DELAY_MS = 10_000;
const JITTER = 0.3;
const OFFLINE_BANNER_AFTER_MS = 3_000;

/**
 * Opens the socket and keeps it open.
 * @param {{path: string, role: string, name?: string,
 *          hello?: object, onFrame: (frame: object) => void,
 *          onOnline?: (online: boolean) => void}} options (`hello`: extra fields, e.g. verbs)
 * @returns {{send: (frame: object) => boolean}} `send` is false when not connected.
 */
export function keepConnected({ path, role, name = null, hello = {}, onFrame, onOnline = () => {} }) {
  const url = new URL(path, location.href);
  url.protocol = url.protocol === "https:" ? "wss:" : "ws:";
  const banner = document.getElementById("docent-offline");
  let socket = null;
  let welcomed = false;
  let delay = FIRST_DELAY_MS;
  let bannerTimer = null;

  const armBanner = () => {
    bannerTimer ??= setTimeout(() => {
      if (banner) banner.hidden = false;
    }, OFFLINE_BANNER_AFTER_MS);
  };
  const online = () => {
    clearTimeout(bannerTimer);
    bannerTimer = null;
    if (banner) banner.hidden = true;
  };

  const open = () => {
    const ws = new WebSocket(url);
    socket = ws;
    ws.onopen = () => ws.send(JSON.stringify({ ...hello, type: "hello", role, name }));
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
        online();
        onOnline(true);
      }
      onFrame(frame);
    };
    ws.onclose = () => {
      if (socket !== ws) return;
      socket = null;
      if (welcomed) onOnline(false);
      welcomed = false;
      armBanner();
      const wait = delay * (1 + JITTER * (2 * Math.random() - 1));
      delay = Math.min(delay * 2, MAX_DELAY_MS);
      setTimeout(open, wait);
    };
    // An error is always followed by `close`, which schedules the retry.
    ws.onerror = () => {};
  };

  armBanner();
  open();
  return {
    send(frame) {
      if (!socket || !welcomed || socket.readyState !== WebSocket.OPEN) return false;
      socket.send(JSON.stringify(frame));
      return true;
    },
  };
}

/** A path under `pages/` or `media/` as a URL path: each segment percent-encoded. */
export function encodePath(path) {
  return path.split("/").map(encodeURIComponent).join("/");
}
