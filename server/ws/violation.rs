//! Websocket protocol violations, and the RFC 6455 close code each is answered with: `1007`
//! for a text message that is not UTF-8, `1009` for a message or frame over the size limit,
//! `1002` for any other broken frame (reserved opcodes or bits, an unmasked frame, a
//! fragmented or oversized control frame). A connection that merely broke off gets no close
//! frame: there is nobody left to read it, and `client.left` says it was lost.

use axum::extract::ws::{CloseFrame, close_code};
use tungstenite::error::{Error as WsError, ProtocolError};

use crate::events::Ended;

/// What ended a connection from the client's side, as `client.left` gives it, and the close
/// frame the server answers with, if any.
pub(super) struct Violation {
    /// The `client.left` reason.
    pub(super) reason: &'static str,
    /// Who ended it, as `client.left` gives it.
    pub(super) ended: Ended,
    /// The close frame to send.
    pub(super) close: Option<CloseFrame>,
}

/// The violation behind an error the websocket stream gave.
pub(super) fn violation(error: axum::Error) -> Violation {
    let error = error.into_inner();
    match error.downcast_ref::<WsError>() {
        Some(WsError::Utf8(_)) => closed(
            "invalid payload: a text message that is not UTF-8",
            close_code::INVALID,
            "text messages must be UTF-8",
        ),
        Some(WsError::Capacity(_)) => closed(
            "message too big",
            close_code::SIZE,
            "message over the server's size limit (`limits` in GET /api/state)",
        ),
        Some(WsError::Protocol(ProtocolError::ResetWithoutClosingHandshake))
        | Some(WsError::Io(_) | WsError::ConnectionClosed | WsError::AlreadyClosed) => Violation {
            reason: "connection lost",
            ended: Ended::Lost,
            close: None,
        },
        Some(WsError::Protocol(_)) | Some(_) | None => closed(
            "protocol error",
            close_code::PROTOCOL,
            "websocket protocol error",
        ),
    }
}

/// The `client.left` reason and ending of a connection the client closed with `frame`. A
/// browser closes the socket of a page that did not close it itself with 1001 (going away):
/// a crashed or killed tab, measured with Chromium (`tests/e2e/kiosk-crash.test.mjs`).
/// Docent's own pages close with 1000 when they leave on purpose (a reload, a navigation,
/// `static/socket.js`), so 1001 means the page vanished: lost, as a connection that broke off.
pub(super) fn client_closed(frame: Option<&CloseFrame>) -> (&'static str, Ended) {
    match frame {
        Some(frame) if frame.code == close_code::AWAY => (GONE_AWAY, Ended::Lost),
        _ => ("closed by client", Ended::Closed),
    }
}

/// The `client.left` reason of a connection its browser closed for a page that did not.
const GONE_AWAY: &str = "going away: the browser closed it for its page (a crashed or killed tab)";

/// A violation closed with `code`, the close frame saying `words`.
pub(super) fn closed(reason: &'static str, code: u16, words: &'static str) -> Violation {
    Violation {
        reason,
        ended: Ended::Server,
        close: Some(CloseFrame {
            code,
            reason: words.into(),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn code(error: WsError) -> Option<u16> {
        violation(axum::Error::new(error)).close.map(|c| c.code)
    }

    #[test]
    fn each_violation_gets_its_rfc_6455_code() {
        assert_eq!(code(WsError::Utf8("bad".into())), Some(1007));
        let too_long = tungstenite::error::CapacityError::MessageTooLong {
            size: 2,
            max_size: 1,
        };
        assert_eq!(code(WsError::Capacity(too_long)), Some(1009));
        assert_eq!(
            code(WsError::Protocol(ProtocolError::InvalidOpcode(3))),
            Some(1002)
        );
        assert_eq!(
            code(WsError::Protocol(ProtocolError::NonZeroReservedBits)),
            Some(1002)
        );
        let reset = WsError::Protocol(ProtocolError::ResetWithoutClosingHandshake);
        assert_eq!(code(reset), None);
    }

    #[test]
    fn a_close_for_a_page_that_went_away_is_lost_and_any_other_close_is_the_clients() {
        let frame = |code| CloseFrame {
            code,
            reason: "".into(),
        };
        assert_eq!(client_closed(Some(&frame(1001))).1, Ended::Lost);
        assert_eq!(client_closed(Some(&frame(1000))).1, Ended::Closed);
        assert_eq!(client_closed(Some(&frame(4000))).1, Ended::Closed);
        assert_eq!(client_closed(None).1, Ended::Closed);
    }

    #[test]
    fn a_connection_that_broke_off_is_lost_and_a_violation_is_the_servers_end() {
        let ended = |error: WsError| violation(axum::Error::new(error)).ended;
        let reset = WsError::Protocol(ProtocolError::ResetWithoutClosingHandshake);
        assert_eq!(ended(reset), Ended::Lost);
        let io = std::io::Error::from(std::io::ErrorKind::ConnectionReset);
        assert_eq!(ended(WsError::Io(io)), Ended::Lost);
        assert_eq!(ended(WsError::Utf8("bad".into())), Ended::Server);
    }
}
