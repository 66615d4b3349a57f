//! Websocket protocol violations, and the RFC 6455 close code each is answered with: `1007`
//! for a text message that is not UTF-8, `1009` for a message or frame over the size limit,
//! `1002` for any other broken frame (reserved opcodes or bits, an unmasked frame, a
//! fragmented or oversized control frame). A connection that merely broke off gets no close
//! frame: there is nobody left to read it.

use axum::extract::ws::{CloseFrame, close_code};
use tungstenite::error::{Error as WsError, ProtocolError};

/// What ended a connection from the client's side, as `client.left` gives it, and the close
/// frame the server answers with, if any.
pub(super) struct Violation {
    /// The `client.left` reason.
    pub(super) reason: &'static str,
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
            close: None,
        },
        Some(WsError::Protocol(_)) | Some(_) | None => closed(
            "protocol error",
            close_code::PROTOCOL,
            "websocket protocol error",
        ),
    }
}

/// A violation closed with `code`, the close frame saying `words`.
pub(super) fn closed(reason: &'static str, code: u16, words: &'static str) -> Violation {
    Violation {
        reason,
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
}
