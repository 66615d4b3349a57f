// A probe in the kiosk shell (`GET /`) that times a page switch as page-switch.mjs does, with
// epoch times (performance.timeOrigin + performance.now(), ms) so they can be set against
// times taken in another document (the content page tapped, the operator console):
//
//   tapAt   a `pointerdown` in the shown content page (its event.timeStamp on its own clock)
//   clickAt the `click` that follows it, where docent-page.js triggers the act (its timeStamp)
//   clickRun when that click's listeners run (a click made from a touch may be dispatched
//            well after its timeStamp)
//   cmd     the DISPLAY_PAGE frame reaches the shell (docentShell.on('command'))
//   shown   the frame with the new page gets class `shown` (kiosk.js does this at its `load`)
//   painted the first requestAnimationFrame callback after that: the frame that paints it
//   post    a message posted from that callback arrives: after that frame's paint (upper bound)
//
// `installShellProbe` runs in the shell page (Playwright sends its source text), once.

export function installShellProbe() {
  const now = () => performance.timeOrigin + performance.now();
  const probe = { current: null };
  window.__shellProbe = probe;

  // Content frames: time the visitor's touch on the page itself.
  const watchFrame = (frame) => {
    if (frame.__watched) return;
    frame.__watched = true;
    const attach = () => {
      const win = frame.contentWindow;
      if (!win || win.__probed) return;
      win.__probed = true;
      win.addEventListener('pointerdown', (e) => {
        if (probe.current && probe.current.tapAt === undefined) probe.current.tapAt = win.performance.timeOrigin + e.timeStamp;
      }, { capture: true });
      win.addEventListener('click', (e) => {
        if (probe.current && probe.current.clickAt === undefined) {
          probe.current.clickAt = win.performance.timeOrigin + e.timeStamp;
          probe.current.clickRun = now();
        }
      }, { capture: true });
    };
    frame.addEventListener('load', attach);
    try {
      if (frame.contentDocument?.readyState === 'complete') attach();
    } catch {
      // not reachable yet: its load attaches
    }
  };
  for (const frame of document.querySelectorAll('iframe')) watchFrame(frame);

  window.docentShell.on('command', (frame) => {
    const run = probe.current;
    if (run && frame.verb === 'DISPLAY_PAGE' && frame.arg === run.page && run.cmd === undefined) run.cmd = now();
  });
  const channel = new MessageChannel();
  channel.port1.onmessage = () => {
    const run = probe.current;
    if (run && run.post === undefined && run.painted !== undefined) {
      run.post = now();
      run.resolve?.();
    }
  };
  const check = (frame) => {
    const run = probe.current;
    if (!run || run.shown !== undefined) return;
    if (!frame.classList.contains('shown') || !frame.src.endsWith(`/pages/${run.page}`)) return;
    run.shown = now();
    requestAnimationFrame(() => {
      run.painted = now();
      channel.port2.postMessage(null);
    });
  };
  new MutationObserver((records) => {
    for (const record of records) {
      if (record.target.tagName === 'IFRAME') watchFrame(record.target);
      check(record.target);
    }
  }).observe(document.body, { subtree: true, attributes: true, attributeFilter: ['class', 'src'] });

  /** Starts timing a switch to `page` (call before the tap or key). */
  probe.arm = (page) => {
    probe.current = { page };
  };
  /** Resolves with the times once the page is painted, or rejects after `deadlineMs`. */
  probe.result = (deadlineMs) =>
    new Promise((resolve, reject) => {
      const run = probe.current;
      const finish = () => {
        clearTimeout(timer);
        probe.current = null;
        const { tapAt, clickAt, clickRun, cmd, shown, painted, post } = run;
        resolve({ tapAt, clickAt, clickRun, cmd, shown, painted, post });
      };
      const timer = setTimeout(() => {
        probe.current = null;
        reject(new Error(`${run.page} was not shown within ${deadlineMs} ms (${JSON.stringify(run)})`));
      }, deadlineMs);
      if (run.post !== undefined) finish();
      else run.resolve = finish;
    });
}
