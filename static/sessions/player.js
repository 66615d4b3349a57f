// player.js: the session clock the page plays back on. The clock itself is the master: it runs
// from the playhead at the chosen speed (0.5× to 4×) against performance.now(), so a session
// without recordings plays the same as one with them. Each recording (`<audio>`/`<video>`)
// follows it: placed by its `start_us` on the session clock, paused outside its own span, given
// the clock's speed, and moved when it drifts more than DRIFT_S from where the clock says it
// must be. A recording that refuses to play is reported through `onProblem`, never ignored.

/** How far a recording may drift from the clock before it is moved, in seconds. */
const DRIFT_S = 0.12;

/**
 * @param {{lengthUs: number, media: {el: HTMLMediaElement, startUs: number}[],
 *          onTick: (positionUs: number, playing: boolean) => void,
 *          onProblem: (message: string) => void}} options
 */
export function createPlayer({ lengthUs, media, onTick, onProblem }) {
  let playing = false;
  let rate = 1;
  let anchorUs = 0; // the clock's position at `anchorWall`
  let anchorWall = performance.now();
  let frame = 0;

  function position() {
    if (!playing) return anchorUs;
    const us = anchorUs + (performance.now() - anchorWall) * 1000 * rate;
    return Math.min(lengthUs, Math.max(0, us));
  }

  function reanchor(us) {
    anchorUs = Math.min(lengthUs, Math.max(0, us));
    anchorWall = performance.now();
  }

  function follow(us) {
    for (const { el, startUs } of media) {
      const local = (us - startUs) / 1e6;
      const within = local >= 0 && (!Number.isFinite(el.duration) || local <= el.duration);
      if (!within) {
        if (!el.paused) el.pause();
        continue;
      }
      if (el.playbackRate !== rate) el.playbackRate = rate;
      if (Math.abs(el.currentTime - local) > DRIFT_S) el.currentTime = local;
      if (playing && el.paused) {
        el.play().catch((error) => onProblem(`A recording does not play (${el.dataset.file}): ${error.message}`));
      } else if (!playing && !el.paused) {
        el.pause();
      }
    }
  }

  function tick() {
    frame = 0;
    const us = position();
    if (playing && us >= lengthUs) {
      playing = false;
      reanchor(lengthUs);
    }
    follow(us);
    onTick(us, playing);
    if (playing) frame = requestAnimationFrame(tick);
  }

  function redraw() {
    if (frame) cancelAnimationFrame(frame);
    tick();
  }

  for (const { el } of media) {
    el.addEventListener("error", () => onProblem(`A recording cannot be loaded (${el.dataset.file}): ${el.error?.message || "unreadable"}`));
  }

  return {
    position,
    playing: () => playing,
    rate: () => rate,
    play() {
      if (playing) return;
      if (position() >= lengthUs) reanchor(0);
      else reanchor(position());
      playing = true;
      redraw();
    },
    pause() {
      if (!playing) return;
      reanchor(position());
      playing = false;
      redraw();
    },
    toggle() {
      if (playing) this.pause();
      else this.play();
    },
    /** Moves the playhead to `us` (clamped to the session). */
    seek(us) {
      reanchor(us);
      redraw();
    },
    /** Plays at `r` times the session's own speed. */
    setRate(r) {
      reanchor(position());
      rate = r;
      redraw();
    },
    stop() {
      playing = false;
      if (frame) cancelAnimationFrame(frame);
      for (const { el } of media) el.pause();
    },
  };
}
