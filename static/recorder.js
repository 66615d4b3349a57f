// recorder.js: the kiosk's side of recording a visitor session (docs/CORPUS.md, "Recording";
// frames in docs/PROTOCOL.md). On a `record` frame it opens the microphone (and camera), records
// WebM with MediaRecorder in one-second chunks and uploads them strictly in order, each with the
// recording's own token, keeping the chunks not yet acknowledged in a bounded queue: a network
// error or a 5xx is retried with back-off (a 503 `corpus-unwritable` pauses: a full or
// read-only corpus disk does not run down the retry budget), a 409 resumes from the chunk the server names, a 410
// ends the recording (stopped, or consent withdrawn), and so does a 507 (a recording limit). It places the first sample on the server's
// clock (a few `clock` round trips, the best kept) and says so in `recording-started`; on
// `record-stop` it stops, uploads what is left and says `recording-stopped`. Whatever fails
// (permission, device, recorder, uploads past the retry budget, a full queue) is reported at
// once in `recording-failed`, which the operators see. A page that goes away (closed, reloaded,
// navigated: `pagehide`) is not a failure: its recordings end quietly, and the server closes
// them as `kiosk-left` when the connection ends; a device that ends is reported a second later
// only if the page still runs (a closing browser ends the tracks just before the page), so
// only a device that ends while the page stays (unplugged) is `no-device`. A page reload ends the
// recording: the next one is a new file with its own WebM header. A piece of recording larger than the chunk
// limit the `record` frame gives (`max_chunk_bytes`) goes up as consecutive chunks: the file is
// their concatenation, so nothing is lost.

const CHUNK_MS = 1000;
const CLOCK_SAMPLES = 5;
const CLOCK_TIMEOUT_MS = 2000;
const MAX_QUEUED_CHUNKS = 120; // two minutes of chunks waiting for the network
const RETRY_FIRST_MS = 250;
const RETRY_MAX_MS = 4000;
const RETRY_BUDGET_MS = 60_000; // failing this long without one chunk stored: reported
const DEFAULT_MAX_CHUNK_BYTES = 8 * 1024 * 1024; // a server that does not say its limit
// A device that ends is reported this much later, if the page still runs: a browser that is
// closing ends the tracks first and the page a few milliseconds after (without `pagehide`
// when the whole browser closes), which must not read as an unplugged device. Measured by
// tests/e2e/recording-alarms.test.mjs: closing the kiosk's browser reported `no-device` in 2
// of 4 runs without it.
const DEVICE_GRACE_MS = 1000;

/**
 * `blob` cut into consecutive pieces of at most `max` bytes (one piece when it fits; none
 * when it is empty): uploaded in order, they make the same file as `blob` in one.
 * @param {Blob} blob
 * @param {number} max
 * @returns {Blob[]}
 */
export function splitChunk(blob, max) {
  if (!(max > 0)) throw new RangeError(`a chunk limit must be positive, not ${max}`);
  const pieces = [];
  for (let at = 0; at < blob.size; at += max) pieces.push(blob.slice(at, Math.min(at + max, blob.size)));
  return pieces;
}

/**
 * Starts answering `record` and `record-stop` frames.
 * @param {{send: (frame: object) => boolean, on: (type: string, fn: Function) => Function}} shell
 */
export function answerRecordRequests({ send, on }) {
  let current = null;
  const asked = []; // every `record` frame's recording and session, for tests and diagnosis
  const clockWaiters = new Map(); // t0 -> resolve
  on("clock", (frame) => {
    clockWaiters.get(frame.t0)?.({ t1: performance.now(), serverUs: frame.server_us });
    clockWaiters.delete(frame.t0);
  });
  const sampleClock = () => new Promise((resolve) => {
    const t0 = performance.now();
    clockWaiters.set(t0, ({ t1, serverUs }) => resolve({ t0, t1, serverUs }));
    if (!send({ type: "clock", t0 })) resolve(null);
    setTimeout(() => clockWaiters.delete(t0) && resolve(null), CLOCK_TIMEOUT_MS);
  });
  /** The best of a few clock samples: the shortest round trip bounds the error. */
  const syncClock = async () => {
    let best = null;
    for (let i = 0; i < CLOCK_SAMPLES; i++) {
      const sample = await sampleClock();
      if (sample && (!best || sample.t1 - sample.t0 < best.t1 - best.t0)) best = sample;
    }
    return best;
  };
  const running = new Map(); // id -> recording not yet ended (one, or a stopping one beside it)
  // The page is going away: every recording ends without a report (the server stops it when
  // the connection ends, `kiosk-left`), so the tracks the browser ends with the page do not
  // read as unplugged devices. A page kept in the back/forward cache that comes back
  // reconnects, and the server asks it to record afresh.
  window.addEventListener("pagehide", () => {
    for (const recording of running.values()) recording.leave();
    running.clear();
  });
  on("record", (frame) => {
    asked.push({ recording: frame.recording, session: frame.session });
    // One being stopped (the session ended, the next began) uploads its last chunk meanwhile;
    // any other was closed by the server already (this kiosk reconnected).
    for (const [id, old] of running) {
      if (old.status().state === "ended") running.delete(id);
      else if (old.status().state !== "stopping") {
        old.abandon();
        running.delete(id);
      }
    }
    current = record(frame, { send, syncClock });
    running.set(frame.recording, current);
  });
  on("record-stop", (frame) => running.get(frame.recording)?.stop());
  window.docentRecorder = {
    get current() {
      return current?.status();
    },
    asked,
  };
}

function record(frame, { send, syncClock }) {
  const id = frame.recording;
  const maxChunkBytes = frame.max_chunk_bytes > 0 ? frame.max_chunk_bytes : DEFAULT_MAX_CHUNK_BYTES;
  const queue = []; // {seq, blob}, oldest first, not yet acknowledged
  let recorder = null;
  let stream = null;
  let nextSeq = 0;
  let uploading = false;
  let stopping = false;
  let ended = false;
  let failingSince = null;
  let retryMs = RETRY_FIRST_MS;
  let startTime = null;
  let acked = 0;

  const release = () => {
    for (const track of stream?.getTracks() ?? []) track.stop();
  };
  const end = () => {
    ended = true;
    queue.length = 0;
    if (recorder?.state === "recording") recorder.stop();
    release();
  };
  const fail = (code, message) => {
    if (ended) return;
    // A warning, not an error: the operators are told (recording.failed), the visitor is not.
    console.warn(`docent: recording ${id} failed (${code}): ${message}`);
    send({ type: "recording-failed", recording: id, code, message });
    end();
  };
  const finishIfDone = () => {
    if (stopping && !ended && recorder?.state === "inactive" && queue.length === 0 && !uploading) {
      ended = true;
      release();
      send({ type: "recording-stopped", recording: id });
    }
  };

  const pump = async () => {
    if (uploading || ended || queue.length === 0) return finishIfDone();
    uploading = true;
    const chunk = queue[0];
    let response = null;
    try {
      response = await fetch(frame.upload + chunk.seq, {
        method: "PUT",
        headers: { Authorization: `Bearer ${frame.token}`, "Content-Type": "application/octet-stream" },
        body: chunk.blob,
      });
    } catch {
      response = null; // the network: retried below
    }
    uploading = false;
    if (ended) return;
    if (response?.ok) {
      const answer = await response.json().catch(() => ({}));
      acked = answer.acked ?? acked;
      queue.shift();
      failingSince = null;
      retryMs = RETRY_FIRST_MS;
      return pump();
    }
    if (response?.status === 409) {
      const { next } = await response.json().catch(() => ({}));
      while (queue.length && queue[0].seq < next) queue.shift();
      if (queue.length && queue[0].seq > next) {
        return fail("upload-failed", `the server expects chunk ${next}, which this kiosk no longer holds`);
      }
      return pump();
    }
    if (response?.status === 410 || response?.status === 507) {
      // Closed by the server (stopped, consent declined or withdrawn; 507: a recording limit
      // or the disk's reserve, which the server has told operators): nothing more to send.
      return end();
    }
    if (response && response.status < 500) {
      return fail("upload-failed", `the server refused chunk ${chunk.seq}: HTTP ${response.status}`);
    }
    // 503 corpus-unwritable: the corpus disk is full or read-only, which the operators are
    // told; the recording pauses (the chunks wait in the queue) instead of running down the
    // retry budget, and goes on once the server stores chunks again.
    const refusal = response?.status === 503 ? await response.json().catch(() => ({})) : {};
    if (refusal.code === "corpus-unwritable") failingSince = null;
    failingSince ??= performance.now();
    if (performance.now() - failingSince > RETRY_BUDGET_MS) {
      const why = response ? `HTTP ${response.status}` : "the network failed";
      return fail("upload-failed", `chunks could not be uploaded for ${RETRY_BUDGET_MS / 1000} s (${why}); later sound is not recorded`);
    }
    setTimeout(pump, retryMs);
    retryMs = Math.min(retryMs * 2, RETRY_MAX_MS);
  };

  const start = async () => {
    const tracks = frame.tracks ?? ["audio"];
    const clock = syncClock();
    try {
      stream = await navigator.mediaDevices.getUserMedia({
        audio: tracks.includes("audio"),
        video: tracks.includes("video"),
      });
    } catch (error) {
      const code = error?.name === "NotAllowedError" || error?.name === "SecurityError"
        ? "permission-denied"
        : ["NotFoundError", "NotReadableError", "OverconstrainedError"].includes(error?.name)
          ? "no-device"
          : "recorder-error";
      return fail(code, `${error?.name ?? "Error"}: ${error?.message ?? error}`);
    }
    if (ended) return release();
    if (stopping) {
      ended = true;
      release();
      send({ type: "recording-stopped", recording: id });
      return;
    }
    if (typeof MediaRecorder === "undefined" || !MediaRecorder.isTypeSupported(frame.mime)) {
      return fail("unsupported", `this browser cannot record ${frame.mime}`);
    }
    try {
      recorder = new MediaRecorder(stream, { mimeType: frame.mime });
    } catch (error) {
      return fail("recorder-error", String(error?.message ?? error));
    }
    recorder.ondataavailable = (event) => {
      if (ended || event.data.size === 0) return;
      for (const blob of splitChunk(event.data, maxChunkBytes)) {
        if (queue.length >= MAX_QUEUED_CHUNKS) {
          return fail("queue-full", `${MAX_QUEUED_CHUNKS} chunks are waiting for upload; later sound is not recorded`);
        }
        queue.push({ seq: nextSeq++, blob });
      }
      pump();
    };
    recorder.onerror = (event) => fail("recorder-error", String(event.error?.message ?? "MediaRecorder failed"));
    recorder.onstop = () => finishIfDone();
    recorder.onstart = async () => {
      const best = await clock;
      if (!best || ended) return;
      const offsetMs = best.serverUs / 1000 - (best.t0 + best.t1) / 2;
      send({
        type: "recording-started",
        recording: id,
        mime: recorder.mimeType || frame.mime,
        mono_us: Math.max(0, Math.round((startTime + offsetMs) * 1000)),
        clock_error_us: Math.round(((best.t1 - best.t0) / 2) * 1000),
      });
    };
    for (const track of stream.getTracks()) {
      track.onended = () => setTimeout(() => fail("no-device", `the ${track.kind} device stopped (unplugged or taken by another program)`), DEVICE_GRACE_MS);
    }
    // The first sample is the one arriving as `start()` is called: Chromium fires the `start`
    // event about 50 ms later, and taking that time put every sound 62 ms late (measured by
    // tests/e2e/recording.test.mjs's alignment test; docs/CORPUS.md, "Recording").
    startTime = performance.now();
    recorder.start(CHUNK_MS);
  };

  start();
  return {
    id,
    stop() {
      stopping = true;
      if (recorder?.state === "recording") recorder.stop(); // its last chunk comes first
      else finishIfDone();
    },
    /** A new `record` frame replaced this one (the server closed it already). */
    abandon: end,
    /** The page is going away: ended without a report (the server closes it, `kiosk-left`). */
    leave: end,
    status: () => ({ recording: id, state: ended ? "ended" : stopping ? "stopping" : recorder?.state ?? "starting", queued: queue.length, acked, next: nextSeq, startTime }),
  };
}
