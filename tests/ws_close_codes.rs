//! Websocket protocol violations are answered with their RFC 6455 close code before the
//! server closes: 1007 for a text message that is not UTF-8, 1002 for a reserved opcode or
//! reserved bits, 1009 for a message over 1 MiB, 1008 for a client without a credential that
//! pings beyond its allowance (and never reads the pongs). Frames are written by hand over raw TCP,
//! since a websocket library will not send broken ones.

use crate::common;

use common::{DEADLINE, TempBundle, TestServer, bundle};
use serde_json::Value;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

/// A raw websocket connection after the opening handshake.
async fn handshake(server: &TestServer) -> TcpStream {
    let mut tcp = TcpStream::connect(server.addr).await.expect("connect");
    let request = format!(
        "GET /ws HTTP/1.1\r\nHost: {}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n\
         Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n",
        server.addr
    );
    tcp.write_all(request.as_bytes()).await.expect("write");
    let mut head = Vec::new();
    while !head.ends_with(b"\r\n\r\n") {
        let mut byte = [0u8; 1];
        tcp.read_exact(&mut byte).await.expect("handshake answer");
        head.push(byte[0]);
    }
    assert!(
        head.starts_with(b"HTTP/1.1 101"),
        "{}",
        String::from_utf8_lossy(&head)
    );
    tcp
}

/// A client frame: `first` is FIN, RSV and opcode; the payload is masked (with a zero mask,
/// which leaves it as is). `length` may claim more than `payload` holds.
fn frame(first: u8, length: u64, payload: &[u8]) -> Vec<u8> {
    let mut out = vec![first];
    match length {
        0..=125 => out.push(0x80 | length as u8),
        126..=0xFFFF => {
            out.push(0x80 | 126);
            out.extend_from_slice(&(length as u16).to_be_bytes());
        }
        _ => {
            out.push(0x80 | 127);
            out.extend_from_slice(&length.to_be_bytes());
        }
    }
    out.extend_from_slice(&[0, 0, 0, 0]);
    out.extend_from_slice(payload);
    out
}

/// Reads server frames until a close frame, returning its code; panics if the connection
/// ends without one.
async fn close_code(tcp: &mut TcpStream) -> u16 {
    let mut received = Vec::new();
    let read = tokio::time::timeout(DEADLINE, tcp.read_to_end(&mut received)).await;
    read.expect("the server closes within the deadline").ok();
    let mut at = 0;
    while at + 2 <= received.len() {
        let (opcode, short) = (received[at] & 0x0F, (received[at + 1] & 0x7F) as usize);
        let (length, start) = match short {
            126 => (
                u16::from_be_bytes([received[at + 2], received[at + 3]]) as usize,
                at + 4,
            ),
            127 => panic!("no server frame here is that long"),
            n => (n, at + 2),
        };
        if opcode == 0x8 {
            assert!(length >= 2, "a close frame without a code");
            return u16::from_be_bytes([received[start], received[start + 1]]);
        }
        at = start + length;
    }
    panic!("closed without a close frame; got {received:?}");
}

async fn violation_closes_with(first: u8, length: u64, payload: &[u8]) -> u16 {
    let server = TestServer::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    let mut tcp = handshake(&server).await;
    tcp.write_all(&frame(first, length, payload))
        .await
        .expect("write");
    let code = close_code(&mut tcp).await;
    server.stop().await;
    code
}

#[tokio::test]
async fn a_text_message_that_is_not_utf8_is_closed_with_1007() {
    assert_eq!(violation_closes_with(0x81, 2, &[0xFF, 0xFE]).await, 1007);
}

#[tokio::test]
async fn a_reserved_opcode_is_closed_with_1002() {
    assert_eq!(violation_closes_with(0x83, 0, &[]).await, 1002);
    assert_eq!(violation_closes_with(0x8B, 0, &[]).await, 1002);
}

#[tokio::test]
async fn reserved_bits_are_closed_with_1002() {
    assert_eq!(violation_closes_with(0xC1, 2, b"{}").await, 1002);
}

#[tokio::test]
async fn a_message_over_one_mebibyte_is_closed_with_1009_and_logged() {
    let server = TestServer::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    let mut tcp = handshake(&server).await;
    let hello = br#"{"type":"hello","role":"kiosk"}"#;
    tcp.write_all(&frame(0x81, hello.len() as u64, hello))
        .await
        .unwrap();
    // The frame header alone announces too much; the server need not wait for the rest.
    tcp.write_all(&frame(0x81, 1024 * 1024 + 1, b"{"))
        .await
        .unwrap();
    assert_eq!(close_code(&mut tcp).await, 1009);
    let corpus = server.stop().await;
    let left: Vec<&Value> = corpus
        .iter()
        .filter(|e| e["type"] == "client.left")
        .collect();
    assert_eq!(left.len(), 1);
    assert_eq!(left[0]["reason"], "message too big");
}

#[tokio::test]
async fn a_message_over_the_bundles_max_size_is_closed_with_1009() {
    let bundle = TempBundle::new("- Label: A\n  Text: [a]\n")
        .with_file("docent.yaml", "server:\n  messages: {max_size: 64 KiB}\n");
    let server = TestServer::start(bundle.path()).await;
    let mut tcp = handshake(&server).await;
    // Within the bundle's limit: answered `frame-too-large`, the connection stays.
    let within = [b' '; 64 * 1024];
    tcp.write_all(&frame(0x81, within.len() as u64, &within))
        .await
        .unwrap();
    let mut answered = Vec::new();
    while !String::from_utf8_lossy(&answered).contains("frame-too-large") {
        let mut chunk = [0u8; 512];
        let read = tokio::time::timeout(DEADLINE, tcp.read(&mut chunk)).await;
        let n = read.expect("answered within the deadline").expect("read");
        assert!(n > 0, "closed instead: {answered:?}");
        answered.extend_from_slice(&chunk[..n]);
    }
    // One byte over it: closed, where the default limit (1 MiB) would have taken it.
    tcp.write_all(&frame(0x81, 64 * 1024 + 1, b"{"))
        .await
        .unwrap();
    assert_eq!(close_code(&mut tcp).await, 1009);
    server.stop().await;
}

/// Writes `count` pings of 100 bytes each, never reading the pongs they ask for. (Just one
/// over the allowance: pings the server never read would make its close a reset, which can
/// lose the close frame on the way.)
/// The pings a client without a credential may send at once (docs/PROTOCOL.md, "Limits").
const PINGS_AT_ONCE: usize = 20;

async fn ping_without_reading(tcp: &mut TcpStream, count: usize) {
    let ping = frame(0x89, 100, &[b'p'; 100]);
    for _ in 0..count {
        if tcp.write_all(&ping).await.is_err() {
            return; // closed meanwhile: what the test waits for
        }
    }
}

#[tokio::test]
async fn a_client_that_pings_and_never_reads_is_closed_with_1008_and_logged() {
    let server = TestServer::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    // One that never said hello.
    let mut silent = handshake(&server).await;
    ping_without_reading(&mut silent, PINGS_AT_ONCE + 1).await;
    assert_eq!(close_code(&mut silent).await, 1008);
    // A kiosk, whose leaving is logged with the reason.
    let mut kiosk = handshake(&server).await;
    let hello = br#"{"type":"hello","role":"kiosk"}"#;
    kiosk
        .write_all(&frame(0x81, hello.len() as u64, hello))
        .await
        .unwrap();
    ping_without_reading(&mut kiosk, PINGS_AT_ONCE + 1).await;
    assert_eq!(close_code(&mut kiosk).await, 1008);
    let corpus = server.stop().await;
    let left: Vec<&Value> = corpus
        .iter()
        .filter(|e| e["type"] == "client.left")
        .collect();
    assert_eq!(left.len(), 1);
    assert_eq!(left[0]["reason"], "too many pings");
}
