//! The browser side as the server delivers it: the kiosk and projector shells (over a real
//! connection), the embedded static files, the page script added to bundle HTML pages (and
//! nothing added to other files; these two through the route table in process, `TestApp`),
//! and the `kiosk:` / `projector:` settings reaching the shells.

use crate::common;

use axum::http::Method;
use common::{TempBundle, TestApp, TestServer};
use docent::content::load_bundle;

const ACTS: &str = "- Label: INVITE\n  Text: Touch the screen!\n";
const CSS: &str = "body { color: #123; }\n";
/// Not valid UTF-8, to show it goes through untouched.
const IMAGE: &[u8] = b"\x89PNG\r\n\x1a\n\xff\x00<head>";

async fn fetch(server: &TestServer, path: &str) -> (u16, String, Vec<u8>) {
    let response = reqwest::get(server.url(path)).await.expect("GET");
    let status = response.status().as_u16();
    let kind = response
        .headers()
        .get("content-type")
        .and_then(|v| v.to_str().ok())
        .unwrap_or_default()
        .to_owned();
    let body = response.bytes().await.expect("body").to_vec();
    (status, kind, body)
}

/// [`fetch`] through the route table, without a connection.
async fn fetch_in_process(app: &TestApp, path: &str) -> (u16, String, Vec<u8>) {
    let answer = app.call(Method::GET, path, None, None).await;
    let kind = answer.header("content-type").to_owned();
    (answer.status.as_u16(), kind, answer.body.to_vec())
}

fn text(body: &[u8]) -> &str {
    std::str::from_utf8(body).expect("utf-8")
}

fn bundle() -> TempBundle {
    let bundle = TempBundle::new(ACTS)
        .with_file(
            "docent.yaml",
            "kiosk:\n  idle: 45s\n  idle_act: INVITE\nprojector:\n  after_video: hold\n",
        )
        .with_file(
            "pages/index.html",
            "<!doctype html>\n<html><head><title>home</title></head>\n\
             <body><button data-act=\"INVITE\">Hi</button></body></html>\n",
        )
        .with_file("pages/style.css", CSS);
    std::fs::write(bundle.path().join("media/poster.png"), IMAGE).expect("image");
    bundle
}

#[tokio::test]
async fn the_shells_render_with_their_settings() {
    let bundle = bundle();
    let server = TestServer::start(bundle.path()).await;

    let (status, kind, body) = fetch(&server, "/").await;
    assert_eq!((status, kind.as_str()), (200, "text/html; charset=utf-8"));
    let page = text(&body);
    for expected in [
        r#"data-ws="/ws""#,
        r#"data-home="index.html""#,
        r#"data-idle-ms="45000""#,
        r#"data-idle-act="INVITE""#,
        r#"src="/static/kiosk.js""#,
    ] {
        assert!(page.contains(expected), "{expected} missing in {page}");
    }

    let (status, kind, body) = fetch(&server, "/projector").await;
    assert_eq!((status, kind.as_str()), (200, "text/html; charset=utf-8"));
    let page = text(&body);
    for expected in [
        r#"data-ws="/ws""#,
        r#"data-after-video="hold""#,
        r#"src="/static/projector.js""#,
    ] {
        assert!(page.contains(expected), "{expected} missing in {page}");
    }
    server.stop().await;
}

#[tokio::test]
async fn static_files_are_embedded_and_unknown_ones_are_json_404() {
    let bundle = bundle();
    let server = TestApp::start(bundle.path()).await;
    for (name, wanted) in [
        ("kiosk.js", "text/javascript"),
        ("socket.js", "text/javascript"),
        ("docent-page.js", "text/javascript"),
        ("projector.js", "text/javascript"),
        ("kiosk.css", "text/css"),
        ("projector.css", "text/css"),
    ] {
        let (status, kind, body) = fetch_in_process(&server, &format!("/static/{name}")).await;
        assert_eq!(status, 200, "{name}");
        assert!(kind.starts_with(wanted), "{name}: {kind}");
        let on_disk = std::fs::read(common::repo().join("static").join(name)).expect("static");
        assert_eq!(body, on_disk, "{name}");
    }
    for missing in [
        "/static/nope.js",
        "/static/../Cargo.toml",
        "/static/pages/x.js",
    ] {
        let (status, body) = server.get(missing).await;
        assert_eq!(status, 404, "{missing}");
        assert_eq!(body["code"], "not-found", "{missing}");
    }
    server.stop().await;
}

#[tokio::test]
async fn html_pages_get_the_page_script_and_other_files_are_untouched() {
    let bundle = bundle();
    let server = TestApp::start(bundle.path()).await;

    let (status, kind, body) = fetch_in_process(&server, "/pages/index.html").await;
    assert_eq!((status, kind.as_str()), (200, "text/html"));
    assert!(
        text(&body).starts_with(
            "<!doctype html>\n<html><head><script \
             src=\"/static/docent-page.js\"></script><title>home</title>"
        ),
        "{}",
        text(&body)
    );

    let (status, kind, body) = fetch_in_process(&server, "/pages/style.css").await;
    assert_eq!((status, body.as_slice()), (200, CSS.as_bytes()));
    assert!(kind.starts_with("text/css"), "{kind}");
    let (status, kind, body) = fetch_in_process(&server, "/media/poster.png").await;
    assert_eq!(
        (status, kind.as_str(), body.as_slice()),
        (200, "image/png", IMAGE)
    );

    // An API client (JSON) gets the JSON error; browsers get a page (tests/bundle_files.rs).
    let (status, body) = server.get("/pages/missing.png").await;
    assert_eq!((status, body["code"].as_str()), (404, Some("not-found")));
    server.stop().await;
}

#[test]
fn an_unknown_idle_act_is_reported_at_its_place() {
    let bundle = TempBundle::new(ACTS).with_file("docent.yaml", "kiosk:\n  idle_act: INVTE\n");
    let report = load_bundle(bundle.path());
    let found: Vec<_> = report
        .diagnostics
        .iter()
        .map(|d| (d.code.as_str(), d.file.as_ref(), d.line, d.column))
        .collect();
    // INVITE, meant as the idle act, is then the operator's (no act has a `Group`).
    assert_eq!(found, [("unknown-act", "docent.yaml", 2, 13)]);
    assert!(
        report.diagnostics[0]
            .message
            .contains("Did you mean `INVITE`?")
    );
    assert!(report.bundle.is_none());
}
