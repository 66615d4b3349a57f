// camera-kiosk.js: the kiosk's side of the live camera. When the shell's body says
// `data-camera="webrtc"`, the kiosk answers operator consoles that call it: an `offer` in a
// `signal` frame gets the device's camera and microphone (getUserMedia once, shared by every
// console watching), one RTCPeerConnection per console without STUN (host candidates on the
// LAN or loopback), an `answer` and the kiosk's ICE candidates back. A `hangup` (a console
// closing sends one), a failed connection (a console that vanished: about 16 s) or the kiosk's
// own socket going away ends that console's call; the camera is released when no console
// watches. A camera the browser cannot open is reported to the console as `{kind: "error",
// message}`. Docent relays these frames and never sees the media (docs/PROTOCOL.md, `signal`).

/**
 * Starts answering. `send` sends a frame on the kiosk's socket (false when offline); `on(type,
 * fn)` listens to the shell's frames and its `connection` ({online}) notices.
 * @param {{send: (frame: object) => boolean, on: (type: string, fn: (value: object) => void) => void}} shell
 */
export function answerCameraCalls({ send, on }) {
  const peers = new Map(); // operator client id -> RTCPeerConnection
  let media = null; // Promise of the MediaStream, while some console watches

  const signal = (to, data) => send({ type: "signal", to, data });

  /** The camera and microphone: the stream already open if it still runs, else a new one. */
  const openMedia = async () => {
    if (!navigator.mediaDevices?.getUserMedia) {
      throw new Error(
        `this page (${location.origin}) is not a secure context: the browser offers a camera only to https or localhost pages`,
      );
    }
    const open = media;
    if (open) {
      const stream = await open.catch(() => null);
      if (stream?.getTracks().every((track) => track.readyState === "live")) return stream;
      if (media === open) media = null; // it failed or ended (a camera unplugged): open again
    }
    if (!media) {
      const opening = navigator.mediaDevices.getUserMedia({ video: true, audio: true });
      media = opening;
      opening.catch(() => {
        if (media === opening) media = null; // the next call tries again
      });
    }
    return media;
  };

  const releaseMedia = () => {
    const stream = media;
    media = null;
    stream?.then((s) => s.getTracks().forEach((track) => track.stop()), () => {});
  };

  const hangUp = (from) => {
    const pc = peers.get(from);
    if (!pc) return;
    peers.delete(from);
    pc.close();
    if (peers.size === 0) releaseMedia();
  };

  const answer = async (from, sdp) => {
    peers.get(from)?.close(); // a console that calls again starts afresh, on the same camera
    const pc = new RTCPeerConnection({ iceServers: [] });
    peers.set(from, pc);
    const current = () => peers.get(from) === pc;
    pc.onicecandidate = ({ candidate }) => {
      if (candidate && current()) signal(from, { kind: "candidate", candidate: candidate.toJSON() });
    };
    pc.onconnectionstatechange = () => {
      if (pc.connectionState === "failed" && current()) hangUp(from);
    };
    try {
      // The offer is set at once, so candidates arriving meanwhile queue behind it.
      const [, stream] = await Promise.all([pc.setRemoteDescription({ type: "offer", sdp }), openMedia()]);
      if (!current()) return;
      for (const track of stream.getTracks()) pc.addTrack(track, stream);
      await pc.setLocalDescription(await pc.createAnswer());
      if (current()) signal(from, { kind: "answer", sdp: pc.localDescription.sdp });
    } catch (error) {
      if (!current()) return;
      console.warn("docent: cannot answer the console's camera call", error);
      signal(from, { kind: "error", message: describe(error) });
      hangUp(from);
    }
  };

  on("signal", ({ from, role, data }) => {
    if (role !== "operator" || typeof data !== "object" || data === null) return;
    if (data.kind === "offer" && typeof data.sdp === "string") {
      answer(from, data.sdp);
    } else if (data.kind === "candidate" && data.candidate) {
      peers.get(from)?.addIceCandidate(data.candidate).catch((error) => {
        console.warn("docent: a console's ICE candidate was refused", error);
      });
    } else if (data.kind === "hangup") {
      hangUp(from);
    }
  });
  // Client ids do not outlive a connection: after a reconnect, consoles call the new kiosk.
  on("connection", ({ online }) => {
    if (!online) for (const from of [...peers.keys()]) hangUp(from);
  });
}

/** A getUserMedia error in words for the operator: "NotFoundError: Requested device not found". */
function describe(error) {
  if (error?.name && error.name !== "Error") return `${error.name}: ${error.message}`;
  return String(error?.message ?? error);
}
