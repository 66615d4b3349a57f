//! A kiosk whose tab crashed: its connection vanishes without a close frame, and `client.left`
//! says it was `lost` (with the kiosk's name), on an operator's stream and in the corpus; so
//! does one its browser closed with 1001 (going away: what Chromium sends for a crashed tab);
//! one that closed with a close frame of its own (1000) says `closed`. And the probe a kiosk PC's watchdog asks,
//! `GET /healthz?role=kiosk&name=NAME`: `503` while no such kiosk is connected, `200` once it
//! is, `400` for a question it cannot answer.

use crate::common;

use common::{TestServer, WsClient, bundle};
use futures_util::{SinkExt, StreamExt};
use serde_json::{Value, json};
use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::tungstenite::protocol::CloseFrame;
use tokio_tungstenite::tungstenite::protocol::frame::coding::CloseCode;
use tokio_tungstenite::{WebSocketStream, client_async};

async fn fig4() -> TestServer {
    TestServer::start(&bundle("tests/fixtures/fig4-verbatim")).await
}

/// A kiosk named `name` over a plain TCP stream the test can reset, after its `welcome`.
async fn kiosk(server: &TestServer, name: &str) -> WebSocketStream<TcpStream> {
    let tcp = TcpStream::connect(server.addr).await.expect("connect");
    let url = format!("ws://{}/ws", server.addr);
    let (mut ws, _) = client_async(url, tcp).await.expect("websocket");
    let hello = json!({"type": "hello", "role": "kiosk", "name": name});
    ws.send(Message::text(hello.to_string()))
        .await
        .expect("hello");
    while let Some(message) = ws.next().await {
        if let Message::Text(text) = message.expect("frame") {
            let frame: Value = serde_json::from_str(&text).expect("JSON");
            if frame["type"] == "welcome" {
                return ws;
            }
        }
    }
    panic!("closed before its welcome");
}

/// Waits for `name`'s `client.connected` on `op`; returns its client id.
async fn connected(op: &mut WsClient, name: &str) -> Value {
    let joined = op
        .event_where(|e| e["type"] == "client.connected" && e["name"] == name)
        .await;
    joined["client"].clone()
}

/// The `client.left` of client `id`, on `op`'s stream and in the corpus (after stopping).
async fn left(server: TestServer, op: &mut WsClient, id: &Value) -> (Value, Value) {
    let live = op
        .event_where(|e| e["type"] == "client.left" && e["client"] == *id)
        .await;
    let corpus = server.stop().await;
    let logged = (corpus.into_iter())
        .find(|e| e["type"] == "client.left" && e["client"] == *id)
        .expect("client.left in the corpus");
    (live, logged)
}

#[tokio::test]
async fn a_kiosk_whose_connection_ends_without_a_close_frame_is_lost() {
    let server = fig4().await;
    let mut op = server.operator().await;
    let ws = kiosk(&server, "entrance").await;
    let id = connected(&mut op, "entrance").await;
    // What a crashed tab's connection looks like to the server: the stream just ends.
    drop(ws);
    let (live, logged) = left(server, &mut op, &id).await;
    for event in [&live, &logged] {
        assert_eq!(event["ended"], "lost", "{event}");
        assert_eq!(event["name"], "entrance", "{event}");
        assert_eq!(event["role"], "kiosk", "{event}");
        assert_eq!(event["reason"], "connection lost", "{event}");
        assert!(event.get("code").is_none(), "{event}");
    }
}

#[tokio::test]
async fn a_kiosk_whose_connection_is_reset_is_lost() {
    let server = fig4().await;
    let mut op = server.operator().await;
    let ws = kiosk(&server, "hall").await;
    let id = connected(&mut op, "hall").await;
    // A killed browser, or a network that failed: a reset, no close frame.
    ws.get_ref().set_zero_linger().expect("SO_LINGER");
    drop(ws);
    let (live, logged) = left(server, &mut op, &id).await;
    assert_eq!(
        (&live["ended"], &logged["ended"]),
        (&json!("lost"), &json!("lost"))
    );
}

#[tokio::test]
async fn a_kiosk_that_closes_with_a_close_frame_is_closed() {
    let server = fig4().await;
    let mut op = server.operator().await;
    let mut ws = kiosk(&server, "entrance").await;
    let id = connected(&mut op, "entrance").await;
    // A page of Docent's reloading closes its socket with 1000.
    let normal = CloseFrame {
        code: CloseCode::Normal,
        reason: "page closed".into(),
    };
    ws.close(Some(normal)).await.expect("close");
    let (live, logged) = left(server, &mut op, &id).await;
    for event in [&live, &logged] {
        assert_eq!(event["ended"], "closed", "{event}");
        assert_eq!(event["reason"], "closed by client", "{event}");
        assert_eq!(event["name"], "entrance", "{event}");
    }
}

#[tokio::test]
async fn a_kiosk_whose_browser_closes_it_going_away_is_lost() {
    let server = fig4().await;
    let mut op = server.operator().await;
    let mut ws = kiosk(&server, "entrance").await;
    let id = connected(&mut op, "entrance").await;
    // What Chromium sends for a tab that crashed: 1001, no reason; Docent's own pages close
    // with 1000 when they leave on purpose.
    let away = CloseFrame {
        code: CloseCode::Away,
        reason: "".into(),
    };
    ws.close(Some(away)).await.expect("close");
    let (live, logged) = left(server, &mut op, &id).await;
    for event in [&live, &logged] {
        assert_eq!(event["ended"], "lost", "{event}");
        assert_eq!(event["name"], "entrance", "{event}");
        assert!(event.get("code").is_none(), "{event}");
    }
}

#[tokio::test]
async fn clients_closed_at_shutdown_were_ended_by_the_server() {
    let server = fig4().await;
    let _ws = kiosk(&server, "entrance").await;
    let corpus = server.stop().await;
    let left = (corpus.iter())
        .find(|e| e["type"] == "client.left" && e["role"] == "kiosk")
        .expect("client.left");
    assert_eq!(
        (&left["ended"], &left["code"]),
        (&json!("server"), &json!(1001))
    );
}

/// GET `path` without any credential: status and JSON body.
async fn get(server: &TestServer, path: &str) -> (u16, Value) {
    let answer = reqwest::get(server.url(path)).await.expect("GET");
    let status = answer.status().as_u16();
    (status, answer.json().await.expect("JSON body"))
}

#[tokio::test]
async fn the_watchdogs_probe_says_503_until_the_kiosk_is_connected_then_200() {
    let server = fig4().await;
    let mut op = server.operator().await;
    let probe = "/healthz?role=kiosk&name=entrance";
    let (status, none) = get(&server, probe).await;
    assert_eq!(status, 503, "{none}");
    assert_eq!(
        (&none["connected"], &none["since"]),
        (&json!(0), &json!("start"))
    );
    assert!(none["none_for_ms"].is_u64(), "{none}");
    // Another kiosk is not this one.
    let other = kiosk(&server, "hall").await;
    assert_eq!(get(&server, probe).await.0, 503);
    let ws = kiosk(&server, "entrance").await;
    let (status, one) = get(&server, probe).await;
    assert_eq!(status, 200, "{one}");
    assert_eq!(
        (&one["connected"], &one["name"]),
        (&json!(1), &json!("entrance"))
    );
    // Any kiosk, without a name.
    let (status, any) = get(&server, "/healthz?role=kiosk").await;
    assert_eq!((status, &any["connected"]), (200, &json!(2)));
    drop(ws);
    // The kiosk is forgotten before its `client.left` is published.
    op.event_where(|e| e["type"] == "client.left" && e["name"] == "entrance")
        .await;
    let (status, gone) = get(&server, probe).await;
    assert_eq!((status, &gone["since"]), (503, &json!("left")), "{gone}");
    // Plain /healthz is as it was.
    let (status, health) = get(&server, "/healthz").await;
    assert_eq!((status, &health["status"]), (200, &json!("ok")));
    assert!(health.get("connected").is_none(), "{health}");
    drop(other);
    server.stop().await;
}

#[tokio::test]
async fn a_probe_it_cannot_answer_is_a_400_with_the_apis_error_body() {
    let server = fig4().await;
    for path in [
        "/healthz?role=robot",
        "/healthz?name=entrance",
        "/healthz?role=kiosk&colour=red",
        "/healthz?role=kiosk&name=",
        "/healthz?role=kiosk&name=a%0Ab",
        "/healthz?role=kiosk&role=projector",
    ] {
        let (status, body) = get(&server, path).await;
        assert_eq!(status, 400, "{path}: {body}");
        assert_eq!(body["code"], "bad-request", "{path}: {body}");
        assert!(
            body["error"]
                .as_str()
                .is_some_and(|e| e.contains("/healthz?role=")),
            "{body}"
        );
    }
    server.stop().await;
}
