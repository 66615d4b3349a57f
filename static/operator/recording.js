// recording.js: what each kiosk's recording is doing (docs/CORPUS.md, "Recording"): a status
// line (role=status) next to the session ("recording media/audio-1.webm on kiosk #3", "not
// recording") and, the moment a kiosk reports a failure (no permission, no microphone, the
// recorder or the uploads failed), an alert (role=alert) saying what to do. Follows the
// `recording.*`, `client.connected`/`client.left` events, after the /api/state snapshot's
// `recording`. Nothing is shown as recording that the kiosk has not reported started.

const ADVICE = {
  "permission-denied": "The kiosk's browser refused the microphone or camera. Allow them for this site in the kiosk browser (or start it with the kiosk launcher's flags), then start a new session.",
  "no-device": "The kiosk has no working microphone or camera (unplugged, or used by another program). Plug it in or free it, then start a new session.",
  unsupported: "The kiosk's browser cannot record WebM. Use Chromium on the kiosk.",
  "recorder-error": "The kiosk's recorder stopped with an error. Start a new session to record again.",
  "upload-failed": "The kiosk could not upload its recording for a while: check its network. What was uploaded is kept; start a new session to record again.",
  "queue-full": "The kiosk's recording could not be uploaded fast enough and was stopped. Check its network, then start a new session.",
  "disk-error": "The server could not write the recording. Check the corpus folder's disk, then start a new session.",
  "limit-reached": "The recording reached its limit (corpus: record_limits in docent.yaml) and was stopped; what was recorded is kept. Start a new session to record again, or raise the limit.",
  "disk-full": "The corpus folder's disk is down to the space kept free for the event log, so recording stopped; the robot goes on. Free space on the disk (or export and purge old sessions), then start a new session.",
};

/**
 * @param {{status: HTMLElement, alert: HTMLElement}} elements
 */
export function createRecording({ status, alert }) {
  const kiosks = new Map(); // client -> {state, recording, file, code, message}

  function render() {
    const recording = [...kiosks].filter(([, k]) => k.state === "recording");
    const failed = [...kiosks].filter(([, k]) => k.state === "failed");
    status.dataset.state = failed.length ? "failed" : recording.length ? "recording" : "off";
    status.textContent = recording.length
      ? `● recording ${recording.map(([client, k]) => `${k.file ?? ""} (kiosk #${client})`).join(", ")}`
      : failed.length ? "recording failed" : "not recording";
    alert.hidden = failed.length === 0;
    alert.textContent = failed
      .map(([client, k]) => `Recording failed on kiosk #${client} (${k.code}): ${k.message}. ${ADVICE[k.code] ?? "Start a new session to record again."}`)
      .join(" ");
  }

  return {
    /** A new connection: forget what the old one told. */
    welcome() {
      kiosks.clear();
      render();
    },
    /** /api/state's `recording`, older than any event since. */
    snapshot(view) {
      for (const k of view?.kiosks ?? []) {
        if (!kiosks.has(k.client)) kiosks.set(k.client, { ...k, state: k.state === "starting" ? "off" : k.state });
      }
      render();
    },
    event(e) {
      if (e.type === "client.connected" && e.role === "kiosk") kiosks.set(e.client, { state: "off" });
      else if (e.type === "client.left" && e.role === "kiosk") kiosks.delete(e.client);
      else if (e.type === "recording.started") kiosks.set(e.client, { state: "recording", recording: e.recording, file: e.file });
      else if (e.type === "recording.failed" && e.client) {
        kiosks.set(e.client, { state: "failed", recording: e.recording, code: e.code, message: e.message });
      } else if (e.type === "recording.failed") {
        alert.hidden = false;
        alert.textContent = `Recording problem (${e.code}): ${e.message}`;
        return;
      } else if (e.type === "recording.stopped") {
        for (const [client, k] of kiosks) {
          if (k.recording === e.recording && k.state === "recording") kiosks.set(client, { state: "off" });
        }
      } else return;
      render();
    },
  };
}
