// projector.js: the projector shell. Black while nothing is projected; a PROJECT command shows
// /media/<file> full screen: an image, or a video played with its sound. When a video ends the
// screen goes black again, or holds the last frame (`projector: after_video: hold`).
// A HIGHLIGHT command hides any image or video and lights its areas in white on black, each
// `left top width height` in fractions of the screen, `ellipse` for an oval, several areas
// separated by `;`; the server sends them parsed (`args.areas`), as it sends whether a PROJECT
// file is a picture or a video (`args.kind`). HIGHLIGHT alone, or a PROJECT, clears them.
// The soft edge is `projector: highlight_edge` (a fraction of the width), as a blur.
//
// Every command is reported with its id, and only what happened (docs/PROTOCOL.md): `done`
// once a picture is decoded and painted, or highlights painted; for a video `started` when it
// plays and `done` (with `held` when its last frame stays) when it ends; `failed` with the
// browser's own reason when it cannot be shown. Ids belong to one connection: after a
// reconnect the server has already settled them, so they are dropped. The welcome and state
// frames never start a film: a film plays only from its command, and the server's state never
// names one that is over (a held film's last frame is shown again, silent).
//
// Captions: with `captions: projector: true` Docent sends `caption` frames here too, and what
// the robot says is shown at the foot of the wall while it is said (`.docent-caption`).
// While Docent is away nothing is shown about it: the wall keeps its last picture (a picture
// is part of the exhibit, and a wall going dark mid-sentence alarms more than one that holds
// still); the welcome after the return shows the server's state again.

import { clientName } from "./client-name.js";
import { encodePath, keepConnected } from "./socket.js";

const config = document.body.dataset;
const mediaPath = config.media || "/media/";
const holdAfterVideo = config.afterVideo === "hold";
const stage = document.getElementById("docent-stage");
const edge = Number.parseFloat(config.highlightEdge);
stage.style.setProperty("--highlight-edge", Number.isFinite(edge) ? String(edge) : "0.02");

let projected = null; // the file on show or loading; null is black
let highlighted = null; // the HIGHLIGHT argument on show; null is none
let connection = 0; // counts welcomes: a command id is answered only on its own connection
let link = null; // the socket, set once connected

/** A reporter for command `id` (null: nothing to report), answering at most once. */
function reporter(id) {
  const from = connection;
  let settled = false;
  const send = (frame) => {
    if (id == null || from !== connection || !link) return;
    link.send({ ...frame, id });
  };
  return {
    started: () => !settled && send({ type: "started" }),
    done: (extra = {}) => {
      if (settled) return;
      settled = true;
      send({ type: "done", ...extra });
    },
    failed: (reason) => {
      if (settled) return;
      settled = true;
      send({ type: "failed", reason });
    },
  };
}

/** Runs `then` once what is on the stage now has been painted. */
function afterPaint(then) {
  requestAnimationFrame(() => requestAnimationFrame(then));
}

/** Replaces what is on the stage by `element` once it is ready to be seen; false if overtaken. */
function reveal(element, file) {
  if (projected !== file || !element.isConnected) {
    element.remove();
    return false;
  }
  element.classList.remove("loading");
  for (const other of [...stage.children]) {
    if (other !== element) other.remove();
  }
  return true;
}

function black() {
  projected = null;
  stage.replaceChildren();
}

/**
 * Why `src` could not be loaded, asking the server (a browser's media errors do not tell a
 * missing file from a broken one); null when the file itself is there. A file the server is
 * still converting, or could not convert, is answered with the server's own words.
 */
async function whyNotLoaded(src, file) {
  try {
    const res = await fetch(src, { cache: "no-store", headers: { Range: "bytes=0-0" } });
    if (res.ok) return null;
    const said = await res.json().then((body) => body?.error, () => null);
    if (typeof said === "string" && said) return said;
    if (res.status === 404) return `the projector cannot find ${file} (404 Not Found)`;
    return `the projector cannot load ${file} (HTTP ${res.status})`;
  } catch (error) {
    return `the projector cannot load ${file}: ${error}`;
  }
}

/**
 * Lights `areas` (parsed by the server: `{left, top, width, height, shape}` fractions) on
 * black, hiding any image or video; `arg` is the command as written; null or "" clears.
 */
function highlight(arg, areas, report = reporter(null)) {
  projected = null;
  highlighted = arg || null;
  stage.replaceChildren(
    ...(areas ?? []).map(({ left, top, width, height, shape }) => {
      const area = document.createElement("div");
      area.className = shape === "ellipse" ? "docent-highlight ellipse" : "docent-highlight";
      Object.assign(area.style, {
        left: `${left * 100}%`,
        top: `${top * 100}%`,
        width: `${width * 100}%`,
        height: `${height * 100}%`,
      });
      return area;
    }),
  );
  afterPaint(() => report.done());
}

/** Shows the picture `file`; reports it once decoded and painted. */
function showPicture(file, report) {
  const src = mediaPath + encodePath(file);
  const image = new Image();
  image.className = "docent-media loading";
  image.alt = "";
  stage.append(image);
  image.src = src;
  image
    .decode()
    .then(() => {
      if (reveal(image, file)) afterPaint(() => report.done());
    })
    .catch(async () => {
      console.error(`docent: cannot show ${src}`);
      image.remove();
      const reason = (await whyNotLoaded(src, file)) ?? `the projector cannot decode ${file} as a picture`;
      if (projected === file) black();
      report.failed(reason);
    });
}

/**
 * Plays the video `file` from its command (`report` answers it), or, with `held`, shows its
 * last frame silently without playing (a welcome after a film that ended on hold).
 */
function playFilm(file, report, { held = false } = {}) {
  const src = mediaPath + encodePath(file);
  const video = document.createElement("video");
  video.className = "docent-media loading";
  video.playsInline = true;
  const fail = (reason) => {
    console.error(`docent: cannot play ${src}: ${reason}`);
    if (projected === file && video.isConnected) black();
    report.failed(reason);
  };
  video.addEventListener("error", async () => {
    const error = video.error;
    const detail = error?.message || `media error ${error?.code ?? "unknown"}`;
    const missing = error?.code === MediaError.MEDIA_ERR_SRC_NOT_SUPPORTED ? await whyNotLoaded(src, file) : null;
    fail(missing ?? `the projector cannot play ${file}: ${detail}`);
  });
  stage.append(video);
  if (held) {
    video.muted = true;
    video.preload = "auto";
    video.addEventListener("loadedmetadata", () => (video.currentTime = video.duration), { once: true });
    video.addEventListener("seeked", () => reveal(video, file), { once: true });
    video.src = src;
    return;
  }
  video.autoplay = true;
  video.addEventListener("loadeddata", () => reveal(video, file), { once: true });
  video.addEventListener("playing", () => report.started(), { once: true });
  video.addEventListener("ended", () => {
    if (projected !== file || !video.isConnected) return;
    report.done(holdAfterVideo ? { held: true } : {});
    if (!holdAfterVideo) black();
  });
  video.src = src;
  video.play().catch((error) => {
    if (video.error != null || !video.isConnected) return; // the error event reports it
    // Without the kiosk launcher's autoplay flag, a browser only plays muted videos.
    console.warn("docent: the browser refused to play with sound; playing muted", error);
    video.muted = true;
    video.play().catch((e) => {
      if (video.error == null) fail(`the projector cannot play ${file}: ${e}`);
    });
  });
}

/** Projects `file` as the server says it is (`kind`: "image" or "video"); null is black. */
function project(file, kind, report = reporter(null)) {
  highlighted = null;
  if (!file) {
    black();
    return report.done();
  }
  stage.querySelectorAll(".docent-highlight").forEach((area) => area.remove());
  stage.querySelectorAll("video").forEach((video) => video.pause()); // replaced: it ends here
  projected = file;
  if (kind === "image") return showPicture(file, report);
  if (kind === "video") return playFilm(file, report);
  black();
  report.failed(`the projector shows pictures and videos only, not ${file}`);
}

/** A welcome or state frame: shows the server's display state, never starting a film. */
function showState(display = {}) {
  if (display.highlight) {
    if (display.highlight !== highlighted || projected !== null) highlight(display.highlight, display.highlight_areas);
    return;
  }
  const file = display.projector ?? null;
  if (file === projected && file !== null) return; // on show already (a film plays on)
  const state = display.projector_state;
  if (!file || (display.projector_kind === "video" && state !== "held")) return black();
  highlighted = null;
  projected = file;
  stage.replaceChildren();
  if (display.projector_kind === "video") playFilm(file, reporter(null), { held: true });
  else showPicture(file, reporter(null));
}

/** Shows `text` as the wall's caption, or removes it (null). */
function caption(text) {
  let element = document.getElementById("docent-caption");
  if (!text) {
    element?.remove();
    return;
  }
  if (!element) {
    element = document.createElement("div");
    element.id = "docent-caption";
    element.className = "docent-caption";
    element.setAttribute("aria-live", "polite");
    document.body.append(element);
  }
  element.textContent = text;
}

link = keepConnected({
  path: config.ws || "/ws",
  role: "projector",
  name: clientName("projector"),
  onFrame: (frame) => {
    if (frame.type === "welcome") {
      connection += 1;
      caption(null); // the caption in force, if any, follows the welcome
    }
    if (frame.type === "welcome" || frame.type === "state") {
      showState(frame.state?.display);
    } else if (frame.type === "command" && frame.verb === "PROJECT") {
      project(frame.args.file, frame.args.kind, reporter(frame.id ?? null));
    } else if (frame.type === "command" && frame.verb === "HIGHLIGHT") {
      highlight(frame.arg ?? null, frame.args.areas, reporter(frame.id ?? null));
    } else if (frame.type === "caption") {
      caption(typeof frame.text === "string" ? frame.text : null);
    } else if (frame.type === "cancel") {
      black(); // a stop: the film or picture on its way ends here
      highlighted = null;
    }
  },
});

for (const type of ["contextmenu", "selectstart", "dragstart"]) {
  addEventListener(type, (event) => event.preventDefault(), { capture: true });
}
