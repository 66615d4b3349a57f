// camera.js: the robot's camera and microphone in the operator console. With `camera: webrtc`
// (docent.yaml `operator.camera`) the console calls a kiosk shell over Docent's websocket
// (`signal` frames, relayed by the server; the media goes straight between the two browsers,
// without STUN) and plays what it sends in a <video>, muted until the operator turns the sound
// on (browsers allow sound only after a gesture). It picks the first kiosk (a selector offers
// the others), calls again when that kiosk reconnects or the call fails, and says what is going
// on: connecting, live, no camera on the kiosk. Kiosks that share a name (every kiosk shell
// says "kiosk") are told apart by their client ids, with a warning. When the kiosk called
// leaves, the one called next must be that kiosk again for sure: the only one of its name, and
// not one seen connected beside it (another device). Otherwise the console asks the operator to
// choose rather than show another kiosk's camera without a word. With a camera URL it shows
// the MJPEG stream in an <img>, reloaded with backoff after an error (a stream that merely
// stops fires no event in an <img>, so a Reload button is offered too). The console mounts it
// (createCamera) and feeds it the `signal` frames and the list of connected clients.

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

/**
 * The kiosk to call after the one called before (`previous`: {client, name}, or null when none
 * was) left: the first kiosk when none was called; the only kiosk with its name when no kiosk
 * of that name was seen beside it (`others`: client ids seen connected at the same time as it,
 * so other devices); the first kiosk when none has its name. Null when there is no kiosk, and
 * "ask" when the name does not tell which kiosk it was.
 */
export function nextKiosk(kiosks, previous, others) {
  if (!kiosks.length) return null;
  if (!previous) return kiosks[0];
  const same = kiosks.filter((k) => k.name === previous.name);
  if (!same.length) return kiosks[0];
  if (same.length === 1 && !others.has(same[0].client)) return same[0];
  return "ask";
}

/** The names several of `kiosks` share: `[[name, [client, ...]], ...]`. */
function sharedNames(kiosks) {
  const byName = new Map();
  for (const k of kiosks) byName.set(k.name ?? "", [...(byName.get(k.name ?? "") ?? []), k.client]);
  return [...byName].filter(([, ids]) => ids.length > 1);
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
  const warning = el("p", { class: "camera-warning", role: "note" });
  warning.hidden = true;
  const bar = el("div", { class: "camera-bar" });
  bar.append(picker, sound, retry);
  element.append(video, bar, status, warning);

  let kiosks = []; // the connected kiosks, in the order given
  let kiosk = null; // the kiosk called (client id), or null
  let previous = null; // {client, name} of the kiosk called last, to find it again after it reconnects
  let others = new Set(); // the kiosks seen connected beside it: not it, whatever their names
  let asking = false; // the kiosk called left and the console cannot tell which one it is now
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
    const placeholder = kiosk === null && kiosks.length ? [el("option", { value: "", text: "choose a kiosk…" })] : [];
    picker.replaceChildren(
      ...placeholder,
      ...kiosks.map((k) => {
        const option = el("option", { value: String(k.client), text: label(k.client) });
        option.selected = k.client === kiosk;
        return option;
      }),
    );
    if (placeholder.length) picker.value = "";
    picker.hidden = kiosks.length < 2 && !asking;
    const shared = sharedNames(kiosks);
    warning.hidden = !shared.length;
    warning.textContent = shared
      .map(([name, ids]) => `${ids.length} kiosks are called “${name || "(no name)"}”: only their numbers (${ids.map((id) => `#${id}`).join(", ")}) tell them apart.`)
      .join(" ");
  };

  /** Calls `next` (a kiosk, or null for none). */
  const callKiosk = (next) => {
    asking = false;
    kiosk = next?.client ?? null;
    if (next) {
      previous = { client: next.client, name: next.name };
      others = new Set(kiosks.filter((k) => k.client !== kiosk).map((k) => k.client));
    }
    retryDelay = RETRY_FIRST_MS;
    fillPicker();
    if (call?.kiosk !== kiosk || !call) {
      hangUp({ tell: false });
      dial();
    }
  };

  picker.addEventListener("change", () => {
    const chosen = kiosks.find((k) => String(k.client) === picker.value);
    // Chosen: let go of the focus, so that the console's typing goes to its search again.
    picker.blur();
    if (!chosen || chosen.client === kiosk) return;
    callKiosk(chosen);
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
      if (still) {
        // Every other kiosk connected now is another device, whatever its name.
        for (const k of kiosks) if (k.client !== kiosk) others.add(k.client);
        fillPicker();
        // The same kiosk, but nothing running (the console's own socket came back): call it.
        if (!call && !retryTimer && element.dataset.state !== "error") dial();
        return;
      }
      if (asking && kiosks.length) {
        fillPicker();
        return;
      }
      // The kiosk left (or reconnected under a new id): find it again, if the name tells.
      const gone = kiosk;
      const next = nextKiosk(kiosks, asking ? null : previous, others);
      if (next !== "ask") {
        callKiosk(next);
        return;
      }
      hangUp({ tell: false });
      kiosk = null;
      asking = true;
      fillPicker();
      const name = previous?.name ?? "kiosk";
      show(
        "choose",
        `${gone === null ? "the kiosk called before" : `${name} (#${gone})`} left; ${kiosks.filter((k) => k.name === previous?.name).length > 1 ? "several kiosks are" : "another kiosk is"} called “${name}”: choose the one to watch`,
      );
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
