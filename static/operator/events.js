// events.js: the server's frames, routed to the panels. Events are handed to every panel once:
// after `welcome` the server replays recent history strictly before the live events, all in
// `seq` order, so an event whose `seq` is not above the highest seen is one already handled. The
// GET /api/state snapshot fetched after `welcome` fills in only what no event has told since (a
// fetch for an older connection is dropped). The live events also give this computer's clock
// offset from the server's, by which proposals show their age.

/**
 * @param {{panels: {live: object, clients: object, history: object, proposals: object,
 *          marks: object, map: object, robotLink?: object, kiosks?: object}, context: object, language: object,
 *          camera: object,
 *          operatorName: HTMLElement, name: () => string|null, stopped: (ref: string) => void,
 *          notice: (message: string) => void,
 *          getJson: (path: string, wanted: () => boolean) => Promise<object|null>,
 *          connected: () => boolean}} options `context`: context.js; `language`: language.js;
 *          `camera`: camerapanel.js;
 *          `operatorName`: where this console's name and client id are shown; `stopped`: a
 *          websocket stop was answered; `getJson`: a GET with the credential (api.js)
 * @returns {{onFrame: (frame: object) => void, now: () => number}} `now`: the server's clock
 *          in ms, as far as the live events tell
 */
export function createEvents({ panels, context, language, camera, operatorName, name, stopped, notice, getJson, connected }) {
  const { live, clients, history, proposals, marks, map } = panels;
  let me = null;
  let lastSeq = -Infinity; // the highest event seq handled on this connection
  let welcomes = 0; // connections welcomed so far: a fetch for an older one is dropped
  let streaming = false; // the live stream began (this console's own client.connected arrived)
  let clockOffset = null; // this computer's clock minus the server's, from live events
  const told = { pose: false, waypoint: false, session: false, robotLink: false }; // newer than the snapshot

  function handleEvent(e) {
    if (typeof e?.seq === "number") {
      if (e.seq <= lastSeq) return;
      lastSeq = e.seq;
    }
    if (e.type === "client.connected" && e.client === me) {
      streaming = true;
      panels.recording?.live(); // the replayed history is over: recording alarms are current from here
    }
    const at = Date.parse(e.time ?? "");
    // The smallest (local - server) time of live events: the clocks' offset plus the least delay.
    if (streaming && Number.isFinite(at)) clockOffset = Math.min(clockOffset ?? Infinity, Date.now() - at);
    if (e.type === "pose") told.pose = true;
    else if (e.type === "robot.link") told.robotLink = true;
    else if (e.type === "command.sent" && e.verb === "SET_WAYPOINT") told.waypoint = true;
    else if (e.type === "session.started" || e.type === "session.ended") told.session = true;
    live.event(e);
    clients.event(e);
    history.event(e);
    proposals.event(e);
    marks.event(e);
    panels.recording?.event(e);
    panels.kiosks?.event(e);
    if (e.type === "pose") map.pose(e);
    // The server parsed the waypoint at load: `args` is {x, y, heading}.
    else if (e.type === "command.sent" && e.verb === "SET_WAYPOINT") map.waypoint(e.args ?? null);
    else if (e.type === "context.changed") context.changed(e);
    else if (e.type === "language.changed") language.changed(e);
    else if (e.type === "robot.link") panels.robotLink?.set(e);
  }

  function welcome(frame) {
    me = frame.client;
    welcomes += 1;
    lastSeq = -Infinity; // a new connection replays its history (a new server run restarts seq)
    camera.clientsUnknown();
    streaming = false;
    told.pose = told.waypoint = told.session = told.robotLink = false;
    history.welcome(me);
    proposals.welcome();
    clients.welcome(me);
    panels.recording?.welcome();
    panels.kiosks?.welcome();
    live.reset();
    live.welcome(frame.state);
    map.pose(frame.state?.pose);
    context.set(frame.state?.context);
    language.set(frame.state?.language);
    operatorName.textContent = `${name() || "operator"} #${me}`;
    loadState();
  }

  async function loadState() {
    const welcome = welcomes;
    const state = await getJson("/api/state", () => welcome === welcomes && connected());
    if (welcome !== welcomes) return;
    camera.clientsWhole();
    if (!state) {
      camera.clients(clients.get()); // as far as the events told
      return;
    }
    live.apiState(state);
    language.snapshot(state);
    clients.snapshot(state.clients);
    proposals.snapshot(state.proposals);
    panels.recording?.snapshot(state.recording);
    // Only what no event told since `welcome`: an event is newer than this answer.
    if (!told.session) marks.setSession(state.session ?? null, state.consent ?? null);
    if (!told.pose) map.pose(state.pose);
    if (!told.robotLink) panels.robotLink?.set(state.robot_link ?? null);
    if (!told.waypoint) map.waypoint(state.waypoint);
    document.body.dataset.snapshots = String(Number(document.body.dataset.snapshots ?? 0) + 1);
  }

  function onFrame(frame) {
    switch (frame.type) {
      case "welcome":
        welcome(frame);
        break;
      case "stopped":
        stopped(frame.ref);
        break;
      case "event":
        handleEvent(frame.event);
        break;
      case "signal":
        camera.signal(frame);
        break;
      case "error":
        notice(frame.message ?? frame.code);
        break;
      case "marked":
        if (frame.mark === "session_start") {
          told.session = true;
          marks.setSession(frame.session);
        }
        break;
      default:
        break;
    }
  }

  return { onFrame, now: () => Date.now() - (clockOffset ?? 0) };
}
