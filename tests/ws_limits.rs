//! What a websocket client without a credential (a kiosk, a projector, a connection that has
//! not said hello) may send: a bounded number of logged recording reports and visitor stops
//! per kiosk address, whatever it sends, and a bounded number of frames per connection, the
//! first frame beyond answered `rate-limited`. Real server on 127.0.0.1:0, real clients;
//! each flood is a bounded loop, and the tests wait for answers, never for time.

use crate::common;

use std::time::Instant;

use common::{DEADLINE, TempBundle, TestServer, WsClient};
use docent::access::{KIOSK_BURST, RECORDING_BURST, RECORDING_PER_SECOND};
use serde_json::{Value, json};

fn site() -> TempBundle {
    TempBundle::new("- Label: WELCOME\n  Text: [Hello!]\n")
        .with_file("docent.yaml", "speech: {adapter: log}\n")
        .with_file(
            "pages/index.html",
            r#"<html><body><button data-act="WELCOME">Hello</button></body></html>"#,
        )
}

async fn kiosk(server: &TestServer) -> WsClient {
    server
        .client(json!({"type": "hello", "role": "kiosk", "name": "kiosk"}))
        .await
}

fn count(corpus: &[Value], kind: &str) -> usize {
    corpus.iter().filter(|e| e["type"] == kind).count()
}

/// `test`, which must end within the deadline as a whole: the server's pings would re-arm a
/// deadline kept per frame, and a flood the server does not refuse would then hang.
async fn within_deadline(test: impl std::future::Future<Output = ()>) {
    let ended = tokio::time::timeout(DEADLINE, test).await;
    ended.expect("the test's answers arrive within the deadline");
}

/// Waits for the answer to a `clock` frame: every frame sent before it was handled.
async fn handled(kiosk: &mut WsClient) {
    kiosk.send(json!({"type": "clock", "t0": -1.0})).await;
    kiosk.recv_where(|f| f["type"] == "clock").await;
}

#[tokio::test]
async fn a_kiosk_flooding_recording_failed_makes_a_bounded_number_of_events() {
    within_deadline(async {
        let bundle = site();
        let server = TestServer::start(bundle.path()).await;
        let started = Instant::now();
        // Two connections from one address share its allowance.
        let mut kiosks = [kiosk(&server).await, kiosk(&server).await];
        let flood = 150;
        for kiosk in &mut kiosks {
            for n in 0..flood {
                let frame = json!({"type": "recording-failed", "code": "recorder-error",
                "message": format!("flood {n}")});
                kiosk.send(frame).await;
            }
        }
        let mut refused = 0;
        for kiosk in &mut kiosks {
            handled(kiosk).await;
            kiosk
                .send(json!({"type": "recording-failed", "code": "no-device"}))
                .await;
            let answer = kiosk.recv_type("error").await;
            assert_eq!(answer["code"], "rate-limited", "{answer}");
            refused += 1;
        }
        let seconds = started.elapsed().as_secs_f64();
        drop(kiosks);
        let corpus = server.stop().await;
        let logged = count(&corpus, "recording.failed");
        let most = RECORDING_BURST + (seconds + 1.0) * RECORDING_PER_SECOND;
        assert!(
            logged >= 1 && (logged as f64) <= most,
            "{logged} logged in {seconds} s"
        );
        assert!(logged + refused < 2 * flood);
    })
    .await;
}

#[tokio::test]
async fn a_kiosk_flooding_stop_makes_a_bounded_number_of_stop_events() {
    within_deadline(async {
        let bundle = site();
        let server = TestServer::start(bundle.path()).await;
        let started = Instant::now();
        let mut kiosk = kiosk(&server).await;
        let flood = 100;
        for _ in 0..flood {
            kiosk.send(json!({"type": "stop"})).await;
        }
        let (mut stopped, mut limited) = (0, 0);
        for _ in 0..flood {
            let answer =
                (kiosk.recv_where(|f| f["type"] == "stopped" || f["type"] == "error")).await;
            match (answer["type"].as_str(), answer["code"].as_str()) {
                (Some("stopped"), _) => stopped += 1,
                (Some("error"), Some("rate-limited")) => limited += 1,
                _ => panic!("{answer}"),
            }
        }
        let seconds = started.elapsed().as_secs_f64();
        assert!(limited > 0, "{stopped} stopped, none refused");
        drop(kiosk);
        let corpus = server.stop().await;
        let stops = corpus
            .iter()
            .filter(|e| e["type"] == "stop" && e["source"] == "kiosk")
            .count();
        assert_eq!(stops, stopped);
        assert!(
            (stops as f64) <= KIOSK_BURST + (seconds + 1.0) * 4.0,
            "{stops}"
        );
    })
    .await;
}

#[tokio::test]
async fn frames_beyond_a_connections_allowance_are_dropped_and_the_first_answered() {
    within_deadline(async {
        let bundle = site();
        let server = TestServer::start(bundle.path()).await;
        let mut kiosk = kiosk(&server).await;
        let flood = 1000;
        for n in 0..flood {
            kiosk.send(json!({"type": "clock", "t0": n})).await;
        }
        // Clock answers up to the allowance, then one `rate-limited`, then nothing for the rest.
        let mut answered = 0;
        let refusal = loop {
            let frame = (kiosk.recv_where(|f| f["type"] == "clock" || f["type"] == "error")).await;
            match frame["type"].as_str() {
                Some("clock") => answered += 1,
                Some("error") => break frame,
                _ => panic!("{frame}"),
            }
        };
        assert_eq!(refusal["code"], "rate-limited", "{refusal}");
        // The allowance is 400 at once, and the `hello` took one of them; more come back at
        // 100 a second while the flood is read, so a slow run answers a few more.
        assert!((399..flood).contains(&answered), "{answered} answered");
        // A connection that never said hello is held to it too: answered `hello-first`, then
        // one `rate-limited`.
        let mut stranger = server.connect().await;
        for _ in 0..flood {
            stranger.send(json!({"type": "stop"})).await;
        }
        let mut first_refused = 0;
        let refusal = loop {
            let frame = stranger.recv_type("error").await;
            if frame["code"] != "hello-first" {
                break frame;
            }
            first_refused += 1;
        };
        assert_eq!(refusal["code"], "rate-limited", "{refusal}");
        assert!(
            (400..flood).contains(&first_refused),
            "{first_refused} answered"
        );
        // An operator, with a credential, is not held to it: every frame is answered.
        let mut op = server.operator().await;
        for _ in 0..flood {
            op.send(json!({"type": "context", "context": "NoSuchContext"}))
                .await;
        }
        for _ in 0..flood {
            let answer = op.recv_type("error").await;
            assert_eq!(answer["code"], "unknown-context", "{answer}");
        }
        server.stop().await;
    })
    .await;
}
