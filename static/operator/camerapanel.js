// camerapanel.js: the camera panel. Hidden when the server has no camera; otherwise, once signed
// in, it starts the camera script (camera.js, loaded only when this server serves it) or shows
// the camera's URL as an image. The camera hears of the kiosks only once the list of clients is
// whole again after a `welcome` (with the snapshot): an empty list in between would look as if
// its kiosk had left.

import { h } from "./dom.js";

/** The connected clients as the camera wants them: `[{client, role, name}]`. */
function clientList(all) {
  return [...all].map(([client, c]) => ({ client, role: c.role, name: c.name }));
}

/**
 * @param {{panel: HTMLElement, element: HTMLElement, script: string|undefined,
 *          send: (frame: object) => boolean, clients: () => Map<number, object>}} options
 *          `script`: the camera script's URL; `send`: over the websocket; `clients`: who is
 *          connected (clients.js)
 */
export function createCameraPanel({ panel, element, script, send, clients }) {
  let camera = null;
  let clientsKnown = false;

  return {
    /** Shows the panel for the camera `settings` (GET /api/operator) and starts the camera. */
    async start(settings) {
      panel.hidden = settings.kind === "none";
      if (panel.hidden || camera) return;
      if (script) {
        try {
          const module = await import(script);
          camera = module.createCamera({ element, send, settings });
          if (clientsKnown) camera.onClients(clientList(clients()));
          return;
        } catch (error) {
          console.error("docent console: the camera did not start", error);
        }
      }
      if (settings.kind === "url") element.replaceChildren(h("img", { src: settings.url, alt: "robot camera" }));
      else element.replaceChildren(h("p", { class: "muted" }, "camera not available in this server"));
    },
    /** Signed out: the camera stops (started again on the next sign-in). */
    stop() {
      camera?.stop();
      camera = null;
    },
    /** A `signal` frame for the camera call. */
    signal(frame) {
      camera?.onSignal(frame);
    },
    /** A new connection: its list of clients is not whole until the snapshot. */
    clientsUnknown() {
      clientsKnown = false;
    },
    /** The list of clients is whole: the camera hears of it from now on. */
    clientsWhole() {
      clientsKnown = true;
    },
    /** The connected clients changed: the camera hears of it once the list is whole. */
    clients(all) {
      if (clientsKnown) camera?.onClients(clientList(all));
    },
  };
}
