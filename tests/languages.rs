//! The visitor's language at run time, on the two-language fixture bundle with the real
//! espeak-ng (its WAV output): an operator switches to German, the act speaks its German
//! alternative with the `de` voice (the WAV is the one espeak-ng makes with `-v de`), the
//! corpus line says `de`; an untranslated act speaks English and says `en`; an unknown
//! language is refused with `unknown-language`; a kiosk may switch only to a language its
//! page offers; a session's end brings the default language back.

use crate::common;

use std::process::Command;

use common::TestServer;
use serde_json::{Value, json};

const RATE: &str = "170"; // the fixture's `speech: rate`

fn fixture() -> std::path::PathBuf {
    common::repo().join("tests/fixtures/two-languages")
}

/// What espeak-ng itself makes of `text` with `voice` at the fixture's rate.
fn espeak_wav(text: &str, voice: &str) -> Vec<u8> {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("direct.wav");
    let status = Command::new("espeak-ng")
        .args(["-v", voice, "-s", RATE, "-w"])
        .arg(&path)
        .arg(text)
        .status()
        .expect("espeak-ng runs");
    assert!(status.success());
    std::fs::read(path).expect("wav written")
}

fn say_id(triggered: &Value) -> u64 {
    assert_eq!(triggered["commands"][0]["verb"], "SAY", "{triggered}");
    triggered["commands"][0]["id"].as_u64().expect("id")
}

#[tokio::test]
async fn a_german_visitor_hears_the_german_text_with_the_german_voice() {
    assert!(
        docent::adapters::espeak_available(),
        "espeak-ng is not installed"
    );
    let wavs = tempfile::tempdir().expect("temp dir");
    let server = TestServer::start_with(&fixture(), |o| {
        o.speech_wav = Some(wavs.path().to_owned());
    })
    .await;
    let mut op = server.operator().await;
    assert_eq!(op.welcome["state"]["language"], "en");
    op.send(json!({"type": "language", "language": "DE", "ref": "l1"}))
        .await;
    let answer = op.recv_type("language").await;
    assert_eq!(
        (answer["language"].as_str(), answer["ref"].as_str()),
        (Some("de"), Some("l1"))
    );
    let changed = op.event("language.changed").await;
    assert_eq!(
        (&changed["language"], &changed["source"]),
        (&json!("de"), &json!("operator"))
    );
    assert_eq!(server.get("/api/state").await.1["language"], "de");

    let triggered = server.trigger("GREETING", json!({})).await;
    assert_eq!(triggered["text"], "Willkommen im Museum!");
    assert_eq!(triggered["language"], "de");
    let say = say_id(&triggered);
    op.event_where(|e| e["type"] == "command.done" && e["command"] == say)
        .await;
    let spoken = std::fs::read(wavs.path().join(format!("{say}.wav"))).expect("wav");
    assert_eq!(
        spoken,
        espeak_wav("Willkommen im Museum!", "de"),
        "espeak-ng was given the de voice"
    );
    assert_ne!(spoken, espeak_wav("Willkommen im Museum!", "en-gb"));

    op.send(json!({"type": "language", "language": "fr", "ref": "l2"}))
        .await;
    let refused = op.recv_type("error").await;
    assert_eq!(
        (refused["code"].as_str(), refused["ref"].as_str()),
        (Some("unknown-language"), Some("l2"))
    );
    assert!(
        refused["message"]
            .as_str()
            .unwrap_or_default()
            .contains("en, de")
    );

    let corpus = server.stop().await;
    let greeting = corpus
        .iter()
        .find(|e| e["type"] == "act.triggered" && e["label"] == "GREETING")
        .expect("act.triggered logged");
    assert_eq!(
        (&greeting["text"], &greeting["language"]),
        (&json!("Willkommen im Museum!"), &json!("de"))
    );
    let sent = corpus
        .iter()
        .find(|e| e["type"] == "command.sent" && e["command"] == say)
        .expect("command.sent logged");
    assert_eq!(sent["args"]["language"], "de");
}

#[tokio::test]
async fn a_kiosk_switches_only_to_a_language_its_page_offers_and_a_session_end_resets_it() {
    let server = TestServer::start(&fixture()).await;
    let mut op = server.operator().await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    assert_eq!(kiosk.welcome["state"]["display"]["page"], "index.html");
    kiosk
        .send(json!({"type": "language", "language": "de", "ref": "k1"}))
        .await;
    // Every kiosk is told of the change (this one too), then this one gets its answer.
    let told = kiosk.recv_type("language").await;
    assert_eq!(
        (told["language"].as_str(), told.get("ref")),
        (Some("de"), None)
    );
    assert_eq!(kiosk.recv_type("language").await["ref"], "k1");
    let changed = op.event("language.changed").await;
    assert_eq!(changed["source"], "kiosk");

    // The tour page has no language button.
    kiosk
        .send(json!({"type": "page", "page": "tour.html", "via": "script"}))
        .await;
    op.event("display.changed").await;
    kiosk
        .send(json!({"type": "language", "language": "en", "ref": "k2"}))
        .await;
    let refused = kiosk.recv_type("error").await;
    assert_eq!(
        (refused["code"].as_str(), refused["ref"].as_str()),
        (Some("not-offered"), Some("k2"))
    );

    // The next visitors start in the default language; the kiosks are told. The visitor's tap
    // on the language button began a session: starting the next one ends it, and its end
    // resets the language in the same step, before the next session starts.
    op.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    let reset = op.event("language.changed").await;
    assert_eq!(
        (&reset["language"], &reset["source"]),
        (&json!("en"), &json!("server"))
    );
    op.event("session.started").await;
    let told = kiosk
        .recv_where(|f| f["type"] == "language" && f["language"] == "en")
        .await;
    assert!(told.get("ref").is_none(), "a notice, not an answer: {told}");

    let corpus = server.stop().await;
    let order: Vec<&str> = corpus
        .iter()
        .filter_map(|e| e["type"].as_str())
        .filter(|t| ["session.started", "session.ended", "language.changed"].contains(t))
        .collect();
    assert_eq!(
        order,
        [
            "session.started",  // by the kiosk's tap on the language button
            "language.changed", // to German, within that session
            "session.ended",    // by the operator's next session
            "language.changed", // back to English, in the same step
            "session.started",
            "session.ended", // the server stopping
        ]
    );
}

#[tokio::test]
async fn a_restarted_server_goes_on_in_the_language_its_reconnecting_kiosk_shows() {
    // A fresh server, as after a restart mid-visit: the kiosk says it shows German pages.
    let server = TestServer::start(&fixture()).await;
    let mut op = server.operator().await;
    let kiosk = server
        .client(json!({"type": "hello", "role": "kiosk", "page": "index.html", "language": "de"}))
        .await;
    assert_eq!(
        kiosk.welcome["state"]["language"], "de",
        "{}",
        kiosk.welcome
    );
    let adopted = op.event("language.changed").await;
    assert_eq!(
        (&adopted["language"], &adopted["source"]),
        (&json!("de"), &json!("kiosk"))
    );
    server.trigger("GREETING", json!({})).await;
    let triggered = op.event("act.triggered").await;
    assert_eq!(triggered["language"], "de", "{triggered}");

    // Once the language changed here, the server's stands: a kiosk still in German from
    // before is brought to English by its welcome.
    op.send(json!({"type": "language", "language": "en", "ref": "back"}))
        .await;
    op.recv_type("language").await;
    let late = server
        .client(json!({"type": "hello", "role": "kiosk", "language": "de"}))
        .await;
    assert_eq!(late.welcome["state"]["language"], "en");

    // A language the bundle lacks is refused, and the kiosk follows the welcome.
    let mut odd = server.connect().await;
    odd.send(json!({"type": "hello", "role": "kiosk", "language": "fr"}))
        .await;
    let refused = odd.recv_type("error").await;
    assert_eq!(refused["code"], "unknown-language", "{refused}");
    assert_eq!(odd.recv_type("welcome").await["state"]["language"], "en");
    server.stop().await;
}
