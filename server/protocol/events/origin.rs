//! Who asked for what happened: the [`Source`] of a trigger, the [`ClientRole`] a websocket
//! client declares, how its connection [`Ended`], and the [`ActRef`] every command event carries. Separate from the event
//! variants because the dispatcher and the websocket layer use them on their own.

use std::sync::Arc;

use serde::{Deserialize, Serialize};

/// Who asked for something: the trigger API's callers and the server itself.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Source {
    /// The HTTP API.
    Http,
    /// A touchscreen page.
    Kiosk,
    /// A projector page.
    Projector,
    /// A remote operator.
    Operator,
    /// An autonomous dialog manager.
    Dm,
    /// An external adapter process.
    Adapter,
    /// The site's reaction to a robot event (`reactions:` in `docent.yaml`).
    Robot,
    /// Docent itself (start-up, shutdown, a drive arriving).
    Server,
}

impl Source {
    /// The name written in the corpus (as serialized).
    pub fn as_str(self) -> &'static str {
        match self {
            Source::Http => "http",
            Source::Kiosk => "kiosk",
            Source::Projector => "projector",
            Source::Operator => "operator",
            Source::Dm => "dm",
            Source::Adapter => "adapter",
            Source::Robot => "robot",
            Source::Server => "server",
        }
    }
}

/// The role a websocket client declares in `hello`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ClientRole {
    /// The touchscreen shell.
    Kiosk,
    /// The projector page.
    Projector,
    /// A remote operator's console.
    Operator,
    /// An autonomous dialog manager.
    Dm,
    /// An external adapter process serving verbs.
    Adapter,
}

impl ClientRole {
    /// The source recorded for triggers from a client in this role.
    pub fn source(self) -> Source {
        match self {
            ClientRole::Kiosk => Source::Kiosk,
            ClientRole::Projector => Source::Projector,
            ClientRole::Operator => Source::Operator,
            ClientRole::Dm => Source::Dm,
            ClientRole::Adapter => Source::Adapter,
        }
    }
}

/// How a websocket connection ended, as `client.left` gives it: what tells a kiosk whose tab
/// crashed (its connection vanished) from one that was closed on purpose.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Ended {
    /// The peer vanished without closing the connection itself: it broke off (end of stream,
    /// a reset, a failed write), fell silent past the idle timeout, or its browser closed it
    /// for a page that did not (1001, going away: a crashed or killed tab). A browser or
    /// computer gone, a network failure.
    Lost,
    /// The client closed the connection with a close frame of its own: it chose to leave (a
    /// page of Docent's reloading or navigating away, a program closing its socket).
    Closed,
    /// Docent ended it: shutdown, a limit, a protocol violation, a refused credential, or
    /// a command over MQTT answered (`code` says which close frame it sent, if any).
    Server,
}

/// What every command event says about the trigger it came from, shared by all its commands.
#[derive(Debug, Serialize, Deserialize)]
pub struct ActRef {
    /// The trigger's id.
    pub trigger: u64,
    /// Who triggered.
    pub source: Source,
    /// The websocket client that triggered, if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub client: Option<u64>,
    /// The caller's own reference, echoed back.
    #[serde(rename = "ref", skip_serializing_if = "Option::is_none")]
    pub reference: Option<String>,
    /// The act's label.
    pub label: Arc<str>,
    /// Where the act is written, `file:line`.
    pub at: String,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_source_is_named_as_it_is_serialized() {
        use Source::*;
        for source in [Http, Kiosk, Projector, Operator, Dm, Adapter, Robot, Server] {
            let serialized = serde_json::to_value(source).unwrap();
            assert_eq!(serialized, source.as_str());
        }
    }
}
