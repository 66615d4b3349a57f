//! The server's limits come from the bundle's `docent.yaml` (`server:`): a lowered
//! per-address cap refuses the next connection from that address with `503
//! too-many-connections` while other addresses are served, and `GET /api/state` reports the
//! limits in force. Raw TCP from several loopback addresses, so each client's address is
//! known to the test.

use crate::common;

use std::net::SocketAddr;

use common::{DEADLINE, OPERATOR_TOKEN, TempBundle, TestServer};
use serde_json::{Value, json};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpSocket, TcpStream};

/// A bundle whose `docent.yaml` sets `server:` to `settings`.
fn bundle_with(settings: &str) -> TempBundle {
    TempBundle::new("- Label: WELCOME\n  Text: [Welcome.]\n")
        .with_file("docent.yaml", &format!("server:\n{settings}"))
}

/// A TCP connection to `addr` from the loopback address `from`.
async fn connect_from(from: &str, addr: SocketAddr) -> TcpStream {
    let socket = TcpSocket::new_v4().expect("socket");
    socket
        .bind(format!("{from}:0").parse().expect("address"))
        .expect("bind");
    socket.connect(addr).await.expect("connect")
}

/// The status and JSON body the server answers on `tcp` before closing it.
async fn answer_until_closed(tcp: &mut TcpStream) -> (u16, Value) {
    let mut answer = Vec::new();
    let read = tokio::time::timeout(DEADLINE, tcp.read_to_end(&mut answer)).await;
    read.expect("the server closes within the deadline")
        .expect("read");
    let answer = String::from_utf8_lossy(&answer);
    let status = (answer.get(9..12).and_then(|s| s.parse().ok()))
        .unwrap_or_else(|| panic!("not an HTTP answer: {answer:?}"));
    let body = answer.split_once("\r\n\r\n").map_or("", |(_, b)| b);
    (status, serde_json::from_str(body).unwrap_or(Value::Null))
}

/// `GET /api/state`'s `limits`, asked from `from` on a connection closed after it.
async fn limits_from(from: &str, addr: SocketAddr) -> Value {
    let mut tcp = connect_from(from, addr).await;
    let request = format!(
        "GET /api/state HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer {OPERATOR_TOKEN}\r\n\
         Connection: close\r\n\r\n"
    );
    tcp.write_all(request.as_bytes()).await.expect("write");
    let (status, state) = answer_until_closed(&mut tcp).await;
    assert_eq!(status, 200, "{state}");
    state["limits"].clone()
}

#[tokio::test]
async fn a_per_address_cap_of_two_from_docent_yaml_refuses_the_third_connection() {
    let bundle = bundle_with("  connections: {per_address: 2}\n");
    let server = TestServer::start(bundle.path()).await;
    // Two connections from one address hold their places with requests never finished.
    let mut held = Vec::new();
    for _ in 0..2 {
        let mut tcp = connect_from("127.0.0.1", server.addr).await;
        tcp.write_all(b"GET /healthz HTTP/1.1\r\n").await.unwrap();
        held.push(tcp);
    }
    let mut third = connect_from("127.0.0.1", server.addr).await;
    let (status, body) = answer_until_closed(&mut third).await;
    assert_eq!(
        (status, body["code"].as_str()),
        (503, Some("too-many-connections")),
        "{body}"
    );
    // Another address is served meanwhile, and is told the limits in force.
    let limits = limits_from("127.0.0.2", server.addr).await;
    assert_eq!(
        limits["connections"],
        json!({"per_address": 2, "total": 1024})
    );
    drop(held);
    server.stop().await;
}

#[tokio::test]
async fn api_state_reports_each_limit_docent_yaml_sets() {
    let bundle = bundle_with(
        "  connections: {per_address: 300, total: 2000}\n  timeouts: {headers: 10s, body: \
         1m}\n  messages: {max_size: 64 KiB}\n  queues: {per_client: 512}\n",
    );
    let server = TestServer::start(bundle.path()).await;
    let limits = limits_from("127.0.0.1", server.addr).await;
    let open_files = limits["open_files"].clone();
    assert_eq!(
        limits,
        json!({
            "connections": {"per_address": 300, "total": 2000},
            "timeouts": {"headers_ms": 10_000, "body_ms": 60_000},
            "messages": {"max_bytes": 65_536, "max_frame_bytes": 16_384},
            "queues": {"per_client": 512},
            "open_files": open_files,
        })
    );
    // Raised at start-up for 2000 connections, unless this machine's hard limit is lower.
    let hard = rustix::process::getrlimit(rustix::process::Resource::Nofile).maximum;
    if hard.is_none_or(|h| h >= 2000 + docent::http::OWN_FILES) {
        let open = open_files.as_u64();
        assert!(open.is_none_or(|o| o >= 2064), "{open_files}");
    }
    server.stop().await;
}
