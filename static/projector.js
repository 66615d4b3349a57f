// projector.js: the projector shell. Black while nothing is projected; a PROJECT command shows
// /media/<file> full screen: an image, or a video played with its sound. When a video ends the
// screen goes black again, or holds the last frame (`projector: after_video: hold`).
// A HIGHLIGHT command hides any image or video and lights its areas in white on black, each
// `left top width height` in fractions of the screen, `ellipse` for an oval, several areas
// separated by `;`; the server sends them parsed (`args.areas`), as it sends whether a PROJECT
// file is a picture or a video (`args.kind`). HIGHLIGHT alone, or a PROJECT, clears them.
// The soft edge is `projector: highlight_edge` (a fraction of the width), as a blur.
// A video projected by a PROJECT command is answered with the command's id: `done` when it
// ends, `failed` on a media error, so that the server's WAIT can follow the film. Ids belong to
// one connection: after a reconnect the server has already settled them, so they are dropped.

import { encodePath, keepConnected } from "./socket.js";

const config = document.body.dataset;
const mediaPath = config.media || "/media/";
const holdAfterVideo = config.afterVideo === "hold";
const stage = document.getElementById("docent-stage");
const edge = Number.parseFloat(config.highlightEdge);
stage.style.setProperty("--highlight-edge", Number.isFinite(edge) ? String(edge) : "0.02");

let projected = null; // the file on show or loading; null is black
let highlighted = null; // the HIGHLIGHT argument on show; null is none
const ended = new Set(); // videos that played to their end (not replayed by a reconnect)
let connection = 0; // counts welcomes: a command id is answered only on its own connection
let link = null; // the socket, set once connected

/** Answers the PROJECT command `id` (from connection `from`), if there is one to answer. */
function answer(id, from, frame) {
  if (id == null || from !== connection || !link) return;
  link.send({ ...frame, id });
}

/** Replaces what is on the stage by `element` once it is ready to be seen. */
function reveal(element, file) {
  if (projected !== file) {
    element.remove();
    return;
  }
  element.classList.remove("loading");
  for (const other of [...stage.children]) {
    if (other !== element) other.remove();
  }
}

function black() {
  stage.replaceChildren();
}

/**
 * Lights `areas` (parsed by the server: `{left, top, width, height, shape}` fractions) on
 * black, hiding any image or video; `arg` is the command as written, which says whether the
 * same areas are on show already; null or "" clears.
 */
function highlight(arg, areas, { again = true } = {}) {
  const wanted = arg || null;
  if (!again && wanted === highlighted && projected === null) return;
  projected = null;
  highlighted = wanted;
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
}

/** Shows `file` as the server says it is (`kind`: "image" or "video"); null is black. */
function project(file, kind, { again = true, id = null } = {}) {
  if (highlighted !== null) {
    highlighted = null;
    for (const area of stage.querySelectorAll(".docent-highlight")) area.remove();
  }
  if (!again && file === projected) return;
  if (!again && file && ended.has(file)) return; // a welcome after a reconnect: it is over
  projected = file ?? null;
  if (!file) return black();
  ended.delete(file);
  const src = mediaPath + encodePath(file);
  if (kind === "image") {
    const image = new Image();
    image.className = "docent-media loading";
    image.alt = "";
    image.onload = () => reveal(image, file);
    image.onerror = () => console.error(`docent: cannot show ${src}`);
    stage.append(image);
    image.src = src;
  } else if (kind === "video") {
    const video = document.createElement("video");
    const from = connection;
    let answered = false;
    const settle = (frame) => {
      if (answered) return;
      answered = true;
      answer(id, from, frame);
    };
    const fail = (reason) => settle({ type: "failed", reason });
    video.className = "docent-media loading";
    video.autoplay = true;
    video.playsInline = true;
    video.addEventListener("loadeddata", () => reveal(video, file), { once: true });
    video.addEventListener("error", () => {
      console.error(`docent: cannot play ${src}`);
      fail(`the projector cannot play ${file} (media error ${video.error?.code ?? "unknown"})`);
    });
    video.addEventListener("ended", () => {
      settle({ type: "done" });
      ended.add(file);
      if (!holdAfterVideo && projected === file) {
        projected = null;
        black();
      }
    });
    stage.append(video);
    video.src = src;
    video.play().catch((error) => {
      // Without the kiosk launcher's autoplay flag, a browser only plays muted videos.
      console.warn("docent: the browser refused to play with sound; playing muted", error);
      video.muted = true;
      video.play().catch((e) => {
        console.error(`docent: cannot play ${src}`, e);
        if (video.error == null) fail(`the projector cannot play ${file}: ${e}`);
      });
    });
  } else {
    console.warn(`docent: the projector shows images and videos only, not ${file}`);
    black();
  }
}

link = keepConnected({
  path: config.ws || "/ws",
  role: "projector",
  name: "projector",
  onFrame: (frame) => {
    if (frame.type === "welcome") connection += 1;
    if (frame.type === "welcome" || frame.type === "state") {
      const display = frame.state?.display ?? {};
      if (display.highlight) {
        highlight(display.highlight, display.highlight_areas, { again: false });
      } else {
        project(display.projector ?? null, display.projector_kind, { again: false });
      }
    } else if (frame.type === "command" && frame.verb === "PROJECT") {
      project(frame.args.file, frame.args.kind, { id: frame.id ?? null });
    } else if (frame.type === "command" && frame.verb === "HIGHLIGHT") {
      highlight(frame.arg ?? null, frame.args.areas);
    }
  },
});

for (const type of ["contextmenu", "selectstart", "dragstart"]) {
  addEventListener(type, (event) => event.preventDefault(), { capture: true });
}
