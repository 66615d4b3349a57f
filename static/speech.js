// speech.js: browser speech for a kiosk whose bundle says `speech: {adapter: browser}`. The
// shell opens a second websocket as an adapter serving SAY and speaks each command with the
// Web Speech API, one utterance at a time, in order; it answers `started`, then `done` when the
// utterance ends or `failed` with the browser's error (e.g. `synthesis-failed` where the
// browser has no voices). A `cancel` frame silences it and drops what is queued.

import { keepConnected } from "./socket.js";

/** Words per minute at the Web Speech API's rate 1 (a typical default voice). */
const NORMAL_WPM = 170;

/**
 * Starts browser speech. `voice` is a language tag (`en-us`) or a voice name; `wpm` the rate.
 * @param {{path: string, voice: string, wpm: number}} options
 */
export function startBrowserSpeech({ path, voice, wpm }) {
  const synth = window.speechSynthesis;
  const queue = [];
  let speaking = null;

  const pickVoice = () => {
    const voices = synth?.getVoices?.() ?? [];
    const wanted = String(voice || "").toLowerCase();
    return (
      voices.find((v) => v.name.toLowerCase() === wanted) ??
      voices.find((v) => v.lang.toLowerCase() === wanted) ??
      voices.find((v) => v.lang.toLowerCase().startsWith(wanted.split("-")[0])) ??
      null
    );
  };

  const next = () => {
    if (speaking || queue.length === 0) return;
    const command = queue.shift();
    if (!synth) {
      socket.send({ type: "failed", id: command.id, reason: "this browser cannot speak (no Web Speech API)" });
      return next();
    }
    const utterance = new SpeechSynthesisUtterance(command.arg ?? "");
    const chosen = pickVoice();
    if (chosen) utterance.voice = chosen;
    if (voice) utterance.lang = voice;
    utterance.rate = Math.min(10, Math.max(0.1, (Number(wpm) || NORMAL_WPM) / NORMAL_WPM));
    speaking = command.id;
    const finish = (frame) => {
      if (speaking !== command.id) return; // cancelled meanwhile: the server already settled it
      speaking = null;
      socket.send(frame);
      next();
    };
    utterance.onstart = () => socket.send({ type: "started", id: command.id });
    utterance.onend = () => finish({ type: "done", id: command.id });
    utterance.onerror = (event) =>
      finish({ type: "failed", id: command.id, reason: `browser speech failed: ${event.error || "unknown error"}` });
    synth.speak(utterance);
  };

  const socket = keepConnected({
    path,
    role: "adapter",
    name: "kiosk speech",
    hello: { verbs: ["SAY"], events: false },
    onFrame: (frame) => {
      if (frame.type === "command" && frame.verb === "SAY") {
        queue.push(frame);
        next();
      } else if (frame.type === "cancel") {
        queue.length = 0;
        speaking = null;
        synth?.cancel();
      }
    },
    onOnline: (online) => {
      if (!online) {
        // The server fails what a lost connection owed; start clean on the next one.
        queue.length = 0;
        speaking = null;
        synth?.cancel();
      }
    },
  });
}
