//! What the HTTP side takes: bodies that are JSON objects, headers and bodies within their
//! time limits (short ones here, so no test waits 30 s), a bounded number of connections per
//! address and in all, and no request with both `Content-Length` and `Transfer-Encoding`.
//! Raw TCP clients, so that the tests can be as slow and as wrong as an attacker.

use crate::common;

use std::net::SocketAddr;
use std::time::{Duration, Instant};

use common::{DEADLINE, OPERATOR_TOKEN, TestApp, TestServer, bundle};
use docent::http::ConnectionLimits;
use serde_json::{Value, json};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpSocket, TcpStream};

const TRIGGER: &str = "/api/acts/WELCOME/trigger";

async fn server_with(limits: ConnectionLimits) -> TestServer {
    TestServer::start_with(&bundle("tests/fixtures/fig4-verbatim"), |o| {
        o.limits = Some(limits);
    })
    .await
}

/// A TCP connection to `addr` from the loopback address `from`.
async fn connect_from(from: &str, addr: SocketAddr) -> TcpStream {
    let socket = TcpSocket::new_v4().expect("socket");
    socket
        .bind(format!("{from}:0").parse().expect("address"))
        .expect("bind");
    socket.connect(addr).await.expect("connect")
}

/// Everything the server sends until it closes the connection.
async fn read_to_close(tcp: &mut TcpStream) -> String {
    let mut answer = Vec::new();
    let read = tokio::time::timeout(DEADLINE, tcp.read_to_end(&mut answer)).await;
    read.expect("the server closes within the deadline")
        .expect("read");
    String::from_utf8_lossy(&answer).into_owned()
}

/// The status code and JSON body of a raw HTTP answer.
fn status_and_body(answer: &str) -> (u16, Value) {
    let status = answer
        .get(9..12)
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("not an HTTP answer: {answer:?}"));
    let body = answer.split_once("\r\n\r\n").map_or("", |(_, b)| b);
    (status, serde_json::from_str(body).unwrap_or(Value::Null))
}

/// Sends `request` on a fresh connection and reads the answer until the server closes.
async fn raw(addr: SocketAddr, request: &str) -> (u16, Value) {
    let mut tcp = connect_from("127.0.0.1", addr).await;
    tcp.write_all(request.as_bytes()).await.expect("write");
    status_and_body(&read_to_close(&mut tcp).await)
}

#[tokio::test]
async fn bodies_that_are_not_json_objects_are_refused_and_trigger_nothing() {
    // What a body says needs no connection: asked of the route table in process.
    let server = TestApp::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    for body in [
        json!(["TextChild", true, "ref"]),
        json!(42),
        json!("TextChild"),
    ] {
        let (status, answer) = server.post(TRIGGER, Some(body.clone())).await;
        assert_eq!(
            (status, answer["code"].as_str()),
            (400, Some("body-not-object")),
            "{body}: {answer}"
        );
        let (status, answer) = server.put("/api/context", body.clone()).await;
        assert_eq!(
            (status, answer["code"].as_str()),
            (400, Some("body-not-object"))
        );
    }
    let (status, answer) = server.post(TRIGGER, Some(json!(["TextChild"]))).await;
    assert!(
        answer["error"].as_str().unwrap().contains("it is an array"),
        "{status} {answer}"
    );
    // An object, and no body at all, still trigger.
    assert_eq!(server.post(TRIGGER, Some(json!({"ref": "a"}))).await.0, 202);
    assert_eq!(server.post(TRIGGER, None).await.0, 202);
    let corpus = server.stop().await;
    let triggered = corpus
        .iter()
        .filter(|e| e["type"] == "act.triggered")
        .count();
    assert_eq!(triggered, 2);
}

#[tokio::test]
async fn headers_not_complete_within_the_limit_close_the_connection() {
    let limit = Duration::from_millis(300);
    let server = server_with(ConnectionLimits {
        header_timeout: limit,
        ..ConnectionLimits::default()
    })
    .await;
    // Silent after half a request line.
    let started = Instant::now();
    let mut silent = connect_from("127.0.0.1", server.addr).await;
    silent
        .write_all(b"GET /healthz HTTP/1.1\r\nHost: x\r\n")
        .await
        .unwrap();
    let answer = read_to_close(&mut silent).await;
    assert!(started.elapsed() >= limit);
    assert!(
        answer.is_empty() || answer.starts_with("HTTP/1.1 408"),
        "{answer:?}"
    );
    // Trickling one header byte at a time keeps nothing open either.
    let started = Instant::now();
    let mut trickle = connect_from("127.0.0.1", server.addr).await;
    trickle
        .write_all(b"GET /healthz HTTP/1.1\r\n")
        .await
        .unwrap();
    let mut pace = tokio::time::interval(limit / 6);
    let closed = loop {
        pace.tick().await;
        if trickle.write_all(b"X").await.is_err() {
            break started.elapsed();
        }
        let mut byte = [0u8; 1];
        // A read that is ready at once means the server answered or closed.
        if let Ok(read) = tokio::time::timeout(Duration::ZERO, trickle.read(&mut byte)).await {
            assert!(matches!(read, Ok(0) | Ok(1) | Err(_)));
            break started.elapsed();
        }
        assert!(
            started.elapsed() < DEADLINE,
            "the trickle was never cut off"
        );
    };
    assert!(closed >= limit, "{closed:?}");
    // Others are served meanwhile, and an idle keep-alive connection is closed after the
    // limit too (`raw` reads until the server closes).
    let (status, _) = raw(server.addr, "GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n").await;
    assert_eq!(status, 200);
    server.stop().await;
}

#[tokio::test]
async fn a_body_not_complete_within_the_limit_is_answered_408() {
    let server = server_with(ConnectionLimits {
        body_timeout: Duration::from_millis(300),
        ..ConnectionLimits::default()
    })
    .await;
    let mut tcp = connect_from("127.0.0.1", server.addr).await;
    let head = format!(
        "POST {TRIGGER} HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer {OPERATOR_TOKEN}\r\n\
         Content-Length: 40\r\nConnection: close\r\n\r\n{{\"ref\":"
    );
    tcp.write_all(head.as_bytes()).await.unwrap();
    let (status, body) = status_and_body(&read_to_close(&mut tcp).await);
    assert_eq!(
        (status, body["code"].as_str()),
        (408, Some("body-timeout")),
        "{body}"
    );
    let corpus = server.stop().await;
    assert!(!corpus.iter().any(|e| e["type"] == "act.triggered"));
}

#[tokio::test]
async fn half_open_connections_from_one_address_do_not_starve_the_others() {
    let server = server_with(ConnectionLimits {
        per_address: 4,
        total: 8,
        ..ConnectionLimits::default()
    })
    .await;
    // An attacker holds its four places with requests it never finishes.
    let mut held = Vec::new();
    for _ in 0..4 {
        let mut tcp = connect_from("127.0.0.2", server.addr).await;
        tcp.write_all(b"GET / HTTP/1.1\r\n").await.unwrap();
        held.push(tcp);
    }
    // Its fifth is answered 503 at once, and the local operator is still served.
    let mut fifth = connect_from("127.0.0.2", server.addr).await;
    let (status, body) = status_and_body(&read_to_close(&mut fifth).await);
    assert_eq!(
        (status, body["code"].as_str()),
        (503, Some("too-many-connections"))
    );
    assert!(
        body["error"].as_str().unwrap().contains("one address"),
        "{body}"
    );
    let (status, _) = raw(
        server.addr,
        "GET /healthz HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n",
    )
    .await;
    assert_eq!(status, 200);
    // Open websockets keep their places too.
    let mut sockets = Vec::new();
    for _ in 0..2 {
        let tcp = connect_from("127.0.0.3", server.addr).await;
        let url = format!("ws://{}/ws", server.addr);
        let (ws, _) = tokio_tungstenite::client_async(url, tcp)
            .await
            .expect("websocket");
        sockets.push(ws);
    }
    for _ in 0..2 {
        let mut tcp = connect_from("127.0.0.3", server.addr).await;
        tcp.write_all(b"GET / HTTP/1.1\r\n").await.unwrap();
        held.push(tcp);
    }
    // Eight open in all: the total protects the server itself, for everyone.
    let mut over = connect_from("127.0.0.4", server.addr).await;
    let (status, body) = status_and_body(&read_to_close(&mut over).await);
    assert_eq!(
        (status, body["code"].as_str()),
        (503, Some("too-many-connections"))
    );
    // Shutting down does not wait for the half-open connections' header time limit.
    let stopping = Instant::now();
    server.stop().await;
    assert!(
        stopping.elapsed() < Duration::from_secs(10),
        "{:?}",
        stopping.elapsed()
    );
    drop(held);
    drop(sockets);
}

#[tokio::test]
async fn a_request_with_content_length_and_transfer_encoding_is_refused() {
    let server = TestServer::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    let smuggled = "GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n";
    for (first, second) in [
        ("Content-Length: 5", "Transfer-Encoding: chunked"),
        ("Transfer-Encoding: chunked", "Content-Length: 5"),
    ] {
        let request = format!(
            "POST {TRIGGER} HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer {OPERATOR_TOKEN}\r\n\
             {first}\r\n{second}\r\n\r\n0\r\n\r\n{smuggled}"
        );
        let (status, body) = raw(server.addr, &request).await;
        assert_eq!(
            (status, body["code"].as_str()),
            (400, Some("conflicting-length")),
            "{first}"
        );
    }
    let two_lengths = format!(
        "POST {TRIGGER} HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer {OPERATOR_TOKEN}\r\n\
         Content-Length: 2\r\nContent-Length: 4\r\n\r\n{{}}{{}}"
    );
    assert_eq!(raw(server.addr, &two_lengths).await.0, 400);
    let corpus = server.stop().await;
    assert!(
        !corpus.iter().any(|e| e["type"] == "act.triggered"),
        "nothing ran"
    );
}

#[tokio::test]
async fn three_hundred_half_open_connections_leave_the_operator_served_at_the_default_limits() {
    let server = server_with(ConnectionLimits::default()).await;
    let per_address = ConnectionLimits::default().per_address;
    let mut held = Vec::new();
    let mut refused = 0;
    for _ in 0..300 {
        let mut tcp = connect_from("127.0.0.2", server.addr).await;
        if held.len() < per_address {
            tcp.write_all(b"GET / HTTP/1.1\r\nHost: x\r\n")
                .await
                .unwrap();
            held.push(tcp);
        } else {
            let (status, _) = status_and_body(&read_to_close(&mut tcp).await);
            refused += usize::from(status == 503);
        }
    }
    assert_eq!(refused, 300 - per_address);
    let started = Instant::now();
    let (status, _) = raw(
        server.addr,
        "GET /healthz HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n",
    )
    .await;
    assert_eq!(status, 200);
    eprintln!(
        "operator's request under {} half-open connections: {:?}",
        held.len(),
        started.elapsed()
    );
    drop(held);
    server.stop().await;
}

#[tokio::test]
async fn a_body_no_route_reads_does_not_hold_its_connection() {
    let server = server_with(ConnectionLimits {
        body_timeout: Duration::from_millis(300),
        header_timeout: Duration::from_millis(300),
        ..ConnectionLimits::default()
    })
    .await;
    // Answered without its body; a body that never completes cannot keep the place.
    for path in ["GET /healthz", "POST /api/stop", "GET /report"] {
        let mut tcp = connect_from("127.0.0.1", server.addr).await;
        let head = format!(
            "{path} HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer {OPERATOR_TOKEN}\r\n\
             Content-Length: 1000\r\n\r\nonly a little"
        );
        tcp.write_all(head.as_bytes()).await.unwrap();
        let answer = read_to_close(&mut tcp).await;
        assert!(answer.starts_with("HTTP/1.1 2"), "{path}: {answer:?}");
    }
    server.stop().await;
}

#[tokio::test]
async fn a_body_over_the_limit_is_a_json_413_whether_its_length_is_said_or_not() {
    let server = TestServer::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    let limit = docent::http::MAX_BODY_BYTES;
    // Said by Content-Length: the body never comes; the answer cannot wait for it.
    let said = format!(
        "POST {TRIGGER} HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer {OPERATOR_TOKEN}\r\n\
         Content-Length: {}\r\nConnection: close\r\n\r\n",
        limit + 1
    );
    let (status, body) = raw(server.addr, &said).await;
    assert_eq!(
        (status, body["code"].as_str()),
        (413, Some("body-too-large")),
        "{body}"
    );
    assert!(
        body["error"].as_str().is_some_and(|e| !e.is_empty()),
        "{body}"
    );
    // Chunked: refused once the bytes pass the limit.
    let mut chunked = format!(
        "POST {TRIGGER} HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer {OPERATOR_TOKEN}\r\n\
         Transfer-Encoding: chunked\r\nConnection: close\r\n\r\n"
    );
    let piece = " ".repeat(1024);
    for _ in 0..=limit / 1024 {
        chunked.push_str(&format!("400\r\n{piece}\r\n"));
    }
    chunked.push_str("0\r\n\r\n");
    let (status, body) = raw(server.addr, &chunked).await;
    assert_eq!(
        (status, body["code"].as_str()),
        (413, Some("body-too-large")),
        "{body}"
    );
    let corpus = server.stop().await;
    assert!(!corpus.iter().any(|e| e["type"] == "act.triggered"));
}
