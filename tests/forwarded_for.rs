//! Who a request comes from when it carries `X-Forwarded-For`: only a proxy listed in
//! `docent.yaml` (`server: trusted_proxies`) is believed. Clients connect from different
//! loopback addresses (127.0.0.2, 127.0.0.3, ...) so that one test can play the attacker, the
//! local operator and the proxy side by side. Refused HTTP credentials are logged.

use crate::common;

use std::net::IpAddr;

use common::{OPERATOR_TOKEN, TempBundle, TestServer, bundle};
use serde_json::Value;

const TRIGGER: &str = "/api/acts/WELCOME/trigger";

/// An HTTP client whose connections come from `local` (a loopback address).
fn client_from(local: &str) -> reqwest::Client {
    let local: IpAddr = local.parse().expect("address");
    reqwest::Client::builder()
        .local_address(local)
        .build()
        .expect("client")
}

/// POSTs the trigger with `token` and, when given, `X-Forwarded-For: forwarded`.
async fn attempt(
    server: &TestServer,
    from: &reqwest::Client,
    token: &str,
    forwarded: Option<&str>,
) -> u16 {
    let mut request = from.post(server.url(TRIGGER)).bearer_auth(token);
    if let Some(forwarded) = forwarded {
        request = request.header("x-forwarded-for", forwarded);
    }
    request.send().await.expect("POST").status().as_u16()
}

fn events<'a>(corpus: &'a [Value], kind: &str) -> Vec<&'a Value> {
    corpus.iter().filter(|e| e["type"] == kind).collect()
}

#[tokio::test]
async fn a_new_x_forwarded_for_with_each_guess_does_not_escape_the_wait() {
    let server = TestServer::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    let attacker = client_from("127.0.0.2");
    let mut statuses = Vec::new();
    for guess in 0..6 {
        let forwarded = format!("203.0.113.{guess}");
        statuses.push(attempt(&server, &attacker, "wrong-guess-0000", Some(&forwarded)).await);
    }
    assert_eq!(statuses, [401, 401, 401, 401, 429, 429]);
    // The attacker's own address waits, whatever it names ...
    let wrong = attempt(&server, &attacker, "wrong-guess-0001", Some("203.0.113.99")).await;
    assert_eq!(wrong, 429);
    // ... though the right credential is always taken ...
    let right = attempt(&server, &attacker, OPERATOR_TOKEN, Some("203.0.113.99")).await;
    assert_eq!(right, 202);
    // ... and the addresses it named were never charged.
    let corpus = server.stop().await;
    let refused = events(&corpus, "request.refused");
    assert_eq!(
        refused.len(),
        5,
        "four 401s and the 429 that began the wait"
    );
    assert!(
        refused.iter().all(|e| e["address"] == "127.0.0.2"),
        "{refused:?}"
    );
}

#[tokio::test]
async fn guesses_claiming_to_be_127_0_0_1_do_not_lock_out_the_local_operator() {
    let server = TestServer::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    let attacker = client_from("127.0.0.2");
    for _ in 0..5 {
        attempt(&server, &attacker, "wrong-guess-0000", Some("127.0.0.1")).await;
    }
    assert_eq!(
        attempt(&server, &attacker, "wrong-guess-0001", Some("127.0.0.1")).await,
        429
    );
    // 127.0.0.1 was not charged: a wrong credential from it is not made to wait.
    let operator = client_from("127.0.0.1");
    assert_eq!(
        attempt(&server, &operator, "wrong-guess-0002", None).await,
        401
    );
    assert_eq!(attempt(&server, &operator, OPERATOR_TOKEN, None).await, 202);
    server.stop().await;
}

#[tokio::test]
async fn a_proxy_listed_in_docent_yaml_is_believed_for_the_client_it_names() {
    let b = TempBundle::new("- Label: WELCOME\n  Text: Hello.\n")
        .with_file("docent.yaml", "server:\n  trusted_proxies: [127.0.0.3]\n");
    let server = TestServer::start(b.path()).await;
    let proxy = client_from("127.0.0.3");
    // What the client wrote itself (the left entry) is not believed; the proxy's entry is.
    for _ in 0..5 {
        attempt(
            &server,
            &proxy,
            "wrong-guess-0000",
            Some("127.0.0.1, 192.0.2.7"),
        )
        .await;
    }
    assert_eq!(
        attempt(&server, &proxy, "wrong-guess-0001", Some("192.0.2.7")).await,
        429,
        "192.0.2.7 waits"
    );
    // Another client behind the same proxy, and the proxy's machine itself, do not.
    let other = Some("192.0.2.8");
    assert_eq!(
        attempt(&server, &proxy, "wrong-guess-0002", other).await,
        401
    );
    let local = client_from("127.0.0.1");
    assert_eq!(
        attempt(&server, &local, "wrong-guess-0003", None).await,
        401
    );
    // The right credential is always taken, from the one that waits too.
    for forwarded in [Some("192.0.2.7"), Some("192.0.2.8")] {
        assert_eq!(
            attempt(&server, &proxy, OPERATOR_TOKEN, forwarded).await,
            202
        );
    }
    assert_eq!(attempt(&server, &local, OPERATOR_TOKEN, None).await, 202);
    // An unlisted peer sending the same header is counted under its own address.
    let stranger = client_from("127.0.0.4");
    let status = attempt(&server, &stranger, "wrong-guess-0000", Some("192.0.2.8")).await;
    assert_eq!(status, 401);
    let corpus = server.stop().await;
    let addresses: Vec<&str> = events(&corpus, "request.refused")
        .iter()
        .map(|e| e["address"].as_str().unwrap())
        .collect();
    assert_eq!(
        addresses,
        ["192.0.2.7"; 5]
            .iter()
            .copied()
            .chain(["192.0.2.8", "127.0.0.1", "127.0.0.4"])
            .collect::<Vec<_>>()
    );
}

#[tokio::test]
async fn refused_http_credentials_are_logged_without_the_credential() {
    let server = TestServer::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    let (status, _) = server
        .post_with(TRIGGER, None, Some("not-the-credential-42"))
        .await;
    assert_eq!(status, 401);
    let (status, _) = server.post_with("/api/stop", None, None).await;
    assert_eq!(status, 401);
    let text = common::corpus_text(&server.corpus);
    let corpus = server.stop().await;
    let refused = events(&corpus, "request.refused");
    let seen: Vec<(&str, &str, &str, &str)> = refused
        .iter()
        .map(|e| {
            (
                e["method"].as_str().unwrap(),
                e["path"].as_str().unwrap(),
                e["code"].as_str().unwrap(),
                e["address"].as_str().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        seen,
        [
            ("POST", TRIGGER, "unauthorized", "127.0.0.1"),
            ("POST", "/api/stop", "unauthorized", "127.0.0.1"),
        ]
    );
    assert!(refused.iter().all(|e| e.get("unlogged").is_none()));
    assert!(!text.contains("not-the-credential-42"));
}

/// The code of the `error` frame a websocket `hello` from `from` with `X-Forwarded-For:
/// forwarded` and a wrong operator credential gets.
async fn refused_hello_from(server: &TestServer, from: &str, forwarded: &str) -> String {
    use futures_util::{SinkExt, StreamExt};
    use tokio_tungstenite::tungstenite::Message;
    use tokio_tungstenite::tungstenite::client::IntoClientRequest;

    let socket = tokio::net::TcpSocket::new_v4().unwrap();
    socket.bind(format!("{from}:0").parse().unwrap()).unwrap();
    let tcp = socket.connect(server.addr).await.unwrap();
    let mut request = format!("ws://{}/ws", server.addr)
        .into_client_request()
        .unwrap();
    request
        .headers_mut()
        .insert("x-forwarded-for", forwarded.parse().unwrap());
    let (mut ws, _) = tokio_tungstenite::client_async(request, tcp).await.unwrap();
    let hello = r#"{"type": "hello", "role": "operator", "token": "wrong-guess-0000"}"#;
    ws.send(Message::text(hello)).await.unwrap();
    loop {
        let next = tokio::time::timeout(common::DEADLINE, ws.next()).await;
        match next.expect("an answer within the deadline") {
            Some(Ok(Message::Text(text))) => {
                let frame: Value = serde_json::from_str(&text).unwrap();
                return frame["code"].as_str().unwrap().to_owned();
            }
            Some(Ok(_)) => continue,
            other => panic!("closed without an error frame: {other:?}"),
        }
    }
}

#[tokio::test]
async fn websocket_hellos_are_counted_against_the_real_peer_too() {
    let server = TestServer::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    let mut codes = Vec::new();
    for guess in 0..5 {
        let forwarded = format!("203.0.113.{guess}");
        codes.push(refused_hello_from(&server, "127.0.0.2", &forwarded).await);
    }
    assert_eq!(
        codes,
        [
            "unauthorized",
            "unauthorized",
            "unauthorized",
            "unauthorized",
            "too-many-attempts"
        ]
    );
    // The local operator, whose address the guesses could not reach, still gets in.
    let operator = server.operator().await;
    assert_eq!(operator.welcome["role"], "operator");
    let corpus = server.stop().await;
    let refused = events(&corpus, "client.refused");
    assert_eq!(refused.len(), 5);
    assert!(
        refused.iter().all(|e| e["address"] == "127.0.0.2"),
        "{refused:?}"
    );
}

#[tokio::test]
async fn an_open_server_refuses_a_client_that_a_header_places_elsewhere() {
    let server = TestServer::start_with(&bundle("tests/fixtures/fig4-verbatim"), |o| {
        o.access = docent::access::AccessMode::Open;
    })
    .await;
    let local = client_from("127.0.0.1");
    let forwarded = attempt(&server, &local, "any", Some("203.0.113.5")).await;
    assert_eq!(
        forwarded, 401,
        "a tunnel or unlisted proxy gets nothing for free"
    );
    assert_eq!(
        attempt(&server, &local, "any", Some("127.0.0.1")).await,
        202
    );
    assert_eq!(attempt(&server, &local, "any", None).await, 202);
    server.stop().await;
}
