//! What the corpus says about clients: websocket clients coming and going (`client.connected`,
//! `client.left`), and credentials refused (`client.refused`, `request.refused`).

use serde::{Deserialize, Serialize};

use super::origin::{ClientRole, Ended};
use crate::{ErrorCode, Open};

/// The fields of a `client.refused` event ([`super::EventKind::ClientRefused`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct ClientRefused {
    /// The role it asked for.
    pub role: ClientRole,
    /// `unauthorized`, `bad-signature` (MQTT) or `too-many-attempts`.
    pub code: Open<ErrorCode>,
    /// Its network address, when known (never for MQTT: the broker does not say).
    pub address: Option<String>,
    /// Credential refusals (websocket and HTTP) left out of the log just before this one,
    /// because refusals from many addresses came faster than they are logged.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub unlogged: u64,
}

/// The fields of a `request.refused` event ([`super::EventKind::RequestRefused`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct RequestRefused {
    /// The request's method.
    pub method: String,
    /// The request's path (without the query), at most 256 bytes.
    pub path: String,
    /// `unauthorized` or `too-many-attempts`.
    pub code: Open<ErrorCode>,
    /// The client's network address, when known.
    pub address: Option<String>,
    /// As for `client.refused`.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub unlogged: u64,
}

/// The fields of a `client.connected` event ([`super::EventKind::ClientConnected`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct ClientConnected {
    /// The connection's id.
    pub client: u64,
    /// Its role.
    pub role: ClientRole,
    /// Its self-given name.
    pub name: Option<String>,
    /// Verbs it serves (adapters).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub verbs: Vec<String>,
}

/// The fields of a `client.left` event ([`super::EventKind::ClientLeft`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct ClientLeft {
    /// The connection's id.
    pub client: u64,
    /// Its role.
    pub role: ClientRole,
    /// Its self-given name, as in its `client.connected` (added without a version change:
    /// older logs lack it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Why it ended.
    pub reason: String,
    /// Who ended it: the peer vanished (`lost`), the client closed it (`closed`), or Docent
    /// did (`server`). Added without a version change: older logs lack it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ended: Option<Ended>,
    /// The close code the server ended the connection with, when the server decided the
    /// end (`1008` a client that stopped reading, `1013` one that fell behind the event
    /// stream, `1001` shutdown, the RFC 6455 code of a protocol violation).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub code: Option<u16>,
}

fn is_zero(n: &u64) -> bool {
    *n == 0
}
