// speech.js: browser speech for a kiosk whose bundle says `speech: {adapter: browser}`. The
// shell opens a second websocket as an adapter serving SAY and speaks each command with the
// Web Speech API, one utterance at a time, in order; it answers `started`, then `done` when the
// utterance ends or `failed` with the browser's error (e.g. `synthesis-failed` where the
// browser has no voices). A `cancel` frame silences it and drops what is queued.
// In the author's preview (the kiosk shell loaded as `/?preview`), a browser without a voice
// (headless, or no speech installed) shows each text instead: the SAY runs as long as the text
// would take to say at the configured rate, so acts go on as they would, and the preview says
// that speech is shown as text only (`detectVoice`, also used by preview.js).
// Each SAY is spoken in its language (`args.language`, docs/PROTOCOL.md): `utterance.lang` is
// set to it, with a voice of that language where the browser has one; the configured voice
// speaks the bundle's default language, or any SAY without a language.

import { keepConnected } from "./socket.js";

/** Words per minute at the Web Speech API's rate 1 (a typical default voice). */
const NORMAL_WPM = 170;
/** How long the browser may take to list its voices (they often arrive a moment late). */
const VOICE_WAIT_MS = 1_000;
/** A text shown instead of spoken stays at least this long, so that it can be read. */
const MIN_TEXT_MS = 1_500;

/**
 * Whether this browser can speak: it has the Web Speech API and at least one voice, once
 * `voiceschanged` has fired or `waitMs` have passed.
 * @returns {Promise<boolean>}
 */
export function detectVoice({ waitMs = VOICE_WAIT_MS } = {}) {
  const synth = window.speechSynthesis;
  if (!synth || typeof window.SpeechSynthesisUtterance !== "function") return Promise.resolve(false);
  if ((synth.getVoices?.() ?? []).length > 0) return Promise.resolve(true);
  return new Promise((resolve) => {
    const decide = () => {
      clearTimeout(timer);
      synth.removeEventListener?.("voiceschanged", decide);
      resolve((synth.getVoices?.() ?? []).length > 0);
    };
    const timer = setTimeout(decide, waitMs);
    synth.addEventListener?.("voiceschanged", decide);
  });
}

/**
 * How long a text is shown for when it cannot be spoken: the speaking time the server sent
 * with the command (`speaking_ms`, at the site's rate), and at least MIN_TEXT_MS to read it.
 */
export function shownMs(command) {
  return Math.max(MIN_TEXT_MS, Number(command.speaking_ms) || 0);
}

/** The language (`en`) the configured voice speaks: its tag's, or its browser voice's. */
function configuredLanguage(configured, voices) {
  const named = voices.find((v) => v.name.toLowerCase() === configured);
  return String(named?.lang ?? configured).toLowerCase().split(/[-_]/)[0];
}

/**
 * Starts browser speech. `voice` is a language tag (`en-us`) or a voice name; `wpm` the rate.
 * @param {{path: string, voice: string, wpm: number}} options
 */
export function startBrowserSpeech({ path, voice, wpm }) {
  const synth = window.speechSynthesis;
  const queue = [];
  let speaking = null;
  let textTimer = null;
  // Only the preview falls back to text; a kiosk without a voice fails its SAY commands.
  const preview = new URLSearchParams(location.search).has("preview");
  let hasVoice = preview ? null : true; // null: still finding out
  if (preview) {
    detectVoice().then((found) => {
      hasVoice = found;
      next();
    });
  }

  /** Shows instead of speaking: started now, done after the time saying it would take. */
  const showAsText = (command) => {
    speaking = command.id;
    socket.send({ type: "started", id: command.id });
    textTimer = setTimeout(() => {
      textTimer = null;
      if (speaking !== command.id) return;
      speaking = null;
      socket.send({ type: "done", id: command.id });
      next();
    }, shownMs(command));
  };
  const silence = () => {
    queue.length = 0;
    speaking = null;
    clearTimeout(textTimer);
    textTimer = null;
    synth?.cancel();
  };

  /** A voice for `language` (a tag such as `de`), else the configured one. */
  const pickVoice = (language) => {
    const voices = synth?.getVoices?.() ?? [];
    const configured = String(voice || "").toLowerCase();
    const tag = String(language || "").toLowerCase();
    const speaksConfigured = !tag || configuredLanguage(configured, voices) === tag.split("-")[0];
    const wanted = speaksConfigured ? configured : tag;
    return (
      voices.find((v) => v.name.toLowerCase() === wanted) ??
      voices.find((v) => v.lang.toLowerCase() === wanted) ??
      voices.find((v) => v.lang.toLowerCase().startsWith(wanted.split("-")[0])) ??
      null
    );
  };

  const next = () => {
    if (speaking || queue.length === 0 || hasVoice === null) return;
    const command = queue.shift();
    if (!hasVoice) return showAsText(command);
    if (!synth) {
      socket.send({ type: "failed", id: command.id, reason: "this browser cannot speak (no Web Speech API)" });
      return next();
    }
    const utterance = new SpeechSynthesisUtterance(command.arg ?? "");
    const language = command.args?.language;
    const chosen = pickVoice(language);
    if (chosen) utterance.voice = chosen;
    if (language) utterance.lang = language;
    else if (voice) utterance.lang = voice;
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
        silence();
      }
    },
    onOnline: (online) => {
      if (!online) {
        // The server fails what a lost connection owed; start clean on the next one.
        silence();
      }
    },
  });
}
