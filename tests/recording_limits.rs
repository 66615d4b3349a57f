//! The limits of a recording's chunk uploads, against a real server on 127.0.0.1:0 with a
//! protocol client in the kiosk's place: the token is checked before any body byte is read
//! (a client without it holds nothing open, waits for nothing), a chunk may be as large as
//! the `record` frame says (`max_chunk_bytes`, the limit docs/PROTOCOL.md gives), a larger one
//! is a JSON `413 body-too-large` saying the limit, and a body that trickles is cut off at the
//! body time limit (`408 body-timeout`). Raw TCP where a client must be slow or wrong.

use crate::common;

use std::time::Duration;

use common::{DEADLINE, TempBundle, TestServer, WsClient};
use docent::http::ConnectionLimits;
use serde_json::{Value, json};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

const MIB: usize = 1024 * 1024;

/// A kiosk bundle whose sessions are started by marks.
fn site() -> TempBundle {
    TempBundle::new("- Label: WELCOME\n  Text: [Hello!]\n")
        .with_file(
            "docent.yaml",
            "speech: {adapter: log}\ncorpus: {session_start: marked}\n",
        )
        .with_file(
            "pages/index.html",
            r#"<html><body><button data-act="WELCOME">Hello</button></body></html>"#,
        )
}

/// A server with `limits` recording a session: the kiosk has its `record` frame.
async fn recording(limits: ConnectionLimits) -> (TestServer, WsClient, Value, TempBundle) {
    let bundle = site();
    let server = TestServer::start_with(bundle.path(), |o| o.limits = Some(limits)).await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk", "name": "kiosk"}))
        .await;
    let mut op = server.operator().await;
    op.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    op.recv_type("marked").await;
    let record = kiosk.recv_type("record").await;
    (server, kiosk, record, bundle)
}

/// The answer to `request` (written on a fresh connection, `Connection: close`), read until
/// the server closes: its status and JSON body.
async fn raw(server: &TestServer, request: &[u8]) -> (u16, Value) {
    let mut tcp = TcpStream::connect(server.addr).await.expect("connect");
    tcp.write_all(request).await.expect("write");
    let mut answer = Vec::new();
    let read = tokio::time::timeout(DEADLINE, tcp.read_to_end(&mut answer)).await;
    read.expect("the server answers and closes within the deadline")
        .expect("read");
    let answer = String::from_utf8_lossy(&answer);
    let status = (answer.get(9..12).and_then(|s| s.parse().ok()))
        .unwrap_or_else(|| panic!("not an HTTP answer: {answer:?}"));
    let body = answer.split_once("\r\n\r\n").map_or("", |(_, b)| b);
    (status, serde_json::from_str(body).unwrap_or(Value::Null))
}

/// A chunk upload's head, announcing `length` body bytes (chunked when `None`).
fn head(record: &Value, seq: u64, token: &str, length: Option<usize>) -> String {
    let framing = match length {
        Some(n) => format!("Content-Length: {n}"),
        None => "Transfer-Encoding: chunked".to_owned(),
    };
    format!(
        "PUT {}{seq} HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer {token}\r\n{framing}\r\n\
         Connection: close\r\n\r\n",
        record["upload"].as_str().expect("upload address")
    )
}

async fn put(server: &TestServer, record: &Value, seq: u64, body: Vec<u8>) -> (u16, Value) {
    let url = server.url(&format!("{}{seq}", record["upload"].as_str().unwrap()));
    let response = reqwest::Client::new()
        .put(url)
        .bearer_auth(record["token"].as_str().unwrap())
        .body(body)
        .send()
        .await
        .expect("PUT");
    let status = response.status().as_u16();
    (status, response.json().await.unwrap_or(Value::Null))
}

#[tokio::test]
async fn an_upload_without_its_token_is_refused_before_its_body_arrives() {
    let (server, _kiosk, record, _bundle) = recording(ConnectionLimits::default()).await;
    // Headers announcing a body that never comes: the answer cannot wait for it.
    for token in ["not-the-token", common::OPERATOR_TOKEN] {
        let request = head(&record, 0, token, Some(MIB));
        let (status, body) = raw(&server, request.as_bytes()).await;
        assert_eq!((status, body["code"].as_str()), (401, Some("unauthorized")));
    }
    // Nothing was stored: chunk 0 is still the one expected.
    assert_eq!(put(&server, &record, 0, b"HEAD".to_vec()).await.0, 200);
    server.stop().await;
}

#[tokio::test]
async fn a_chunk_up_to_the_limit_the_record_frame_gives_is_stored_and_one_over_is_a_json_413() {
    let (server, _kiosk, record, _bundle) = recording(ConnectionLimits::default()).await;
    let limit = record["max_chunk_bytes"]
        .as_u64()
        .expect("the record frame says the limit");
    assert_eq!(limit as usize, 8 * MIB);
    assert_eq!(limit as usize, docent::recording::MAX_CHUNK_BYTES);
    // Over the 2 MiB the framework allows by default: stored.
    let (status, stored) = put(&server, &record, 0, vec![7; 3 * MIB]).await;
    assert_eq!(
        (status, &stored["acked"]),
        (200, &json!(3 * MIB)),
        "{stored}"
    );
    let (status, stored) = put(&server, &record, 1, vec![8; 8 * MIB]).await;
    assert_eq!(
        (status, &stored["acked"]),
        (200, &json!(11 * MIB)),
        "{stored}"
    );
    // One byte over, announced by Content-Length: refused at once (the body never comes), in
    // JSON, with the limit.
    let token = record["token"].as_str().unwrap();
    let request = head(&record, 2, token, Some(8 * MIB + 1));
    let (status, refused) = raw(&server, request.as_bytes()).await;
    assert_eq!(status, 413, "{refused}");
    assert_eq!(refused["code"], "body-too-large");
    let message = refused["error"].as_str().unwrap();
    assert!(message.contains("8 MiB"), "{message}");
    // Chunked, with no length said: refused once the bytes pass the limit.
    let mut request = head(&record, 2, token, None).into_bytes();
    let piece = vec![b'x'; MIB];
    for _ in 0..9 {
        request.extend_from_slice(format!("{:x}\r\n", piece.len()).as_bytes());
        request.extend_from_slice(&piece);
        request.extend_from_slice(b"\r\n");
    }
    request.extend_from_slice(b"0\r\n\r\n");
    let (status, refused) = raw(&server, &request).await;
    assert_eq!(
        (status, refused["code"].as_str()),
        (413, Some("body-too-large"))
    );
    // Nothing of the refused chunks was stored.
    let (status, stored) = put(&server, &record, 2, b"TAIL".to_vec()).await;
    assert_eq!((status, &stored["acked"]), (200, &json!(11 * MIB + 4)));
    server.stop().await;
}

#[tokio::test]
async fn a_chunk_body_not_complete_within_the_limit_is_answered_408() {
    let limits = ConnectionLimits {
        body_timeout: Duration::from_millis(300),
        ..ConnectionLimits::default()
    };
    let (server, _kiosk, record, _bundle) = recording(limits).await;
    let mut request = head(&record, 0, record["token"].as_str().unwrap(), Some(100));
    request.push_str("only ten b");
    let (status, body) = raw(&server, request.as_bytes()).await;
    assert_eq!(
        (status, body["code"].as_str()),
        (408, Some("body-timeout")),
        "{body}"
    );
    assert_eq!(put(&server, &record, 0, b"HEAD".to_vec()).await.0, 200);
    server.stop().await;
}
