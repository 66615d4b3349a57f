//! `/pages/` and `/media/` serve the bundle's files, and no request path leaves the bundle:
//! `..`, encoded dots and slashes, absolute paths, backslashes and symlinks all answer 404.
//! Those requests are written by hand on a real connection because HTTP client libraries
//! normalise such paths away; the answers to missing pages and the timers' delays are asked
//! of the route table in process (`TestApp`).

use crate::common;

use common::{TempBundle, TestApp, TestServer};
use tokio::io::{AsyncReadExt, AsyncWriteExt};

const SECRET: &str = "top-secret-outside-the-bundle";

async fn raw_get(server: &TestServer, path: &str, extra: &str) -> (u16, String) {
    let mut tcp = tokio::net::TcpStream::connect(server.addr).await.unwrap();
    let request =
        format!("GET {path} HTTP/1.1\r\nHost: docent\r\n{extra}Connection: close\r\n\r\n");
    tcp.write_all(request.as_bytes()).await.unwrap();
    let mut response = Vec::new();
    tcp.read_to_end(&mut response).await.unwrap();
    let text = String::from_utf8_lossy(&response).into_owned();
    let status = text
        .split_whitespace()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    (status, text)
}

#[tokio::test]
async fn bundle_files_are_served_and_no_path_leaves_the_bundle() {
    let outer = tempfile::tempdir().unwrap();
    std::fs::write(outer.path().join("secret.txt"), SECRET).unwrap();
    let b = TempBundle::new("- Label: A\n  Text: [a]\n")
        .with_file("pages/sub/page.html", "<p>sub</p>")
        .with_file("media/clip.webm", &"w".repeat(1000));
    std::os::unix::fs::symlink(
        outer.path().join("secret.txt"),
        b.path().join("pages/leak.html"),
    )
    .unwrap();
    std::os::unix::fs::symlink(
        b.path().join("pages/index.html"),
        b.path().join("pages/alias.html"),
    )
    .unwrap();
    let server = TestServer::start(b.path()).await;

    let (status, page) = raw_get(&server, "/pages/index.html", "").await;
    assert_eq!(status, 200);
    assert!(
        page.to_lowercase().contains("content-type: text/html"),
        "{page}"
    );
    assert_eq!(raw_get(&server, "/pages/sub/page.html", "").await.0, 200);
    assert_eq!(
        raw_get(&server, "/pages/alias.html", "").await.0,
        200,
        "a symlink inside the bundle is fine"
    );
    let (status, clip) = raw_get(&server, "/media/clip.webm", "Range: bytes=0-99\r\n").await;
    assert_eq!(status, 206, "videos can be sought: {clip:.200}");
    assert!(clip.to_lowercase().contains("content-type: video/webm"));

    let outside = tempfile::Builder::new()
        .prefix("outside")
        .tempdir_in(b.path().parent().unwrap())
        .unwrap();
    let escapes = [
        "/pages/../acts.yaml".to_owned(),
        "/pages/%2e%2e/acts.yaml".into(),
        "/pages/%2E%2E/%2E%2E/etc/passwd".into(),
        "/pages/..%2facts.yaml".into(),
        "/pages/..%5cacts.yaml".into(),
        "/pages/sub/..%2f..%2facts.yaml".into(),
        "/pages//etc/passwd".into(),
        "/pages/%2fetc%2fpasswd".into(),
        "/media/..%2f..%2f..%2f..%2fetc%2fpasswd".into(),
        "/pages/leak.html".into(),
        "/pages/%00index.html".into(),
        "/pages/INDEX.HTML".into(),
        "/pages/sub".into(),
        "/pages/".into(),
        format!(
            "/pages/..%2f..%2f{}%2fsecret.txt",
            outside.path().file_name().unwrap().to_str().unwrap()
        ),
        format!("/pages/{}", outer.path().join("secret.txt").display()),
    ];
    for path in &escapes {
        let (status, body) = raw_get(&server, path, "").await;
        assert!(status == 404 || status == 400, "{path} answered {status}");
        assert!(
            !body.contains(SECRET) && !body.contains("root:"),
            "{path} leaked: {body}"
        );
        assert!(!body.contains("Label"), "{path} served the acts file");
    }
    server.stop().await;
}

#[tokio::test]
async fn a_missing_page_answers_a_browser_with_the_friendly_page_and_an_api_client_with_json() {
    let b = TempBundle::new("- Label: A\n  Text: [a]\n")
        .with_file(
            "pages/index.html",
            "<!doctype html><head><link rel=\"stylesheet\" href=\"css/site.css\"></head><p>home",
        )
        .with_file("pages/css/site.css", "body { color: teal }");
    let server = TestApp::start(b.path()).await;
    let browser = Some("text/html,application/xhtml+xml,*/*;q=0.8");
    let from = ("referer", "http://docent/pages/index.html");

    for (path, accept) in [
        ("/pages/gone.html", None),
        ("/pages/gone.html", Some("*/*")),
        ("/pages/gone.html", browser),
        ("/pages/Index.html", browser), // miscased: not found either
        ("/pages/sub/", browser),
        ("/pages/images/gone.png", browser),
    ] {
        let headers: Vec<_> = accept
            .map(|a| ("accept", a))
            .into_iter()
            .chain([from])
            .collect();
        let answer = server.get_with(path, &headers).await;
        let (kind, body) = (answer.header("content-type"), answer.text());
        assert_eq!(answer.status, 404, "{path}");
        assert_eq!(kind, "text/html; charset=utf-8", "{path}: {body}");
        assert!(body.contains("This page is not available."), "{body}");
        assert!(body.contains(r#"<a class="docent-home" href="/pages/index.html""#));
        assert!(body.contains(r#"<link rel="stylesheet" href="css/site.css">"#));
        assert!(body.contains(r#"<script src="/static/docent-page.js"></script>"#));
        assert!(
            !body.contains("not-found") && !body.contains("spelled"),
            "{body}"
        );
    }
    for (path, accept) in [
        ("/pages/gone.html", Some("application/json")),
        ("/pages/images/gone.png", Some("*/*")),
        ("/pages/images/gone.png", None),
        ("/media/gone.html", browser),
    ] {
        let headers: Vec<_> = accept.map(|a| ("accept", a)).into_iter().collect();
        let answer = server.get_with(path, &headers).await;
        let (kind, body) = (answer.header("content-type"), answer.text());
        assert_eq!(
            (answer.status.as_u16(), kind),
            (404, "application/json"),
            "{path}"
        );
        assert!(body.contains(r#""code":"not-found""#), "{path}: {body}");
    }

    let missing: Vec<_> = server
        .stop()
        .await
        .into_iter()
        .filter(|e| e["type"] == "page.missing")
        .map(|e| (e["page"].as_str().unwrap().to_owned(), e["from"].clone()))
        .collect();
    let from = serde_json::json!("index.html");
    let pages = [
        "gone.html",
        "gone.html",
        "gone.html",
        "Index.html",
        "sub/",
        "images/gone.png",
    ];
    let expected: Vec<_> = pages
        .iter()
        .map(|p| (p.to_string(), from.clone()))
        .collect();
    assert_eq!(missing, expected, "only the friendly answers are logged");
}

#[tokio::test]
async fn a_flood_of_missing_pages_is_not_all_logged() {
    let b = TempBundle::new("- Label: A\n  Text: [a]\n");
    let server = TestApp::start(b.path()).await;
    for i in 0..60 {
        let answer = server
            .get_with(&format!("/pages/nothing-{i}.html"), &[])
            .await;
        assert_eq!(answer.status, 404);
    }
    let logged = server.stop().await;
    let logged = logged
        .iter()
        .filter(|e| e["type"] == "page.missing")
        .count();
    // The burst of 20, plus what refilled (2 a second) while the 60 requests ran.
    assert!((20..30).contains(&logged), "{logged} logged");
}

/// One grammar for page timers: the server reads `data-act-after` with the checker's rule and
/// serves the delay in milliseconds, which is all the page script reads.
#[tokio::test]
async fn timer_delays_are_served_in_milliseconds_read_by_the_checkers_rule() {
    let page = "<!doctype html><div data-act=\"NEXT\" data-act-after=\" 1.5 s \"></div>";
    let bundle =
        TempBundle::new("- Label: NEXT\n  Text: Next\n").with_file("pages/slides.html", page);
    let server = TestApp::start(bundle.path()).await;
    let answer = server.get_with("/pages/slides.html", &[]).await;
    let html = answer.text();
    assert_eq!(answer.status, 200, "{html}");
    assert!(
        html.contains(r#"data-act-after=" 1.5 s " data-act-after-ms="1500""#),
        "{html}"
    );
    server.stop().await;
}

#[tokio::test]
async fn what_a_mac_or_an_editor_leaves_is_not_served_but_the_pages_are() {
    let bundle = TempBundle::new("- Label: A\n  Text: Hi\n")
        .with_file("pages/index.html", "<!doctype html><title>home</title>")
        .with_file("media/poster.png", "not really a picture");
    let copied = common::mac_copy::as_copied_from_a_mac(bundle.path());
    assert!(copied >= 4, "{copied} `._` files");
    std::fs::write(bundle.path().join("pages/index.html.bak"), "<p>old</p>").expect("write");
    let app = TestApp::start(bundle.path()).await;
    for litter in [
        "/pages/._index.html",
        "/pages/.DS_Store",
        "/media/._poster.png",
        "/pages/index.html.bak",
    ] {
        let answer = app.get_with(litter, &[]).await;
        assert_eq!(answer.status, 404, "{litter} is not content");
    }
    assert_eq!(app.get_with("/pages/index.html", &[]).await.status, 200);
    app.stop().await;
}
