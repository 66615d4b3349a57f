//! A client that sends faster than it reads is slowed down, never cut off: its own answers
//! hold back the reading of its frames (TCP back-pressure), and every trigger it sent is
//! answered. A subscriber that cannot keep up with the broadcasts is closed with a status code
//! and a reason, which the log and the corpus keep.

use crate::common;

use common::{DEADLINE, TempBundle, TestServer, within};
use futures_util::{SinkExt, StreamExt};
use serde_json::{Value, json};
use tokio::net::{TcpSocket, TcpStream};
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::{WebSocketStream, client_async, connect_async};

const ACTS: &str = "- Label: OK\n  Cmds: [DISPLAY_PAGE index.html]\n";

fn bundle() -> TempBundle {
    TempBundle::new(ACTS)
        .with_file("pages/index.html", "<!doctype html><title>home</title>")
        .with_file("docent.yaml", "speech: {adapter: log}\n")
}

/// What a connection ended with, as its client saw it.
#[derive(Debug, PartialEq)]
enum Ended {
    /// Still open: every expected answer arrived.
    Open,
    /// A close frame with its code and reason.
    Closed(u16, String),
    /// The connection ended without a close frame (a client sees 1006).
    Dropped(String),
}

/// Sends `total` triggers in bursts of `burst` from an operator (who gets every event too),
/// reading concurrently or, with `sent_first`, only once everything is sent; returns how many
/// were answered and how the connection ended.
async fn bursts(
    server: &TestServer,
    total: usize,
    burst: usize,
    sent_first: bool,
) -> (usize, Ended) {
    let (ws, _) = connect_async(format!("ws://{}/ws", server.addr))
        .await
        .unwrap();
    let (mut tx, mut rx) = ws.split();
    let hello = json!({"type": "hello", "role": "operator", "name": "burst", "token": common::OPERATOR_TOKEN});
    tx.send(Message::text(hello.to_string())).await.unwrap();
    let reader = async move {
        let mut answered = 0;
        let mut welcomed = false;
        loop {
            if welcomed && answered == total {
                return (answered, Ended::Open);
            }
            let next = match within(DEADLINE, rx.next()).await {
                Ok(next) => next,
                Err(_) => {
                    panic!("{answered} of {total} answered, then nothing within the deadline")
                }
            };
            match next {
                Some(Ok(Message::Text(text))) => {
                    let frame: Value = serde_json::from_str(&text).unwrap();
                    match frame["type"].as_str() {
                        Some("welcome") => welcomed = true,
                        Some("triggered") => answered += 1,
                        Some("error") => panic!("an error instead of an answer: {frame}"),
                        _ => {}
                    }
                }
                Some(Ok(Message::Close(Some(close)))) => {
                    return (
                        answered,
                        Ended::Closed(close.code.into(), close.reason.to_string()),
                    );
                }
                Some(Ok(Message::Close(None))) => {
                    return (answered, Ended::Closed(1005, String::new()));
                }
                Some(Err(e)) => return (answered, Ended::Dropped(e.to_string())),
                None => return (answered, Ended::Dropped("the stream ended".into())),
                Some(Ok(_)) => {}
            }
        }
    };
    let sender = async move {
        for start in (0..total).step_by(burst) {
            for i in start..(start + burst).min(total) {
                let frame = json!({"type": "trigger", "label": "OK", "ref": format!("r{i}")});
                if tx.feed(Message::text(frame.to_string())).await.is_err() {
                    return tx;
                }
            }
            if tx.flush().await.is_err() {
                return tx;
            }
        }
        tx
    };
    if sent_first {
        let _tx = within(DEADLINE, sender)
            .await
            .expect("everything sent within the deadline");
        reader.await
    } else {
        tokio::join!(reader, sender).0
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_operator_sending_bursts_while_it_reads_gets_every_answer() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    for burst in [10, 50, 500] {
        let (answered, ended) = bursts(&server, 3000, burst, false).await;
        assert_eq!((answered, ended), (3000, Ended::Open), "bursts of {burst}");
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_client_that_sends_everything_before_reading_gets_its_welcome_and_every_answer() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let (answered, ended) = bursts(&server, 3000, 3000, true).await;
    assert_eq!((answered, ended), (3000, Ended::Open));
}

/// An operator connection whose socket holds little (a 4 KiB receive buffer), so that what the
/// server sends it waits in the server as soon as it reads slower than events come.
async fn small_buffered_operator(server: &TestServer) -> WebSocketStream<TcpStream> {
    let socket = TcpSocket::new_v4().unwrap();
    socket.set_recv_buffer_size(4096).unwrap();
    let tcp = socket.connect(server.addr).await.unwrap();
    let (mut ws, _) = client_async(format!("ws://{}/ws", server.addr), tcp)
        .await
        .unwrap();
    let hello = json!({"type": "hello", "role": "operator", "name": "slow", "token": common::OPERATOR_TOKEN});
    ws.send(Message::text(hello.to_string())).await.unwrap();
    ws
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_subscriber_that_falls_behind_the_events_is_closed_with_1013_and_a_reason() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut slow = small_buffered_operator(&server).await;
    // A dialog manager's triggers make three events each; after each round of 100 the slow
    // operator reads 50 frames: it never stops reading (so no write to it waits long), but
    // falls behind by about 250 events a round, until it is more than the channel holds.
    let mut dm = server.client(json!({"type": "hello", "role": "dm"})).await;
    // What the kernel buffers for it comes first (a few MB: `tcp_wmem`), then the channel.
    let most_rounds = 1000;
    let mut close = None;
    'rounds: for round in 0..most_rounds {
        for i in 0..100 {
            let frame = json!({"type": "trigger", "label": "OK", "ref": format!("{round}-{i}")});
            dm.send(frame).await;
        }
        for _ in 0..100 {
            dm.recv_type("triggered").await;
        }
        for _ in 0..50 {
            let next = within(DEADLINE, slow.next())
                .await
                .expect("a frame in time");
            match next {
                Some(Ok(Message::Close(frame))) => {
                    close = Some(frame.expect("a close frame with a code"));
                    break 'rounds;
                }
                Some(Ok(_)) => {}
                other => panic!("no close frame: {other:?}"),
            }
        }
    }
    let close = close.expect("closed within 100,000 triggers");
    assert_eq!(u16::from(close.code), 1013, "{close:?}");
    assert!(
        close.reason.starts_with("too slow: fell ") && close.reason.contains("reconnect"),
        "{close:?}"
    );
    let log = server.stop().await;
    let joined = (log.iter())
        .find(|e| e["type"] == "client.connected" && e["name"] == "slow")
        .expect("the slow operator joined");
    let left = (log.iter())
        .find(|e| e["type"] == "client.left" && e["client"] == joined["client"])
        .expect("the slow operator's leaving is in the corpus");
    assert_eq!(
        (left["reason"].as_str(), left["code"].as_u64()),
        (Some("too slow: fell behind the event stream"), Some(1013)),
        "{left}"
    );
}
