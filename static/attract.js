// attract.js: the kiosk's attract loop. After the bundle's idle time without a touch the kiosk
// shows its attract pages in turn (each for `every_ms`) and/or triggers its attract act; the
// loop as Docent parsed it (`kiosk: attract:` or the schedule range's) comes from the shell.
// While it runs, a transparent shield lies over the page: the first touch ends the loop and
// takes the kiosk home, and never reaches whatever was under the finger. The start and end are
// reported to Docent (an `attract` frame), which logs them and shows them to the operators;
// reports made while the server is away are sent on reconnection, in order.

const DEFAULT_EVERY_MS = 10_000;
const UNSENT_LIMIT = 16;
// After the finger lifts, the shield stays long enough to swallow the click that follows.
const CLICK_GRACE_MS = 600;

/**
 * @param {{show: (page: string) => void, trigger: (label: string) => void,
 *   send: (frame: object) => boolean, onTouchEnd: () => void}} shell
 */
export function createAttract(shell) {
  let loop = null; // the loop running, or null
  let timer = null;
  let next = 0;
  const unsent = [];
  const shield = document.createElement("div");
  shield.id = "docent-attract";
  shield.setAttribute("aria-hidden", "true");
  shield.style.cssText = "position:fixed;inset:0;z-index:2147483000;background:transparent;touch-action:none";
  const swallow = (event) => {
    event.preventDefault();
    event.stopPropagation();
  };
  shield.addEventListener("pointerdown", (event) => {
    swallow(event);
    if (loop) stop("touch");
    shell.onTouchEnd();
  });
  for (const type of ["pointerup", "pointercancel"]) {
    shield.addEventListener(type, (event) => {
      swallow(event);
      if (!loop) setTimeout(() => loop || shield.remove(), CLICK_GRACE_MS);
    });
  }
  shield.addEventListener("click", (event) => {
    swallow(event);
    if (!loop) shield.remove();
  });
  // The shield is the target of the whole touch, so nothing reaches the page; its click (which
  // a cancelled touchend would suppress, keeping the shield up) takes it away.
  for (const type of ["mousedown", "mouseup", "contextmenu"]) shield.addEventListener(type, swallow);

  function report(frame) {
    unsent.push(frame);
    flush();
  }
  function flush() {
    while (unsent.length && shell.send(unsent[0])) unsent.shift();
    if (unsent.length > UNSENT_LIMIT) unsent.splice(1, unsent.length - UNSENT_LIMIT);
  }

  function cycle() {
    const pages = loop.pages ?? [];
    if (pages.length) {
      shell.show(pages[next % pages.length]);
      next += 1;
      if (pages.length > 1) timer = setTimeout(cycle, loop.every_ms ?? DEFAULT_EVERY_MS);
      return;
    }
    // Only an act: triggered at the start and, with `every`, again and again.
    if (loop.every_ms) timer = setTimeout(() => (shell.trigger(loop.act), cycle()), loop.every_ms);
  }

  /** Starts `attractLoop` ({pages, every_ms, act}); nothing when one runs. */
  function start(attractLoop) {
    if (loop || !attractLoop) return;
    loop = attractLoop;
    next = 0;
    document.body.append(shield);
    document.body.dataset.docentAttract = "";
    report({ type: "attract", state: "started" });
    if (loop.act) shell.trigger(loop.act);
    cycle();
  }

  /** Ends the loop, saying why: `touch`, `robot` (a page Docent showed) or `schedule`. */
  function stop(by) {
    if (!loop) return;
    loop = null;
    clearTimeout(timer);
    delete document.body.dataset.docentAttract;
    if (by !== "touch") shield.remove(); // a touch's shield stays until the finger lifts
    report({ type: "attract", state: "ended", by });
  }

  return { start, stop, flush, running: () => loop !== null };
}
