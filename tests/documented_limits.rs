//! The limits docs/PROTOCOL.md (and docs/FLEET.md) give are the real ones: each is read from
//! its table row or sentence and checked against the constant the code keeps (or the default
//! of its `server:` setting, which names it) and, where a
//! client can see it, against a running server (the HTTP body limit, which routes need a
//! credential and which roles it opens them to, `/report` and `/api/report` among them).

use crate::common;

use std::fs;

use common::{DM_TOKEN, OPERATOR_TOKEN, TestServer, bundle, repo};

fn doc(name: &str) -> String {
    let path = repo().join("docs").join(name);
    fs::read_to_string(&path).unwrap_or_else(|e| panic!("reading {}: {e}", path.display()))
}

/// The cells of the table row whose first cell is `first`.
fn row(doc: &str, first: &str) -> Vec<String> {
    let start = format!("| {first} |");
    let line = (doc.lines().find(|l| l.starts_with(&start)))
        .unwrap_or_else(|| panic!("no table row {start}"));
    let cells = line.trim().trim_matches('|').split(" | ");
    cells.map(|c| c.trim().to_owned()).collect()
}

/// Every size written as `N KiB` or `N MiB` in `text`, in bytes, in order.
fn sizes(text: &str) -> Vec<usize> {
    let words: Vec<&str> = text.split_whitespace().collect();
    let unit = |w: &str| match w.trim_end_matches([',', ';', '.', ')']) {
        "KiB" => Some(1024),
        "MiB" => Some(1024 * 1024),
        _ => None,
    };
    (words.windows(2))
        .filter_map(|w| Some(number(w[0])? as usize * unit(w[1])?))
        .collect()
}

/// `"1,024"` → 1024; `None` for a word that is no number.
fn number(word: &str) -> Option<f64> {
    word.trim_start_matches('(').replace(',', "").parse().ok()
}

/// `N at once, then M per second` in `text`: (N, M).
fn rate(text: &str) -> (f64, f64) {
    let (burst, rest) = text
        .split_once(" at once, then ")
        .expect("N at once, then M");
    let burst = burst.split_whitespace().last().and_then(number).expect("N");
    let per_second = rest.split_whitespace().next().and_then(number).expect("M");
    (burst, per_second)
}

#[test]
fn the_http_body_and_recording_chunk_limits_are_the_constants() {
    let protocol = doc("PROTOCOL.md");
    let body = row(&protocol, "HTTP body");
    assert_eq!(
        sizes(&body[1]),
        [
            docent::http::MAX_BODY_BYTES,
            docent::recording::MAX_CHUNK_BYTES
        ],
        "{body:?}"
    );
    let upload = row(&protocol, "`PUT /api/recordings/{recording}/chunks/{seq}`");
    assert_eq!(sizes(&upload[1]), [docent::recording::MAX_CHUNK_BYTES]);
    let example = format!(
        "\"max_chunk_bytes\": {}",
        docent::recording::MAX_CHUNK_BYTES
    );
    assert!(
        protocol.contains(&example),
        "the record frame's example says {example}"
    );
}

/// The first number of `text` (`"1,024 frames"` → 1024).
fn first_number(text: &str) -> usize {
    let first = text.split_whitespace().next().and_then(number);
    first.unwrap_or_else(|| panic!("{text:?} starts with no number")) as usize
}

#[test]
fn the_server_limits_are_the_defaults_and_name_their_settings() {
    let protocol = doc("PROTOCOL.md");
    let limits = docent::content::config::ServerLimits::default();
    let cell = |first: &str, setting: &str| {
        let value = row(&protocol, first).swap_remove(1);
        let named = format!("`server: {setting}`");
        assert!(value.contains(&named), "{first}: {value:?} names {named}");
        value
    };
    let per_address = cell("Connections per address", "connections: per_address");
    assert_eq!(first_number(&per_address), limits.per_address);
    assert_eq!(
        first_number(&cell("Connections in all", "connections: total")),
        limits.total
    );
    let queue = cell("Outgoing queue per client", "queues: per_client");
    assert_eq!(first_number(&queue), limits.queue_per_client);
    let message = cell("Message size", "messages: max_size");
    assert_eq!(sizes(&message), [limits.max_message_bytes]);
    let headers = cell("HTTP headers", "timeouts: headers");
    let seconds = limits.header_timeout.as_secs();
    assert!(
        headers.contains(&format!("within {seconds} s")),
        "{headers:?}"
    );
    let body = cell("HTTP body", "timeouts: body");
    let seconds = limits.body_timeout.as_secs();
    assert!(body.contains(&format!("within {seconds} s")), "{body:?}");
    let frame = row(&protocol, "Frame size");
    assert_eq!(sizes(&frame[1]), [docent::ws::protocol::MAX_FRAME_BYTES]);
}

#[test]
fn the_websocket_allowances_are_the_constants() {
    let protocol = doc("PROTOCOL.md");
    let pairs = [
        (
            "Kiosk triggers, page reports and stops",
            (
                docent::access::KIOSK_BURST,
                docent::access::KIOSK_PER_SECOND,
            ),
        ),
        (
            "Kiosk recording reports",
            (
                docent::access::RECORDING_BURST,
                docent::access::RECORDING_PER_SECOND,
            ),
        ),
        (
            "Frames without a credential",
            (docent::ws::FRAME_BURST, docent::ws::FRAMES_PER_SECOND),
        ),
        (
            "Pings without a credential",
            (docent::ws::PING_BURST, docent::ws::PINGS_PER_SECOND),
        ),
    ];
    for (first, constants) in pairs {
        let cells = row(&protocol, first);
        assert_eq!(rate(&cells[1]), constants, "{first}: {cells:?}");
    }
}

#[test]
fn the_mqtt_message_limit_is_the_constant() {
    let fleet = doc("FLEET.md");
    let limit = docent::fleet::MAX_MESSAGE_BYTES;
    let sentence = (fleet
        .lines()
        .find(|l| l.starts_with("Docent takes messages of at most")))
    .expect("FLEET.md says the message limit");
    assert_eq!(sizes(sentence), [limit], "{sentence}");
}

/// The routes of the endpoints table that a GET without parameters reaches, with the
/// credential the table says they need.
fn documented_gets(protocol: &str) -> Vec<(String, String)> {
    let rows = protocol.lines().filter(|l| l.starts_with("| `GET /"));
    let gets = rows.filter_map(|line| {
        let cells: Vec<&str> = line.trim().trim_matches('|').split(" | ").collect();
        let path = cells[0].trim().strip_prefix("`GET ")?.strip_suffix('`')?;
        (!path.contains('{')).then(|| (path.to_owned(), cells[2].trim().to_owned()))
    });
    gets.collect()
}

#[tokio::test]
async fn each_route_needs_the_credential_the_endpoints_table_gives_and_bodies_their_limit() {
    let protocol = doc("PROTOCOL.md");
    let routes = documented_gets(&protocol);
    let listed: Vec<&str> = routes.iter().map(|(p, _)| p.as_str()).collect();
    for path in ["/report", "/api/report", "/api/state"] {
        assert!(
            listed.contains(&path),
            "{path} is not in the endpoints table"
        );
    }
    let server = TestServer::start(&bundle("tests/fixtures/fig4-verbatim")).await;
    let http = reqwest::Client::new();
    let status = |path: &str, token: Option<&str>| {
        let mut request = http.get(server.url(path));
        if let Some(token) = token {
            request = request.bearer_auth(token);
        }
        async move { request.send().await.expect("answers").status().as_u16() }
    };
    for (path, credential) in &routes {
        match credential.as_str() {
            "none" => assert_ne!(status(path, None).await, 401, "{path} needs none"),
            // "Bearer": the operator's or the dialog manager's credential.
            "Bearer" => {
                assert_eq!(status(path, None).await, 401, "{path} needs a credential");
                for token in [OPERATOR_TOKEN, DM_TOKEN] {
                    let answer = status(path, Some(token)).await;
                    assert!((200..300).contains(&answer), "{path}: {answer}");
                }
            }
            other => panic!("{path}: a credential the test does not know: {other}"),
        }
    }
    // The body limit: its last byte is taken, one more is refused.
    let limit = sizes(&row(&protocol, "HTTP body")[1])[0];
    for (size, expected) in [(limit, 400), (limit + 1, 413)] {
        let response = http
            .post(server.url("/api/acts/WELCOME/trigger"))
            .bearer_auth(OPERATOR_TOKEN)
            .body(
                vec![b' '; size - 2]
                    .into_iter()
                    .chain(*b"[]")
                    .collect::<Vec<u8>>(),
            )
            .send()
            .await
            .expect("answers");
        assert_eq!(
            response.status().as_u16(),
            expected,
            "a body of {size} bytes"
        );
    }
    server.stop().await;
}

/// The shipped systemd unit gives the process the files the default connection total and
/// Docent's own files need, and docs/DEVICE.md says the figure the unit sets.
#[test]
fn the_systemd_units_open_files_fit_the_default_connection_total() {
    let unit = fs::read_to_string(repo().join("kiosk/systemd/docent.service")).expect("the unit");
    let set = (unit.lines().find_map(|l| l.strip_prefix("LimitNOFILE=")))
        .expect("the unit sets LimitNOFILE=");
    let files: u64 = set.trim().parse().expect("a number");
    let total = docent::content::config::ServerLimits::default().total as u64;
    assert!(
        files >= total + docent::http::OWN_FILES,
        "LimitNOFILE={files}"
    );
    assert!(doc("DEVICE.md").contains(&format!("`LimitNOFILE={files}`")));
}
