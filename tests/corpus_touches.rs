//! A visitor's touch is a `touch` event (page, element, act or link) and starts the session;
//! what a page does by itself (its timers, the idle return home, its scripts) is not a touch
//! and starts nothing. The session's manifest names the content it was recorded with. Read back
//! from the corpus files, as a researcher would.

use crate::common;

use common::{TempBundle, TestServer, json_lines, session_dirs};
use docent::corpus::layout::SESSION_EVENTS;
use docent::corpus::manifest::SessionManifest;
use serde_json::{Value, json};

const ACTS: &str = r#"
- Label: WELCOME
  Text: [Hello!]
- Label: HINT
  Text: [Touch the screen.]
"#;

fn kiosk_bundle() -> TempBundle {
    TempBundle::new(ACTS)
        .with_file("docent.yaml", "speech: {adapter: log}\n")
        .with_file(
            "pages/index.html",
            r#"<html><body><button data-act="WELCOME">Hello</button>
<p data-act="HINT" data-act-after="20s"></p><a href="map.html">Map</a></body></html>"#,
        )
        .with_file("pages/map.html", "<html><body>Map</body></html>")
}

#[tokio::test]
async fn timers_and_the_idle_return_start_nothing_and_a_touch_is_logged_with_its_element() {
    let b = kiosk_bundle();
    // Our own folder: the server's own is removed when it stops.
    let folder = tempfile::tempdir().unwrap();
    let server = TestServer::start_with(b.path(), |o| o.corpus_dir = folder.path().into()).await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    // The page's own doing: a timer's act and the idle return home.
    let timer = json!({"type": "trigger", "label": "HINT", "ref": "timer", "via": "timer",
        "element": "p[data-act=HINT]"});
    kiosk.send(timer).await;
    kiosk.recv_type("triggered").await;
    kiosk
        .send(json!({"type": "page", "page": "index.html", "via": "idle"}))
        .await;
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["session"], Value::Null, "no visitor touched yet");

    // A visitor's tap on the button, then on the link.
    let tap = json!({"type": "trigger", "label": "WELCOME", "ref": "tap", "via": "touch",
        "element": "  button[data-act=WELCOME] \"Hello\"  "});
    kiosk.send(tap).await;
    kiosk.recv_type("triggered").await;
    let link = json!({"type": "page", "page": "map.html", "via": "touch",
        "element": "a[href=map.html] \"Map\""});
    kiosk.send(link).await;
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["display"]["page"], "map.html");
    let corpus = server.corpus.clone();
    let all = server.stop().await;

    let sessions = session_dirs(&corpus);
    assert_eq!(sessions.len(), 1, "the tap started one session");
    let session = json_lines(&sessions[0].join(SESSION_EVENTS));
    let manifest = SessionManifest::read_from(&sessions[0]).unwrap();
    let fingerprint = docent::content::bundle_fingerprint(b.path()).unwrap();
    assert_eq!(
        manifest.bundle_hash.as_deref(),
        Some(fingerprint.as_str()),
        "the manifest names the content it was recorded with"
    );
    let types: Vec<&str> = (session.iter())
        .map(|e| e["type"].as_str().unwrap_or(""))
        .filter(|t| {
            [
                "session.started",
                "touch",
                "act.triggered",
                "display.changed",
            ]
            .contains(t)
        })
        .collect();
    assert_eq!(
        types,
        [
            "session.started",
            "touch",
            "act.triggered",
            "touch",
            "display.changed"
        ],
        "each touch is logged in the session it started, before what it caused"
    );
    assert_eq!(
        session[0]["page"], "index.html",
        "a session's start says what the touchscreen showed"
    );
    let touches: Vec<&Value> = session.iter().filter(|e| e["type"] == "touch").collect();
    assert_eq!(touches[0]["act"], "WELCOME");
    assert_eq!(touches[0]["element"], "button[data-act=WELCOME] \"Hello\"");
    assert_eq!(touches[0]["page"], "index.html");
    assert_eq!(touches[1]["link"], "map.html");
    assert_eq!(touches[1]["page"], "index.html", "the page the link was on");
    assert_eq!(touches[1].get("act"), None);
    let hint = all
        .iter()
        .find(|e| e["type"] == "act.triggered" && e["label"] == "HINT");
    assert_eq!(
        hint.map(|e| e.get("session_us").is_none()),
        Some(true),
        "the timer's act is in the day log, outside any session"
    );
    assert_eq!(all.iter().filter(|e| e["type"] == "touch").count(), 2);
}

#[tokio::test]
async fn a_touch_on_an_act_no_page_offers_is_logged_before_its_refusal() {
    let b = kiosk_bundle();
    let server = TestServer::start(b.path()).await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    let tap = json!({"type": "trigger", "label": "SECRET", "via": "touch", "element": "div#x"});
    kiosk.send(tap).await;
    assert_eq!(kiosk.recv_type("error").await["code"], "not-offered");
    let all = server.stop().await;
    let touch = all.iter().position(|e| e["type"] == "touch");
    let refused = all.iter().position(|e| e["type"] == "trigger.refused");
    assert!(touch.is_some() && touch < refused, "{all:#?}");
    assert_eq!(all[touch.unwrap()]["act"], "SECRET");
}
