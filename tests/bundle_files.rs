//! `/pages/` and `/media/` serve the bundle's files, and no request path leaves the bundle:
//! `..`, encoded dots and slashes, absolute paths, backslashes and symlinks all answer 404.
//! Requests are written by hand because HTTP client libraries normalise such paths away.

mod common;

use common::{TempBundle, TestServer};
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
