//! `DISPLAY_PAGE` is done only when a touchscreen reports the page shown: with none connected
//! it fails at once (the state keeps the page, so a kiosk that connects shows the tour's page),
//! a `failed` report fails it, a later page replaces it, a kiosk leaving fails what it owed, and
//! a report missing after `adapters: timeout` fails it (paused clock).

use crate::common;

use common::{TempBundle, TestServer, WsClient};
use serde_json::{Value, json};

const ACTS: &str = "\
- Label: MAP
  Cmds: [DISPLAY_PAGE map.html, WAIT, SAY Here is the map]
- Label: HOME
  Cmds: [DISPLAY_PAGE index.html]
";

fn bundle() -> TempBundle {
    TempBundle::new(ACTS)
        .with_file("docent.yaml", "speech: {adapter: log}\n")
        .with_file("pages/map.html", "<!DOCTYPE html><title>map</title>")
}

async fn kiosk(server: &TestServer) -> WsClient {
    server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await
}

fn is(kind: &'static str, command: u64) -> impl Fn(&Value) -> bool {
    move |e| e["type"] == kind && e["command"] == command
}

async fn map(op: &mut WsClient) -> (u64, u64, u64) {
    op.send(json!({"type": "trigger", "label": "MAP"})).await;
    let t = op.recv_type("triggered").await;
    let ids: Vec<u64> = (t["commands"].as_array().expect("commands").iter())
        .map(|c| c["id"].as_u64().expect("id"))
        .collect();
    (ids[0], ids[1], ids[2])
}

#[tokio::test]
async fn with_no_touchscreen_display_page_fails_at_once_but_the_page_is_kept_for_one() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let (page, wait, say) = map(&mut op).await;
    let failed = op.event_where(is("command.failed", page)).await;
    assert_eq!(failed["reason"], "no touchscreen connected", "{failed}");
    let events = op.events_until(is("command.failed", wait)).await;
    assert!(!events.iter().any(is("command.sent", say)), "{events:#?}");
    let late = kiosk(&server).await;
    assert_eq!(late.welcome["state"]["display"]["page"], "map.html");
}

#[tokio::test]
async fn display_page_is_done_when_the_touchscreen_reports_it_shown() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut screen = kiosk(&server).await;
    let (page, wait, say) = map(&mut op).await;
    let command = screen.recv_type("command").await;
    assert_eq!(command["id"], page, "{command}");
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["queues"]["display"]["queued"], 1, "waiting: {state}");
    screen.send(json!({"type": "done", "id": page})).await;
    let events = op.events_until(is("command.sent", say)).await;
    let done = events.iter().position(is("command.done", page));
    let wait_done = events.iter().position(is("command.done", wait));
    assert!(done.is_some() && done < wait_done, "{events:#?}");
}

#[tokio::test]
async fn a_failed_report_a_later_page_or_the_kiosk_leaving_ends_it() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut screen = kiosk(&server).await;

    let (page, _, _) = map(&mut op).await;
    screen.recv_type("command").await;
    let reason = "the touchscreen could not show map.html: it is not available";
    screen
        .send(json!({"type": "failed", "id": page, "reason": reason}))
        .await;
    assert_eq!(
        op.event_where(is("command.failed", page)).await["reason"],
        reason
    );

    let (page, _, _) = map(&mut op).await;
    screen.recv_type("command").await;
    op.send(json!({"type": "trigger", "label": "HOME"})).await;
    let cancelled = op.event_where(is("command.cancelled", page)).await;
    // The touchscreen channel's policy (replace) names what took over.
    assert_eq!(
        cancelled["reason"],
        "replaced by act HOME from the operator"
    );

    let (page, _, _) = map(&mut op).await;
    screen
        .recv_where(|f| f["type"] == "command" && f["id"] == page)
        .await;
    drop(screen);
    let failed = op.event_where(is("command.failed", page)).await;
    assert_eq!(failed["reason"], "the touchscreen disconnected", "{failed}");
}

#[tokio::test(start_paused = true)]
async fn a_touchscreen_that_never_reports_fails_the_page_after_the_timeout() {
    let b = TempBundle::new(ACTS)
        .with_file(
            "docent.yaml",
            "speech: {adapter: log}\nadapters: {timeout: 5s}\n",
        )
        .with_file("pages/map.html", "<!DOCTYPE html><title>map</title>");
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut screen = kiosk(&server).await;
    // Measured from before the trigger: the server's clock starts when it sends, and with the
    // clock paused, time may move on while the command is on its way.
    let asked = tokio::time::Instant::now();
    let (page, wait, say) = map(&mut op).await;
    screen.recv_type("command").await;
    let failed = op.event_where(is("command.failed", page)).await;
    assert!(asked.elapsed() >= std::time::Duration::from_secs(5));
    assert_eq!(
        failed["reason"], "the touchscreen did not report it shown within 5s",
        "{failed}"
    );
    let events = op.events_until(is("command.failed", wait)).await;
    assert!(!events.iter().any(is("command.sent", say)), "{events:#?}");
    // A late report changes nothing.
    screen.send(json!({"type": "done", "id": page})).await;
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["queues"]["display"]["queued"], 0, "{state}");
}
