//! Access control: operator and dialog-manager credentials over HTTP and the websocket, the
//! wait after wrong ones (never for the right one), an `--open` development server, and a kiosk limited to the acts
//! its pages offer at a limited rate. Credentials never reach the corpus.

use crate::common;

use common::{DM_TOKEN, OPERATOR_TOKEN, TempBundle, TestServer, bundle};
use docent::access::AccessMode;
use serde_json::{Value, json};

async fn fig4() -> TestServer {
    TestServer::start(&bundle("tests/fixtures/fig4-verbatim")).await
}

#[tokio::test]
async fn the_http_trigger_stop_and_context_endpoints_need_a_credential() {
    let server = fig4().await;
    let trigger = "/api/acts/WELCOME/trigger";
    // Four refusals: one short of the address having to wait.
    for token in [None, Some("not-the-credential")] {
        let (status, body) = server.post_with(trigger, None, token).await;
        assert_eq!(
            (status, body["code"].as_str()),
            (401, Some("unauthorized")),
            "{body}"
        );
    }
    let (status, _) = server.post_with("/api/stop", None, None).await;
    assert_eq!(status, 401);
    let r = reqwest::Client::new()
        .put(server.url("/api/context"))
        .json(&json!({"context": "TextGroup"}))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status().as_u16(), 401);
    assert_eq!(r.headers()["www-authenticate"], "Bearer realm=\"docent\"");
    for token in [OPERATOR_TOKEN, DM_TOKEN] {
        let (status, body) = server.post_with(trigger, None, Some(token)).await;
        assert_eq!(status, 202, "{body}");
    }
    assert_eq!(server.post("/api/stop", None).await.0, 202);
    assert_eq!(
        server
            .put("/api/context", json!({"context": "TextGroup"}))
            .await
            .0,
        200
    );
    // The acts stay open to read; the state (client names, a dialog manager's reasons) not.
    assert_eq!(server.get("/api/acts").await.0, 200);
    assert_eq!(server.get("/api/state").await.0, 200);
    // (On a second server: a fifth refusal here would make this address wait.)
    let second = fig4().await;
    let anonymous = reqwest::get(second.url("/api/state")).await.unwrap();
    assert_eq!(anonymous.status().as_u16(), 401);
    second.stop().await;
    let corpus = server.stop().await;
    let refused = corpus
        .iter()
        .filter(|e| e["type"] == "act.triggered")
        .count();
    assert_eq!(refused, 2, "only the two authorised triggers ran");
}

#[tokio::test]
async fn after_five_wrong_credentials_only_wrong_ones_wait_and_stop_with_the_right_one_works() {
    let server = fig4().await;
    let trigger = "/api/acts/WELCOME/trigger";
    for attempt in 1..5 {
        let (status, _) = server.post_with(trigger, None, Some("guess-guess")).await;
        assert_eq!(status, 401, "attempt {attempt}");
    }
    for _ in 0..3 {
        let r = reqwest::Client::new()
            .post(server.url(trigger))
            .bearer_auth("guess-guess")
            .send()
            .await
            .unwrap();
        assert_eq!(r.status().as_u16(), 429);
        let retry: u64 = r.headers()["retry-after"]
            .to_str()
            .unwrap()
            .parse()
            .unwrap();
        assert!((1..=60).contains(&retry), "{retry}");
        let body: Value = r.json().await.unwrap();
        assert_eq!(body["code"], "too-many-attempts");
    }
    // The holder of the credential, at the same address, is never made to wait: Stop first.
    let (status, body) = server
        .post_with("/api/stop", None, Some(OPERATOR_TOKEN))
        .await;
    assert_eq!(status, 202, "{body}");
    let (status, body) = server.post_with(trigger, None, Some(DM_TOKEN)).await;
    assert_eq!(status, 202, "{body}");
    // The websocket: a wrong hello waits, the right one is welcomed and may stop.
    let frames = refused_hello(
        &server,
        json!({"type": "hello", "role": "operator", "token": "guess-guess"}),
    )
    .await;
    assert_eq!(frames[0]["code"], "too-many-attempts", "{frames:?}");
    let mut op = server.connect().await;
    op.send(json!({"type": "hello", "role": "operator", "token": OPERATOR_TOKEN}))
        .await;
    op.recv_type("welcome").await;
    op.send(json!({"type": "stop", "ref": "s1"})).await;
    assert_eq!(op.recv_type("stopped").await["ref"], "s1");
    server.stop().await;
}

/// The frames a refused client gets before the server closes its connection.
async fn refused_hello(server: &TestServer, hello: Value) -> Vec<Value> {
    let mut c = server.connect().await;
    c.send(hello).await;
    c.frames_until_closed().await
}

#[tokio::test]
async fn operator_and_dialog_manager_hellos_need_their_own_credential() {
    let server = fig4().await;
    let cases = [
        json!({"type": "hello", "role": "operator"}),
        json!({"type": "hello", "role": "operator", "token": "wrong-credential-1"}),
        json!({"type": "hello", "role": "operator", "token": DM_TOKEN}),
        json!({"type": "hello", "role": "dm", "token": OPERATOR_TOKEN}),
    ];
    for hello in cases {
        let frames = refused_hello(&server, hello.clone()).await;
        assert_eq!(frames.len(), 1, "{hello}: {frames:?}");
        assert_eq!(frames[0]["code"], "unauthorized", "{hello}");
        assert!(!frames[0].to_string().contains("credential-1"));
    }
    let op = server
        .client(json!({"type": "hello", "role": "operator", "token": OPERATOR_TOKEN}))
        .await;
    assert_eq!(op.welcome["role"], "operator");
    let dm = server
        .client(json!({"type": "hello", "role": "dm", "token": DM_TOKEN}))
        .await;
    assert_eq!(dm.welcome["role"], "dm");
    // Kiosks, projectors and adapters on this machine need none.
    for role in ["kiosk", "projector"] {
        let c = server.client(json!({"type": "hello", "role": role})).await;
        assert_eq!(c.welcome["role"], role);
    }
    let adapter = server
        .client(json!({"type": "hello", "role": "adapter", "verbs": ["SAY"]}))
        .await;
    assert_eq!(adapter.welcome["role"], "adapter");
    let corpus_text = common::corpus_text(&server.corpus);
    let corpus = server.stop().await;
    let refusals: Vec<&Value> = corpus
        .iter()
        .filter(|e| e["type"] == "client.refused")
        .collect();
    assert_eq!(refusals.len(), 4);
    assert_eq!(refusals[0]["code"], "unauthorized");
    assert_eq!(refusals[0]["address"], "127.0.0.1");
    for secret in [OPERATOR_TOKEN, DM_TOKEN, "wrong-credential-1"] {
        assert!(!corpus_text.contains(secret), "the corpus holds {secret}");
    }
}

#[tokio::test]
async fn an_open_development_server_asks_for_no_credential() {
    let server = TestServer::start_with(&bundle("tests/fixtures/fig4-verbatim"), |o| {
        o.access = AccessMode::Open;
    })
    .await;
    let (status, body) = server
        .post_with("/api/acts/WELCOME/trigger", None, None)
        .await;
    assert_eq!(status, 202, "{body}");
    let mut op = server.connect().await;
    op.send(json!({"type": "hello", "role": "operator"})).await;
    assert_eq!(op.recv_type("welcome").await["role"], "operator");
    server.stop().await;
}

fn kiosk_bundle() -> TempBundle {
    TempBundle::new(concat!(
        "- Label: OFFERED\n  Text: Hello.\n",
        "- Label: SECRET\n  Text: Only the operator says this.\n",
        "- Label: IDLE\n  Text: Anybody there?\n",
    ))
    .with_file(
        "pages/index.html",
        "<!doctype html><button data-act=\"OFFERED\">Hi</button>",
    )
    .with_file("docent.yaml", "kiosk: { idle_act: IDLE }\n")
}

#[tokio::test]
async fn a_kiosk_may_trigger_only_the_acts_its_pages_offer() {
    let b = kiosk_bundle();
    let server = TestServer::start_with(b.path(), |_| {}).await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    kiosk
        .send(json!({"type": "trigger", "label": "OFFERED", "ref": "a"}))
        .await;
    assert_eq!(kiosk.recv_type("triggered").await["ref"], "a");
    kiosk
        .send(json!({"type": "trigger", "label": "IDLE", "ref": "b"}))
        .await;
    assert_eq!(kiosk.recv_type("triggered").await["ref"], "b");
    kiosk
        .send(json!({"type": "trigger", "label": "SECRET", "ref": "c"}))
        .await;
    let error = kiosk.recv_type("error").await;
    assert_eq!(
        (error["code"].as_str(), error["ref"].as_str()),
        (Some("not-offered"), Some("c"))
    );
    assert!(
        error["message"].as_str().unwrap().contains("SECRET"),
        "{error}"
    );
    // The operator may trigger it.
    let mut op = server.operator().await;
    op.send(json!({"type": "trigger", "label": "SECRET"})).await;
    op.recv_type("triggered").await;
    let corpus = server.stop().await;
    let refused: Vec<&Value> = corpus
        .iter()
        .filter(|e| e["type"] == "trigger.refused")
        .collect();
    assert_eq!(refused.len(), 1, "{refused:?}");
    assert_eq!(
        (
            refused[0]["label"].as_str(),
            refused[0]["code"].as_str(),
            refused[0]["source"].as_str()
        ),
        (Some("SECRET"), Some("not-offered"), Some("kiosk"))
    );
    let secret_runs = corpus
        .iter()
        .filter(|e| e["type"] == "act.triggered" && e["label"] == "SECRET")
        .map(|e| e["source"].as_str().unwrap())
        .collect::<Vec<_>>();
    assert_eq!(secret_runs, ["operator"]);
}

#[tokio::test]
async fn a_kiosk_flooding_triggers_is_held_to_its_rate() {
    let b = kiosk_bundle();
    let server = TestServer::start_with(b.path(), |_| {}).await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    // Twenty at once: far faster than the four per second a kiosk may keep up.
    for i in 0..20 {
        kiosk
            .send(json!({"type": "trigger", "label": "OFFERED", "ref": i.to_string()}))
            .await;
    }
    let mut answers = Vec::new();
    while answers.len() < 20 {
        let frame = kiosk.recv().await;
        if frame["type"] == "triggered" || frame["type"] == "error" {
            answers.push(frame);
        }
    }
    // The burst passes the allowance (the same act is then answered `already-speaking`: it is
    // not said twice, tests/channel_policies.rs).
    for first in &answers[..5] {
        assert_ne!(first["code"], "rate-limited", "the burst passes: {first}");
    }
    let limited = answers
        .iter()
        .filter(|f| f["code"] == "rate-limited")
        .count();
    assert!(limited >= 10, "{limited} of 20 were held back");
    let corpus = server.stop().await;
    let logged = corpus
        .iter()
        .filter(|e| e["type"] == "trigger.refused" && e["code"] == "rate-limited")
        .count();
    assert_eq!(logged, 1, "one run of rate-limited triggers is logged once");
}

#[tokio::test]
async fn a_refused_connection_is_closed_after_its_error() {
    let server = fig4().await;
    let mut c = server.connect().await;
    c.send(json!({"type": "hello", "role": "dm", "token": "nope-nope-nope"}))
        .await;
    let frames = c.frames_until_closed().await;
    assert_eq!(frames[0]["code"], "unauthorized");
    // The server itself keeps serving.
    let op = server.operator().await;
    assert_eq!(op.welcome["type"], "welcome");
    server.stop().await;
}

#[tokio::test]
async fn pages_of_other_sites_are_refused() {
    let server = fig4().await;
    let r = reqwest::Client::new()
        .post(server.url("/api/acts/WELCOME/trigger"))
        .bearer_auth(OPERATOR_TOKEN)
        .header("origin", "http://evil.example")
        .send()
        .await
        .unwrap();
    assert_eq!(r.status().as_u16(), 403);
    let same = reqwest::Client::new()
        .post(server.url("/api/acts/WELCOME/trigger"))
        .bearer_auth(OPERATOR_TOKEN)
        .header("origin", format!("http://{}", server.addr))
        .send()
        .await
        .unwrap();
    assert_eq!(same.status().as_u16(), 202);
    use tokio_tungstenite::tungstenite::client::IntoClientRequest;
    let mut request = format!("ws://{}/ws", server.addr)
        .into_client_request()
        .unwrap();
    request
        .headers_mut()
        .insert("origin", "http://evil.example".parse().unwrap());
    let refused = tokio_tungstenite::connect_async(request).await;
    assert!(
        refused.is_err(),
        "a websocket from another site's page is refused"
    );
    server.stop().await;
}

#[tokio::test]
async fn a_flood_of_hellos_without_a_credential_is_logged_only_until_the_address_waits() {
    let server = fig4().await;
    let mut codes = Vec::new();
    for _ in 0..20 {
        let frames = refused_hello(&server, json!({"type": "hello", "role": "operator"})).await;
        codes.push(frames[0]["code"].as_str().unwrap().to_owned());
    }
    assert_eq!(codes[..4], ["unauthorized"; 4]);
    assert!(
        codes[4..].iter().all(|c| c == "too-many-attempts"),
        "{codes:?}"
    );
    let corpus = server.stop().await;
    let logged = corpus
        .iter()
        .filter(|e| e["type"] == "client.refused")
        .count();
    assert_eq!(
        logged, 5,
        "the four refusals and the one that made the address wait"
    );
}

#[tokio::test]
async fn kiosk_connections_from_one_address_share_one_allowance() {
    let b = kiosk_bundle();
    let server = TestServer::start_with(b.path(), |_| {}).await;
    let mut kiosks = Vec::new();
    for _ in 0..4 {
        kiosks.push(
            server
                .client(json!({"type": "hello", "role": "kiosk"}))
                .await,
        );
    }
    let mut triggered = 0;
    for round in 0..3 {
        for kiosk in &mut kiosks {
            kiosk
                .send(json!({"type": "trigger", "label": "OFFERED", "ref": round.to_string()}))
                .await;
            let answer = kiosk
                .recv_where(|f| f["type"] == "triggered" || f["type"] == "error")
                .await;
            // Past the allowance: triggered, or refused as already speaking (the same act).
            triggered += usize::from(answer["code"] != "rate-limited");
        }
    }
    // Separate allowances would have let all twelve through at once.
    assert!(
        (5..12).contains(&triggered),
        "{triggered} of 12 went through: the burst of 5, plus what refilled meanwhile"
    );
    server.stop().await;
}
