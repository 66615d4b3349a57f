// camera.js: the robot's camera and microphone in the operator console. With `camera: webrtc`
// (docent.yaml `operator.camera`) the console calls a kiosk shell over Docent's websocket
// (`signal` frames, relayed by the server; the media goes straight between the two browsers,
// without STUN) and plays what it sends in a <video>, muted until the operator turns the sound
// on (browsers allow sound only after a gesture). It picks the first kiosk (a selector offers
// the others), calls again when that kiosk reconnects or the call fails, and says what is going
// on: connecting, live, no camera on the kiosk. With a camera URL it shows the MJPEG stream in
// an <img>, reloaded with backoff after an error (a stream that merely stops fires no event in
// an <img>, so a Reload button is offered too). The console mounts it (createCamera) and feeds
// it the `signal` frames and the list of connected clients.

const RETRY_FIRST_MS = 1_000;
const RETRY_MAX_MS = 15_000;
/** How long a call may stay `disconnected` (it may recover by itself) before calling again. */
const DISCONNECTED_GRACE_MS = 4_000;

/**
 * Shows the camera in `element` (its contents are replaced).
 * @param {{element: HTMLElement, send: (frame: object) => boolean,
 *          settings: {kind: "webrtc"} | {kind: "url", url: string} | {kind: "none"}}} options
 * `settings` is the `camera` of `GET /api/operator`; `send` sends a frame on the console's
 * socket (false when offline).
 * @returns {{onSignal: (frame: object) => void,
 *            onClients: (clients: {client: number, role: string, name: string|null}[]
 *                                 | Map<number, {role: string, name: string|null}>) => void,
 *            stop: () => void}} `onSignal` takes `signal` frames, `onClients` the connected
 * clients whenever they change, `stop` ends the call and empties `element`.
 */
export function createCamera({ element, send, settings }) {
  element.replaceChildren();
  element.classList.add("camera-view");
  if (settings?.kind === "webrtc") return webrtcCamera(element, send);
  if (settings?.kind === "url" && settings.url) return urlCamera(element, settings.url);
  element.append(el("p", { class: "camera-state muted", text: "no camera (operator.camera: none)" }));
  element.dataset.state = "none";
  return { onSignal() {}, onClients() {}, stop() { element.replaceChildren(); } };
}

/** A small element: `el("p", {class, text, ...attributes})`. */
function el(tag, { text, ...attrs } = {}) {
  const node = document.createElement(tag);
  for (const [name, value] of Object.entries(attrs)) node.setAttribute(name, value);
  if (text !== undefined) node.textContent = text;
  return node;
}

/**
 * The kiosks among `clients`: a list of `{client, role, name}` (kept in its order), or a Map or
 * object from client id to `{role, name}` (by id).
 */
function kiosksOf(clients) {
  const list = Array.isArray(clients)
    ? clients
    : [...(clients instanceof Map ? clients : Object.entries(clients ?? {}))]
        .map(([id, c]) => ({ ...c, client: Number(id) }))
        .sort((a, b) => a.client - b.client);
  return list.filter((c) => c?.role === "kiosk");
}

/** The kiosk with the name of the one called before, else the first kiosk. */
function pickKiosk(kiosks, previousName) {
  return kiosks.find((k) => previousName !== undefined && k.name === previousName) ?? kiosks[0] ?? null;
}

function webrtcCamera(element, send) {
  const picker = el("select", { class: "camera-pick", "aria-label": "Kiosk camera" });
  picker.hidden = true;
  const video = el("video", { class: "camera-video" });
  Object.assign(video, { autoplay: true, playsInline: true, muted: true });
  video.style.cssText = "display:block;width:100%;background:#000;aspect-ratio:4/3";
  const sound = el("button", { type: "button", class: "camera-sound", text: "Sound on" });
  sound.hidden = true;
  const retry = el("button", { type: "button", class: "camera-retry", text: "Try again" });
  retry.hidden = true;
  const status = el("p", { class: "camera-state", role: "status" });
  const bar = el("div", { class: "camera-bar" });
  bar.append(picker, sound, retry);
  element.append(video, bar, status);

  let kiosks = []; // the connected kiosks, in the order given
  let kiosk = null; // the kiosk called (client id), or null
  let kioskName; // its name, to find it again after it reconnects
  let call = null; // {pc, kiosk, offeredAt, firstFrameMs}
  let retryDelay = RETRY_FIRST_MS;
  let retryTimer = null;
  let graceTimer = null;
  let stopped = false;

  const show = (state, text, title = "") => {
    element.dataset.state = state;
    status.textContent = text;
    status.title = title;
    retry.hidden = !["error", "failed"].includes(state);
  };

  const hangUp = ({ tell = true } = {}) => {
    clearTimeout(retryTimer);
    clearTimeout(graceTimer);
    retryTimer = graceTimer = null;
    if (!call) return;
    const { pc, kiosk: to } = call;
    call = null;
    pc.close();
    // Only to a kiosk still there: the server answers a call to a gone client with an error.
    if (tell && kiosks.some((k) => k.client === to)) send({ type: "signal", to, data: { kind: "hangup" } });
    video.srcObject = null;
    sound.hidden = true;
  };

  const callAgainLater = (why) => {
    hangUp();
    if (stopped || kiosk === null) return;
    show("failed", `${why}; calling again in ${Math.round(retryDelay / 1000)} s`);
    retryTimer = setTimeout(dial, retryDelay);
    retryDelay = Math.min(retryDelay * 2, RETRY_MAX_MS);
  };

  async function dial() {
    hangUp();
    if (stopped) return;
    if (kiosk === null) {
      show("waiting", "no kiosk connected");
      return;
    }
    const to = kiosk;
    const pc = new RTCPeerConnection({ iceServers: [] });
    const mine = { pc, kiosk: to, offeredAt: 0, firstFrameMs: null };
    call = mine;
    const current = () => call === mine;
    show("connecting", `connecting to ${label(to)}…`);
    pc.addTransceiver("video", { direction: "recvonly" });
    pc.addTransceiver("audio", { direction: "recvonly" });
    const stream = new MediaStream();
    pc.ontrack = ({ track }) => {
      stream.addTrack(track);
      if (video.srcObject !== stream) video.srcObject = stream;
      if (track.kind === "audio") sound.hidden = false;
    };
    pc.onicecandidate = ({ candidate }) => {
      if (!candidate || !current()) return;
      send({ type: "signal", to, data: { kind: "candidate", candidate: candidate.toJSON() } });
    };
    pc.onconnectionstatechange = () => {
      if (!current()) return;
      clearTimeout(graceTimer);
      if (pc.connectionState === "failed") {
        callAgainLater("the connection to the kiosk failed");
      } else if (pc.connectionState === "disconnected") {
        show("connecting", "connection interrupted…");
        const lost = () => current() && callAgainLater("the connection to the kiosk was lost");
        graceTimer = setTimeout(lost, DISCONNECTED_GRACE_MS);
      } else if (pc.connectionState === "connected" && video.readyState >= 2) {
        live();
      }
    };
    try {
      await pc.setLocalDescription(await pc.createOffer());
      if (!current()) return;
      mine.offeredAt = performance.now();
      if (!send({ type: "signal", to, data: { kind: "offer", sdp: pc.localDescription.sdp } })) {
        callAgainLater("not connected to Docent");
      }
    } catch (error) {
      if (current()) callAgainLater(`cannot make an offer (${error.message})`);
    }
  }

  const live = () => {
    if (!call) return;
    retryDelay = RETRY_FIRST_MS;
    call.firstFrameMs ??= Math.round(performance.now() - call.offeredAt);
    const { videoWidth: w, videoHeight: h } = video;
    show("live", `live from ${label(call.kiosk)}`, `${w}x${h}, first picture ${call.firstFrameMs} ms after the offer`);
    element.dataset.firstFrameMs = String(call.firstFrameMs);
  };
  // `loadeddata`: the first frame is there to show.
  video.addEventListener("loadeddata", () => call?.pc.connectionState === "connected" && live());
  video.addEventListener("resize", () => element.dataset.state === "live" && live());

  const label = (id) => {
    const k = kiosks.find((c) => c.client === id);
    return k?.name ? `${k.name} (#${id})` : `kiosk #${id}`;
  };

  const fillPicker = () => {
    picker.replaceChildren(
      ...kiosks.map((k) => {
        const option = el("option", { value: String(k.client), text: label(k.client) });
        option.selected = k.client === kiosk;
        return option;
      }),
    );
    picker.hidden = kiosks.length < 2;
  };

  picker.addEventListener("change", () => {
    const chosen = kiosks.find((k) => String(k.client) === picker.value);
    if (!chosen || chosen.client === kiosk) return;
    kiosk = chosen.client;
    kioskName = chosen.name;
    retryDelay = RETRY_FIRST_MS;
    dial();
  });
  sound.addEventListener("click", () => {
    video.muted = !video.muted;
    sound.textContent = video.muted ? "Sound on" : "Sound off";
    if (!video.muted) video.play().catch(() => {});
  });
  retry.addEventListener("click", () => {
    retryDelay = RETRY_FIRST_MS;
    dial();
  });
  // A console closed or reloaded hangs up, so the kiosk releases its camera at once.
  const leave = () => hangUp();
  addEventListener("pagehide", leave);

  show("waiting", "no kiosk connected");

  return {
    onSignal({ from, data }) {
      if (!call || from !== call.kiosk || typeof data !== "object" || data === null) return;
      const { pc } = call;
      if (data.kind === "answer" && typeof data.sdp === "string") {
        pc.setRemoteDescription({ type: "answer", sdp: data.sdp }).catch((error) => {
          callAgainLater(`the kiosk's answer was not usable (${error.message})`);
        });
      } else if (data.kind === "candidate" && data.candidate) {
        pc.addIceCandidate(data.candidate).catch((error) => {
          console.warn("docent: a kiosk ICE candidate was refused", error);
        });
      } else if (data.kind === "error") {
        hangUp({ tell: false });
        show("error", `no camera on the kiosk: ${data.message ?? "unknown error"}`);
      }
    },
    onClients(clients) {
      kiosks = kiosksOf(clients);
      const still = kiosks.find((k) => k.client === kiosk);
      if (!still) {
        // The kiosk left (or reconnected under a new id): find it again by its name.
        const next = pickKiosk(kiosks, kioskName);
        kiosk = next?.client ?? null;
        if (next) kioskName = next.name;
        retryDelay = RETRY_FIRST_MS;
        fillPicker();
        if (call?.kiosk !== kiosk) {
          hangUp({ tell: false });
          dial();
        }
        return;
      }
      fillPicker();
      // The same kiosk, but nothing running (the console's own socket came back): call it.
      if (!call && !retryTimer && element.dataset.state !== "error") dial();
    },
    stop() {
      stopped = true;
      removeEventListener("pagehide", leave);
      hangUp();
      element.replaceChildren();
    },
  };
}

function urlCamera(element, url) {
  const status = el("p", { class: "camera-state", role: "status" });
  // A stream that stops or freezes fires no event in an <img>: the operator can reload it.
  const reload = el("button", { type: "button", class: "camera-retry", text: "Reload" });
  let img = null;
  let delay = RETRY_FIRST_MS;
  let timer = null;
  const show = (state, text) => {
    element.dataset.state = state;
    status.textContent = text;
  };
  // A fresh <img> for every attempt, so a late event of an abandoned one changes nothing.
  const load = () => {
    timer = null;
    const attempt = el("img", { class: "camera-image", alt: "the robot's camera" });
    attempt.style.cssText = "display:block;width:100%;background:#000";
    // An MJPEG stream fires `load` with its first picture.
    attempt.addEventListener("load", () => {
      if (img !== attempt) return;
      delay = RETRY_FIRST_MS;
      show("live", "live");
    });
    attempt.addEventListener("error", () => {
      if (img !== attempt || timer !== null) return;
      show("failed", `no picture from the camera; trying again in ${Math.round(delay / 1000)} s`);
      timer = setTimeout(load, delay);
      delay = Math.min(delay * 2, RETRY_MAX_MS);
    });
    if (img) {
      img.removeAttribute("src"); // ends its request, so an abandoned stream does not go on
      img.replaceWith(attempt);
    } else {
      element.prepend(attempt);
    }
    img = attempt;
    show("connecting", "connecting to the camera…");
    // In a later task: given the same address at once, the new <img> would share the old
    // request (and its frozen stream) instead of making a new one.
    setTimeout(() => {
      if (img === attempt) attempt.src = url;
    }, 0);
  };
  reload.addEventListener("click", () => {
    clearTimeout(timer);
    delay = RETRY_FIRST_MS;
    load();
  });
  const bar = el("div", { class: "camera-bar" });
  bar.append(reload);
  element.append(bar, status);
  load();
  return {
    onSignal() {},
    onClients() {},
    stop() {
      clearTimeout(timer);
      img?.removeAttribute("src");
      img = null;
      element.replaceChildren();
    },
  };
}
