//! The HTTP trigger API, called in process through the server's route table (`TestApp`: no
//! socket; `access.rs` and `http_limits.rs` test the same routes over real connections): the
//! paper's Fig. 4 bundle resolves, choices never repeat back to back, contexts fall back to
//! `Text`, unknown labels get a suggestion.

use crate::common;

use axum::http::Method;
use common::{TempBundle, TestApp, bundle};
use serde_json::{Value, json};

fn commands(triggered: &Value) -> Vec<(String, Option<String>)> {
    triggered["commands"]
        .as_array()
        .expect("commands")
        .iter()
        .map(|c| {
            (
                c["verb"].as_str().unwrap().to_owned(),
                c["arg"].as_str().map(str::to_owned),
            )
        })
        .collect()
}

fn say(text: &str) -> (String, Option<String>) {
    ("SAY".into(), Some(text.into()))
}

#[tokio::test]
async fn every_act_of_the_paper_sample_resolves_into_its_commands() {
    let server = TestApp::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    let welcome = server.trigger("WELCOME", json!({})).await;
    assert_eq!(
        commands(&welcome),
        vec![
            say("Hello!"),
            ("DISPLAY_PAGE".into(), Some("Welcome/Welcome.html".into()))
        ]
    );
    let ok = server.trigger("OK", json!({})).await;
    let text = ok["text"].as_str().unwrap();
    assert!(["OK!", "Great!", "Splendid!"].contains(&text), "{text}");
    assert_eq!(commands(&ok), vec![say(text)]);
    let where_from = server.trigger("WHERE_FROM", json!({})).await;
    assert_eq!(commands(&where_from), vec![say("Where do you come from?")]);
    let video = server.trigger("RUN_VIDEO_EXHIBIT", json!({})).await;
    assert_eq!(
        commands(&video),
        vec![
            say("Let me show you a video about this exhibit."),
            ("PROJECT".into(), Some("Exhibit/video.mp4".into()))
        ]
    );
    assert!(video["trigger"].as_u64().unwrap() > where_from["trigger"].as_u64().unwrap());
    server.stop().await;
}

#[tokio::test]
async fn alternatives_never_repeat_back_to_back() {
    let server = TestApp::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    let mut texts = Vec::new();
    for _ in 0..40 {
        texts.push(
            server.trigger("OK", json!({})).await["text"]
                .as_str()
                .unwrap()
                .to_owned(),
        );
    }
    assert!(texts.windows(2).all(|w| w[0] != w[1]), "{texts:?}");
    for alt in ["OK!", "Great!", "Splendid!"] {
        assert!(
            texts.iter().any(|t| t == alt),
            "{alt} never chosen in {texts:?}"
        );
    }
    server.stop().await;
}

#[tokio::test]
async fn the_same_seed_gives_the_same_choices() {
    let mut runs = Vec::new();
    for _ in 0..2 {
        let server = TestApp::start_with(&bundle("tests/fixtures/fig4-verbatim"), |o| {
            o.seed = Some(99)
        })
        .await;
        let mut texts = Vec::new();
        for _ in 0..12 {
            texts.push(server.trigger("OK", json!({})).await["text"].clone());
        }
        runs.push(texts);
        server.stop().await;
    }
    assert_eq!(runs[0], runs[1]);
}

#[tokio::test]
async fn a_context_picks_its_variant_and_falls_back_to_text() {
    let server = TestApp::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    let group = server
        .trigger("WHERE_FROM", json!({"context": "TextGroup"}))
        .await;
    assert_eq!(
        (group["variant"].as_str(), group["text"].as_str()),
        (Some("TextGroup"), Some("Where are you from?"))
    );
    let formal = server
        .trigger("WHERE_FROM", json!({"context": "TextFormally"}))
        .await;
    assert_eq!(formal["text"], "May I ask from where you are?");
    // WELCOME has no TextGroup: it falls back to Text.
    let welcome = server
        .trigger("WELCOME", json!({"context": "TextGroup"}))
        .await;
    assert_eq!(
        (welcome["context"].as_str(), welcome["variant"].as_str()),
        (Some("TextGroup"), Some("Text"))
    );

    // The current context applies when a trigger names none.
    let (status, body) = server
        .put("/api/context", json!({"context": "TextFormally"}))
        .await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(
        server.get("/api/context").await.1["context"],
        "TextFormally"
    );
    let current = server.trigger("WHERE_FROM", json!({})).await;
    assert_eq!(current["text"], "May I ask from where you are?");

    let (status, body) = server
        .put("/api/context", json!({"context": "TextGrop"}))
        .await;
    assert_eq!(
        (status, body["code"].as_str(), body["suggestion"].as_str()),
        (400, Some("unknown-context"), Some("TextGroup"))
    );
    let (status, body) = server
        .post("/api/acts/OK/trigger", Some(json!({"context": "Nope"})))
        .await;
    assert_eq!(
        (status, body["code"].as_str()),
        (400, Some("unknown-context"))
    );
    server.stop().await;
}

#[tokio::test]
async fn an_unknown_label_answers_404_naming_the_closest_label() {
    let server = TestApp::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    let (status, body) = server.post("/api/acts/WELCOM/trigger", None).await;
    assert_eq!(status, 404);
    assert_eq!(body["code"], "unknown-act");
    assert_eq!(body["suggestion"], "WELCOME");
    assert!(
        body["error"].as_str().unwrap().contains("WELCOME"),
        "{body}"
    );
    let (status, body) = server
        .post("/api/acts/OK/trigger", Some(json!({"colour": "red"})))
        .await;
    assert_eq!((status, body["code"].as_str()), (400, Some("bad-request")));
    let (status, _) = server.get("/api/no-such-thing").await;
    assert_eq!(status, 404);
    server.stop().await;
}

#[tokio::test]
async fn the_acts_listing_carries_labels_variants_commands_and_positions() {
    let server = TestApp::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    let (status, body) = server.get("/api/acts").await;
    assert_eq!(status, 200);
    let acts = body["acts"].as_array().unwrap();
    let labels: Vec<&str> = acts.iter().map(|a| a["label"].as_str().unwrap()).collect();
    assert_eq!(labels, ["WELCOME", "OK", "WHERE_FROM", "RUN_VIDEO_EXHIBIT"]);
    assert_eq!(
        acts[0]["at"],
        json!({"file": "acts.yaml", "line": 1, "column": 10})
    );
    assert_eq!(acts[0]["commands"][0]["verb"], "DISPLAY_PAGE");
    assert_eq!(acts[0]["commands"][0]["at"]["line"], 5);
    let where_from = &acts[2]["variants"];
    let names: Vec<&str> = where_from
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["Text", "TextGroup", "TextFormally"]);
    assert_eq!(
        body["contexts"],
        json!(["Text", "TextFormally", "TextGroup"])
    );
    let (status, health) = server.get("/healthz").await;
    assert_eq!(
        (status, health["status"].as_str(), health["acts"].as_u64()),
        (200, Some("ok"), Some(4))
    );
    server.stop().await;
}

#[tokio::test]
async fn the_acts_listing_names_the_variant_a_trigger_speaks_in_each_context() {
    let acts = "- Label: HELLO\n  Text: [Hello]\n  TextGroup: [Hello all]\n\
                - Label: CHILD\n  TextChild: [Hi there]\n\
                - Label: QUIET\n  Cmds: [WAIT 1ms]\n";
    let b = TempBundle::new(acts);
    let server = TestApp::start(b.path()).await;
    let (status, body) = server.get("/api/acts").await;
    assert_eq!(status, 200);
    assert_eq!(body["contexts"], json!(["Text", "TextChild", "TextGroup"]));
    let speaks: Vec<(&str, &Value)> = (body["acts"].as_array().unwrap().iter())
        .map(|a| (a["label"].as_str().unwrap(), &a["speaks"]))
        .collect();
    assert_eq!(
        speaks,
        [
            (
                "HELLO",
                &json!({"Text": "Text", "TextChild": "Text", "TextGroup": "TextGroup"})
            ),
            (
                "CHILD",
                &json!({"Text": null, "TextChild": "TextChild", "TextGroup": null})
            ),
            (
                "QUIET",
                &json!({"Text": null, "TextChild": null, "TextGroup": null})
            ),
        ]
    );
    // What the listing says is what a trigger in that context speaks.
    for (label, by_context) in speaks {
        for (context, variant) in by_context.as_object().unwrap() {
            let triggered = server.trigger(label, json!({"context": context})).await;
            assert_eq!(&triggered["variant"], variant, "{label} in {context}");
        }
    }
    server.stop().await;
}

#[tokio::test]
async fn a_kiosk_is_told_its_opening_hours_evaluated_from_its_own_clock() {
    let config = "home: index.html\nschedule:\n  closed: closed.html\n  open:\n    \
                  - {days: Mon-Fri, hours: 09:00-12:00, home: school.html}\n    \
                  - {days: Mon-Fri, hours: 12:00-17:00}\n";
    let b = TempBundle::new("- Label: HELLO\n  Text: [Hello]\n")
        .with_file("docent.yaml", config)
        .with_file("pages/closed.html", "<!doctype html><title>closed</title>")
        .with_file("pages/school.html", "<!doctype html><title>school</title>");
    let server = TestApp::start(b.path()).await;
    // No credential: the kiosk asks.
    let path = "/api/schedule/2025-12-01T08:59";
    let answer = server.call(Method::GET, path, None, None).await;
    assert_eq!(answer.status.as_u16(), 200);
    let table = answer.json();
    assert_eq!(
        table["showing"],
        json!({"state": "closed", "page": "closed.html"})
    );
    let open = |home: &str| json!({"state": "open", "home": home, "attract": null});
    let closed = json!({"state": "closed", "page": "closed.html"});
    assert_eq!(
        table["changes"].as_array().expect("changes")[..4],
        [
            json!({"at": "2025-12-01T09:00", "showing": open("school.html")}),
            json!({"at": "2025-12-01T12:00", "showing": open("index.html")}),
            json!({"at": "2025-12-01T17:00", "showing": closed}),
            json!({"at": "2025-12-02T09:00", "showing": open("school.html")}),
        ]
    );
    assert_eq!(table["until"], "2025-12-10T00:00");
    for bad in ["2025-12-01", "2025-13-01T08:59", "now"] {
        let (status, body) = server.get(&format!("/api/schedule/{bad}")).await;
        assert_eq!(
            (status, body["code"].as_str()),
            (400, Some("bad-request")),
            "{bad}"
        );
    }
    server.stop().await;
}

#[tokio::test]
async fn state_reports_display_pose_context_and_queues() {
    let server = TestApp::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    server.trigger("WELCOME", json!({})).await;
    let (status, state) = server.get("/api/state").await;
    assert_eq!(status, 200);
    assert_eq!(state["display"]["page"], "Welcome/Welcome.html");
    assert_eq!(state["context"], "Text");
    assert_eq!(state["pose"]["moving"], false);
    assert!(
        state["queues"].as_object().unwrap().contains_key("display"),
        "{state}"
    );
    let (status, stopped) = server.post("/api/stop", None).await;
    assert_eq!((status, stopped["stopped"].as_bool()), (202, Some(true)));
    server.stop().await;
}

#[tokio::test]
async fn the_acts_listing_gives_each_variants_texts_per_language_with_the_fallback_named_and_keywords()
 {
    let acts = "- Label: HELLO\n  Text: [Hello, Hi]\n  Text@de: [Hallo, Servus]\n\
                \x20 TextChild: [Hi kid]\n\
                - Label: VIDEO\n  Keywords: [film, Projektion]\n  Text: [Watch this]\n\
                - Label: QUIET\n  Keywords: movie\n  Cmds: [WAIT 1ms]\n";
    let b = TempBundle::new(acts).with_file("docent.yaml", "languages: [en, de]\n");
    let server = TestApp::start(b.path()).await;
    let (status, body) = server.get("/api/acts").await;
    assert_eq!(status, 200);
    assert_eq!(body["languages"], json!(["en", "de"]), "the default first");
    let hello = &body["acts"][0]["variants"];
    assert_eq!(
        hello[0]["languages"],
        json!({
            "en": {"language": "en", "texts": ["Hello", "Hi"]},
            "de": {"language": "de", "texts": ["Hallo", "Servus"]},
        })
    );
    // No German child text: in German the robot says the English one, and the listing says so.
    assert_eq!(
        hello[1]["languages"]["de"],
        json!({"language": "en", "texts": ["Hi kid"]})
    );
    assert_eq!(body["acts"][1]["keywords"], json!(["film", "Projektion"]));
    assert_eq!(body["acts"][2]["keywords"], json!(["movie"]));
    assert_eq!(body["acts"][0]["keywords"], json!([]));
    server.stop().await;
}
