//! Docent's websocket protocol as the benchmark speaks it: connecting with a `hello`, waiting
//! for `welcome`, the `trigger` and `done` frames, and reading the few fields of a server frame
//! that the benchmark needs (`docs/PROTOCOL.md`, `server/protocol/client_frames.rs`).

use std::time::Duration;

use futures_util::{SinkExt, StreamExt};
use serde::Deserialize;
use tokio::net::TcpStream;
use tokio::time::timeout;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::{MaybeTlsStream, WebSocketStream, connect_async_with_config};

use crate::Error;

/// A client connection.
pub type Ws = WebSocketStream<MaybeTlsStream<TcpStream>>;

/// How long connecting, and then waiting for `welcome`, may take each.
const HANDSHAKE_TIMEOUT: Duration = Duration::from_secs(5);

/// Who a connection says it is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// Sends triggers (and receives every event, as operator consoles do).
    Operator,
    /// An external adapter process serving `SAY`.
    SayAdapter,
    /// A touchscreen page: receives `DISPLAY_PAGE` commands.
    Kiosk,
}

impl Role {
    /// The `hello` frame for this role.
    pub fn hello(self) -> &'static str {
        match self {
            // Senders only trigger, like the floor's: they decline the event stream.
            Role::Operator => {
                r#"{"type":"hello","role":"operator","name":"docent-bench","events":false}"#
            }
            Role::SayAdapter => {
                r#"{"type":"hello","role":"adapter","verbs":["SAY"],"name":"docent-bench"}"#
            }
            Role::Kiosk => r#"{"type":"hello","role":"kiosk"}"#,
        }
    }
}

/// The fields of a server frame the benchmark reads; the rest is skipped.
#[derive(Debug, Deserialize)]
pub struct Incoming {
    /// `welcome`, `triggered`, `command`, `event`, `error`, ...
    #[serde(rename = "type")]
    pub kind: String,
    /// Command id (`command` frames).
    pub id: Option<u64>,
    /// The trigger's `ref`, echoed back.
    #[serde(rename = "ref")]
    pub reference: Option<String>,
    /// What went wrong (`error` frames).
    pub message: Option<String>,
}

/// Reads a server text frame; `None` when it is not a JSON object with a `type`.
pub fn parse(text: &str) -> Option<Incoming> {
    serde_json::from_str(text).ok()
}

/// The trigger number in a ref the benchmark made (`r17` → 17).
pub fn ref_number(reference: &str) -> Option<u64> {
    reference.strip_prefix('r')?.parse().ok()
}

/// A `trigger` frame for `label` with ref `r{number}`.
pub fn trigger(label: &str, number: u64) -> Message {
    Message::text(format!(
        r#"{{"type":"trigger","label":"{label}","ref":"r{number}"}}"#
    ))
}

/// The `done` answer to command `id`.
pub fn done(id: u64) -> Message {
    Message::text(format!(r#"{{"type":"done","id":{id}}}"#))
}

/// Opens a connection (TCP_NODELAY), says hello as `role` and waits for `welcome`.
pub async fn connect(url: &str, role: Role) -> Result<Ws, Error> {
    let (mut ws, _) = timeout(
        HANDSHAKE_TIMEOUT,
        connect_async_with_config(url, None, true),
    )
    .await
    .map_err(|_| format!("no websocket handshake with {url} within {HANDSHAKE_TIMEOUT:?}"))?
    .map_err(|e| format!("connecting to {url}: {e}"))?;
    ws.send(Message::text(role.hello())).await?;
    timeout(HANDSHAKE_TIMEOUT, welcome(&mut ws))
        .await
        .map_err(|_| format!("no welcome from {url} within {HANDSHAKE_TIMEOUT:?}"))??;
    Ok(ws)
}

async fn welcome(ws: &mut Ws) -> Result<(), Error> {
    while let Some(msg) = ws.next().await {
        let Message::Text(text) = msg? else { continue };
        match parse(&text) {
            Some(f) if f.kind == "welcome" => return Ok(()),
            Some(f) if f.kind == "error" => {
                let why = f.message.unwrap_or_default();
                return Err(format!("the server refused hello: {why}").into());
            }
            _ => {}
        }
    }
    Err("the server closed the connection before welcome".into())
}
