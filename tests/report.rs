//! `GET /api/report` through the server's route table in process (`TestApp`; over a real
//! connection in `documented_limits.rs`): refused without the operator credential, and for
//! a small bundle it lists every act (texts, commands, place, group, key), every page with the
//! acts it offers and the acts that show it, every media file with the acts that project it
//! and the pages naming it, and the live bundle's warnings and notes. `GET /report` is the
//! public shell.

use crate::common;

use axum::http::Method;
use common::{OPERATOR_TOKEN, TempBundle, TestApp};
use serde_json::json;

/// A 1×1 PNG: a real picture, whatever the check sniffs.
const PNG: &[u8] = b"\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x01\x00\x00\x00\x01\x08\x06\x00\x00\x00\x1f\x15\xc4\x89\x00\x00\x00\x0d\x49\x44\x41\x54\x78\xda\x63\x64\x60\xf8\x5f\x0f\x00\x02\x87\x01\x80\xeb\x47\xba\x92\x00\x00\x00\x00\x49\x45\x4e\x44\xae\x42\x60\x82";

const ACTS: &str = "\
- Label: WELCOME
  Text:
    - Welcome to the museum.
    - Hello and welcome.
  TextChild: Hi there!
  Cmds:
    - DISPLAY_PAGE index.html
  Group: Start
  Key: W
- Label: PAINTING
  Text: yes
  Cmds: PROJECT painting.png
";

const INDEX: &str = "<!doctype html>\n<title>Start</title>\n<button data-act=\"PAINTING\">The painting</button>\n<img src=\"../media/painting.png\" alt=\"\">\n";

fn fixture() -> TempBundle {
    let bundle = TempBundle::new(ACTS).with_file("pages/index.html", INDEX);
    std::fs::write(bundle.path().join("media/painting.png"), PNG).expect("write media");
    bundle
}

#[tokio::test]
async fn the_report_needs_the_operator_credential() {
    let bundle = fixture();
    let server = TestApp::start(bundle.path()).await;
    let none = server.call(Method::GET, "/api/report", None, None).await;
    assert_eq!(none.status.as_u16(), 401);
    assert!(none.headers.contains_key("www-authenticate"));
    let body = none.json();
    assert!(body.is_object() && body.get("acts").is_none(), "{body}");
    let wrong = "not-the-operator-credential";
    let wrong = (server.call(Method::GET, "/api/report", None, Some(wrong))).await;
    assert_eq!(wrong.status.as_u16(), 401);
    // The page itself is public and carries no content.
    let page = server.call(Method::GET, "/report", None, None).await;
    assert_eq!(page.status.as_u16(), 200);
    let html = page.text();
    assert!(html.contains(r#"data-api="/api/report""#));
    assert!(!html.contains("Welcome to the museum") && !html.contains(OPERATOR_TOKEN));
    server.stop().await;
}

#[tokio::test]
async fn the_report_lists_acts_pages_media_and_problems() {
    let bundle = fixture();
    let server = TestApp::start(bundle.path()).await;
    let (status, report) = server.get("/api/report").await;
    assert_eq!(status, 200, "{report}");
    assert_eq!(report["home"], "index.html");
    assert_eq!(
        report["acts"],
        json!([
            {
                "label": "WELCOME", "file": "acts.yaml", "line": 1, "group": "Start", "key": "W",
                "variants": [
                    {"name": "Text", "texts": ["Welcome to the museum.", "Hello and welcome."]},
                    {"name": "TextChild", "texts": ["Hi there!"]},
                ],
                "commands": ["DISPLAY_PAGE index.html"],
                "offered_on": [],
            },
            {
                "label": "PAINTING", "file": "acts.yaml", "line": 10, "group": "acts", "key": null,
                "variants": [{"name": "Text", "texts": ["yes"]}],
                "commands": ["PROJECT painting.png"],
                "offered_on": ["index.html"],
            },
        ])
    );
    assert_eq!(
        report["pages"],
        json!([{
            "path": "index.html",
            "offers": [{"label": "PAINTING", "line": 3, "known": true}],
            "displayed_by": ["WELCOME"],
        }])
    );
    assert_eq!(
        report["media"],
        json!([{"path": "painting.png", "projected_by": ["PAINTING"], "used_on": ["index.html"]}])
    );
    let problems: Vec<(&str, &str, &str, u64, u64)> = report["problems"]
        .as_array()
        .expect("problems")
        .iter()
        .map(|p| {
            (
                p["severity"].as_str().unwrap_or(""),
                p["code"].as_str().unwrap_or(""),
                p["file"].as_str().unwrap_or(""),
                p["line"].as_u64().unwrap_or(0),
                p["column"].as_u64().unwrap_or(0),
            )
        })
        .collect();
    assert_eq!(
        problems,
        [("warning", "unquoted-scalar", "acts.yaml", 11, 9)]
    );
    server.stop().await;
}

#[tokio::test]
async fn the_report_lists_files_ignored_from_a_mac_copy_as_a_note() {
    let bundle = fixture();
    common::mac_copy::as_copied_from_a_mac(bundle.path());
    let server = TestApp::start(bundle.path()).await;
    let (status, report) = server.get("/api/report").await;
    assert_eq!(status, 200, "{report}");
    let problems: Vec<(&str, &str, &str)> = report["problems"]
        .as_array()
        .expect("problems")
        .iter()
        .map(|p| {
            let text = |k: &str| p[k].as_str().unwrap_or("");
            (text("severity"), text("code"), text("file"))
        })
        .collect();
    assert_eq!(
        problems,
        [
            ("note", "ignored-files", ".DS_Store"),
            ("warning", "unquoted-scalar", "acts.yaml"),
        ]
    );
    server.stop().await;
}
