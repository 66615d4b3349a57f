//! The built-in `HIGHLIGHT` verb end to end: projector clients get the command, the display
//! state keeps the areas for projectors that connect later, a `PROJECT` or an empty
//! `HIGHLIGHT` clears them, and every change is a `display.changed` event.

use crate::common;

use common::{TempBundle, TestServer, WsClient};
use serde_json::{Value, json};

const ACTS: &str = "\
- Label: SECTION_1
  Cmds:
    - HIGHLIGHT 0.10 0.20 0.35 0.25; 0.6 0.6 0.3 0.3 ellipse
- Label: POSTER
  Cmds:
    - PROJECT poster.png
- Label: DARK
  Cmds:
    - HIGHLIGHT
- Label: HOME
  Cmds:
    - DISPLAY_PAGE index.html
";

fn poster_bundle() -> TempBundle {
    TempBundle::new(ACTS).with_file("media/poster.png", "not really a png")
}

async fn projector(server: &TestServer) -> WsClient {
    server
        .client(json!({"type": "hello", "role": "projector"}))
        .await
}

/// The next `display.changed` event seen by the operator.
async fn changed(op: &mut WsClient) -> Value {
    op.event("display.changed").await
}

#[tokio::test]
async fn projectors_get_highlight_commands_and_late_ones_the_current_areas() {
    let bundle = poster_bundle();
    let server = TestServer::start(bundle.path()).await;
    let mut op = server.operator().await;
    let mut early = projector(&server).await;
    let display = &early.welcome["state"]["display"];
    assert_eq!(display["highlight"], Value::Null, "{display}");
    assert_eq!(display["projector"], Value::Null, "{display}");

    server.trigger("SECTION_1", json!({})).await;
    let command = early.recv_type("command").await;
    assert_eq!(
        (command["verb"].as_str(), command["arg"].as_str()),
        (
            Some("HIGHLIGHT"),
            Some("0.10 0.20 0.35 0.25; 0.6 0.6 0.3 0.3 ellipse")
        )
    );
    // Parsed once, by the server: the projector draws these numbers as they are.
    let areas = json!([
        {"left": 0.10, "top": 0.20, "width": 0.35, "height": 0.25, "shape": "rect"},
        {"left": 0.6, "top": 0.6, "width": 0.3, "height": 0.3, "shape": "ellipse"}
    ]);
    assert_eq!(command["args"], json!({ "areas": areas }), "{command}");
    let event = changed(&mut op).await;
    assert_eq!(
        event["highlight"],
        "0.10 0.20 0.35 0.25; 0.6 0.6 0.3 0.3 ellipse"
    );
    assert_eq!(event["projector"], Value::Null);
    assert_eq!(event["page"], "index.html");

    let late = projector(&server).await;
    let display = &late.welcome["state"]["display"];
    assert_eq!(
        display["highlight"], "0.10 0.20 0.35 0.25; 0.6 0.6 0.3 0.3 ellipse",
        "{display}"
    );
    assert_eq!(display["projector"], Value::Null, "{display}");
    assert_eq!(display["highlight_areas"], areas, "{display}");
    let (status, state) = server.get("/api/state").await;
    assert_eq!(status, 200, "{state}");
    assert_eq!(
        state["display"]["highlight"],
        "0.10 0.20 0.35 0.25; 0.6 0.6 0.3 0.3 ellipse"
    );

    server.trigger("DARK", json!({})).await;
    let command = early.recv_type("command").await;
    assert_eq!(command["verb"], "HIGHLIGHT");
    assert_eq!(command["arg"], Value::Null, "{command}");
    assert_eq!(command["args"], json!({ "areas": [] }), "{command}");
    assert_eq!(changed(&mut op).await["highlight"], Value::Null);
    let after = projector(&server).await;
    let display = &after.welcome["state"]["display"];
    assert_eq!(display["highlight"], Value::Null, "{display}");
    assert_eq!(display["projector"], Value::Null, "{display}");

    drop(early);
    let corpus = server.stop().await;
    let mut highlights: Vec<&Value> = corpus
        .iter()
        .filter(|e| e["type"] == "display.changed")
        .map(|e| &e["highlight"])
        .collect();
    // The projector's reports (and its leaving) change its state, not the areas.
    highlights.dedup();
    assert_eq!(
        highlights,
        [
            &json!("0.10 0.20 0.35 0.25; 0.6 0.6 0.3 0.3 ellipse"),
            &Value::Null
        ]
    );
}

#[tokio::test]
async fn project_and_highlight_replace_each_other() {
    let bundle = poster_bundle();
    let server = TestServer::start(bundle.path()).await;
    let mut op = server.operator().await;
    let mut projector_client = projector(&server).await;

    server.trigger("POSTER", json!({})).await;
    let project = projector_client.recv_type("command").await;
    assert_eq!(project["verb"], "PROJECT");
    let event = changed(&mut op).await;
    assert_eq!(
        (event["projector"].as_str(), &event["highlight"]),
        (Some("poster.png"), &Value::Null)
    );
    // The projector reports the picture shown, as a real one does: the PROJECT is done, and
    // the HIGHLIGHT that follows replaces a finished picture, not a running command.
    projector_client
        .send(json!({"type": "done", "id": project["id"]}))
        .await;
    op.event_where(|e| e["type"] == "command.done" && e["command"] == project["id"])
        .await;

    server.trigger("SECTION_1", json!({})).await;
    let highlight = projector_client.recv_type("command").await;
    assert_eq!(highlight["verb"], "HIGHLIGHT");
    let event = changed(&mut op).await;
    assert_eq!(event["projector"], Value::Null, "HIGHLIGHT hides the image");
    assert!(event["highlight"].is_string(), "{event}");
    projector_client
        .send(json!({"type": "done", "id": highlight["id"]}))
        .await;
    op.event_where(|e| e["type"] == "command.done" && e["command"] == highlight["id"])
        .await;

    server.trigger("POSTER", json!({})).await;
    let event = changed(&mut op).await;
    assert_eq!(event["projector"], "poster.png");
    assert_eq!(event["highlight"], Value::Null, "PROJECT clears highlights");
    let late = projector(&server).await;
    assert_eq!(late.welcome["state"]["display"]["highlight"], Value::Null);
    assert_eq!(late.welcome["state"]["display"]["projector"], "poster.png");
    server.stop().await;
}

#[tokio::test]
async fn kiosks_do_not_get_highlight_commands() {
    let bundle = poster_bundle();
    let server = TestServer::start(bundle.path()).await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    let mut projector_client = projector(&server).await;
    server.trigger("SECTION_1", json!({})).await;
    server.trigger("POSTER", json!({})).await;
    assert_eq!(
        projector_client.recv_type("command").await["verb"],
        "HIGHLIGHT"
    );
    assert_eq!(
        projector_client.recv_type("command").await["verb"],
        "PROJECT"
    );
    server.trigger("HOME", json!({})).await;
    let first = kiosk.recv_type("command").await;
    assert_eq!(
        first["verb"], "DISPLAY_PAGE",
        "the kiosk skipped no projector command: {first}"
    );
    server.stop().await;
}
