// recording.js: what each kiosk's recording is doing (docs/CORPUS.md, "Recording"): a status
// line (role=status) next to the session ("recording media/audio-1.webm on kiosk #3", "not
// recording") and, while a kiosk's recording is failing (no permission, no microphone, the
// recorder or the uploads failed), one alert per kiosk saying what to do, updated in place.
// An alarm is about something current: it clears itself when its cause ends (that kiosk
// records again, it leaves, the session ends or the next one starts). What happened before is
// the history's (history.js): the events replayed after `welcome` are the past, and what is
// still wrong when this console connects is what /api/state's `recording` says (the server
// decides that, not this file). Nothing is shown as recording that the kiosk has not reported
// started.

import { h } from "./dom.js";

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

/** The alarm's key for a failure no kiosk reported (the server's, `client` 0). */
const SERVER = "server";

/**
 * @param {{status: HTMLElement, alert: HTMLElement}} elements `alert`: the container of the
 *        alarms (role=alert), one `<p data-client>` per kiosk
 */
export function createRecording({ status, alert }) {
  const kiosks = new Map(); // client -> {state, recording, file, code, message, times}
  let serverProblem = null; // {code, message}: until the next session starts
  let live = false; // events before this console's own client.connected are replayed history
  const told = new Set(); // kiosks a live event told about since `welcome`: newer than the snapshot

  function render() {
    const recording = [...kiosks].filter(([, k]) => k.state === "recording");
    const failed = [...kiosks].filter(([, k]) => k.state === "failed");
    status.dataset.state = failed.length || serverProblem ? "failed" : recording.length ? "recording" : "off";
    status.textContent = recording.length
      ? `● recording ${recording.map(([client, k]) => `${k.file ?? ""} (kiosk #${client})`).join(", ")}`
      : failed.length || serverProblem ? "recording failed" : "not recording";
    const alarms = new Map(failed.map(([client, k]) => [String(client), alarmText(client, k)]));
    if (serverProblem) alarms.set(SERVER, `Recording problem (${serverProblem.code}): ${serverProblem.message}`);
    // In place: an alarm that stays keeps its element; one whose cause ended goes.
    for (const p of [...alert.children]) if (!alarms.has(p.dataset.client)) p.remove();
    for (const [key, text] of alarms) {
      const p = alert.querySelector(`p[data-client="${key}"]`) ?? alert.appendChild(h("p", { class: "recording-problem", dataset: { client: key } }));
      if (p.textContent !== text) p.textContent = text;
    }
    alert.hidden = alarms.size === 0;
  }

  const alarmText = (client, k) => {
    const again = k.times > 1 ? ` (${k.times} times)` : "";
    return `Recording failed on kiosk #${client}${again} (${k.code}): ${k.message}. ${ADVICE[k.code] ?? "Start a new session to record again."}`;
  };

  /** A session started or ended: the failures were about the one before. */
  function forgetFailures() {
    for (const [client, k] of kiosks) if (k.state === "failed") kiosks.set(client, { state: "off" });
    serverProblem = null;
  }

  return {
    /** A new connection: forget what the old one told; what follows is replayed history. */
    welcome() {
      kiosks.clear();
      told.clear();
      serverProblem = null;
      live = false;
      render();
    },
    /** This console's own `client.connected`: the events from here on are live. */
    live() {
      live = true;
    },
    /** /api/state's `recording`: what is current, except what a live event told since. */
    snapshot(view) {
      const current = new Set((view?.kiosks ?? []).map((k) => k.client));
      for (const client of kiosks.keys()) if (!current.has(client) && !told.has(client)) kiosks.delete(client);
      for (const k of view?.kiosks ?? []) {
        if (told.has(k.client)) continue;
        kiosks.set(k.client, { ...k, state: k.state === "starting" ? "off" : k.state, times: 1 });
      }
      render();
    },
    event(e) {
      if (!live) return; // the past: the history shows it
      if (e.type === "client.connected" && e.role === "kiosk") kiosks.set(e.client, { state: "off" });
      else if (e.type === "client.left" && e.role === "kiosk") kiosks.delete(e.client);
      else if (e.type === "recording.started") kiosks.set(e.client, { state: "recording", recording: e.recording, file: e.file });
      else if (e.type === "recording.failed" && e.client) {
        const before = kiosks.get(e.client);
        const times = before?.state === "failed" ? (before.times ?? 1) + 1 : 1;
        kiosks.set(e.client, { state: "failed", recording: e.recording, code: e.code, message: e.message, times });
      } else if (e.type === "recording.failed") {
        serverProblem = { code: e.code, message: e.message };
      } else if (e.type === "recording.stopped") {
        for (const [client, k] of kiosks) {
          if (k.recording === e.recording && k.state === "recording") kiosks.set(client, { state: "off" });
        }
      } else if (e.type === "session.started" || e.type === "session.ended") {
        forgetFailures();
        for (const client of kiosks.keys()) told.add(client);
      } else return;
      if (e.client) told.add(e.client);
      render();
    },
  };
}
