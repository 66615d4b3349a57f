//! [`ErrorCode`]: every stable code a client is told, in a websocket `error` frame or an HTTP
//! error body. A compatibility boundary: the codes are listed in `docs/PROTOCOL.md`'s two
//! error tables, and a test holds the enum and the tables to the same set.

use serde::{Deserialize, Serialize};

/// A stable error code; serialised as its kebab-case name (`frame-too-large`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ErrorCode {
    /// `bad-request`: A request body or address that is not right.
    BadRequest,
    /// `body-not-object`: A request body that is JSON but not an object.
    BodyNotObject,
    /// `conflicting-length`: A request with both `Content-Length` and `Transfer-Encoding`.
    ConflictingLength,
    /// `body-timeout`: A request body that did not arrive in time.
    BodyTimeout,
    /// `body-too-large`: A chunked request body over the limit.
    BodyTooLarge,
    /// `too-many-connections`: A connection over a connection limit.
    TooManyConnections,
    /// `unknown-context`: No such context.
    UnknownContext,
    /// `unknown-language`: Not one of the bundle's languages.
    UnknownLanguage,
    /// `unauthorized`: A missing or wrong credential.
    Unauthorized,
    /// `cross-origin`: A request from a browser page of another site.
    CrossOrigin,
    /// `unknown-act`: No act has this label.
    UnknownAct,
    /// `not-found`: No such route or file.
    NotFound,
    /// `method-not-allowed`: Wrong method on a known route.
    MethodNotAllowed,
    /// `too-many-attempts`: An address that has to wait after wrong credentials.
    TooManyAttempts,
    /// `internal`: A fault in Docent (details in the server log).
    Internal,
    /// `corpus-unwritable`: The corpus log cannot be written.
    CorpusUnwritable,
    /// `malformed-json`: A frame that is not JSON.
    MalformedJson,
    /// `missing-type`: A frame without `type`.
    MissingType,
    /// `unknown-type`: A frame of an unknown `type`.
    UnknownType,
    /// `bad-frame`: A known frame type with wrong fields.
    BadFrame,
    /// `frame-too-large`: A text frame over the size limit.
    FrameTooLarge,
    /// `binary-frame`: A binary frame.
    BinaryFrame,
    /// `hello-first`: Anything but `hello` before `hello`.
    HelloFirst,
    /// `already-introduced`: A second `hello`.
    AlreadyIntroduced,
    /// `no-verbs`: An adapter `hello` without verbs.
    NoVerbs,
    /// `forbidden`: A frame the role may not send, or a refused `signal`.
    Forbidden,
    /// `not-offered`: A kiosk triggered an act no page offers.
    NotOffered,
    /// `rate-limited`: A kiosk beyond its allowance, or too many signals.
    RateLimited,
    /// `unknown-page`: A kiosk's `page` names no page of the bundle.
    UnknownPage,
    /// `already-speaking`: A kiosk triggered an act whose speech is already running or waiting.
    AlreadySpeaking,
    /// `unknown-command`: An answer for a command not owed by this connection.
    UnknownCommand,
    /// `unknown-proposal`: A proposal that is not pending.
    UnknownProposal,
    /// `too-many-proposals`: Too many proposals wait for an operator.
    TooManyProposals,
    /// `no-session`: `session_end` while no visitor session runs.
    NoSession,
    /// `bad-mark`: A `mark` with a value that is not allowed.
    BadMark,
    /// `confirmation-required`: A consent `mark` that deletes a session's recordings without
    /// `confirm: true`: nothing changed.
    ConfirmationRequired,
    /// `bad-signal`: A `signal` with no known `kind`.
    BadSignal,
    /// `unknown-client`: A `signal` to a client that is not connected.
    UnknownClient,
    /// `verb-not-routed`: Some of an adapter's verbs are routed to another adapter.
    VerbNotRouted,
    /// `unknown-session`: No corpus session has this name (or the name is a path).
    UnknownSession,
    /// `session-recording`: The session is still being recorded: it can be replayed once it has ended.
    SessionRecording,
    /// `unknown-tier`: An annotation's tier is not in the codebook.
    UnknownTier,
    /// `unknown-code`: An annotation's code is not one of its tier's.
    UnknownCode,
    /// `bad-time`: An annotation that ends before it starts or after the session.
    BadTime,
    /// `unknown-annotation`: A change or removal of an annotation the session does not have.
    UnknownAnnotation,
    /// `annotations-unwritable`: The session's annotations file cannot be written: nothing was saved.
    AnnotationsUnwritable,
    /// `bad-ticket`: A media address whose ticket is unknown, expired or for another session.
    BadTicket,
    /// `session-damaged`: The session's log or manifest is damaged: it cannot be replayed as it is.
    SessionDamaged,
    /// `chunk-out-of-order`: A recording chunk after a gap (the answer says the `next` one).
    ChunkOutOfOrder,
    /// `recording-gone`: A chunk for a recording that is closed or unknown.
    RecordingGone,
    /// `recording-limit`: A chunk beyond a recording limit or the disk's reserve.
    RecordingLimit,
    /// `broker-down`: The fleet view's link to the MQTT broker is down: nothing was sent.
    BrokerDown,
    /// `robot-silent`: A robot did not answer a fleet command in time.
    RobotSilent,
    /// `robot-refused`: A robot answered a fleet command with an error (its code in the message).
    RobotRefused,
    /// `unsigned-command`: A fleet command over MQTT that is not signed (or carries a raw credential).
    UnsignedCommand,
    /// `bad-signature`: A fleet command whose MAC is not the role's credential's, or that names another robot.
    BadSignature,
    /// `stale-command`: A fleet command signed more than 30 s from the robot's clock.
    StaleCommand,
    /// `replayed-command`: A fleet command whose `ref` was taken already.
    ReplayedCommand,
    /// `no-credential`: The fleet view has no operator credential to sign a command with.
    NoCredential,
    /// `media-converting`: A media file is still being converted for Chromium (HTTP 503 with
    /// `Retry-After`); the message says how far it is.
    MediaConverting,
    /// `media-unconvertible`: A media file could not be converted for Chromium; the message
    /// says why and what to do.
    MediaUnconvertible,
}

impl ErrorCode {
    /// Every code, for tests and documentation checks.
    pub const ALL: &[ErrorCode] = &[
        ErrorCode::BadRequest,
        ErrorCode::BodyNotObject,
        ErrorCode::ConflictingLength,
        ErrorCode::BodyTimeout,
        ErrorCode::BodyTooLarge,
        ErrorCode::TooManyConnections,
        ErrorCode::UnknownContext,
        ErrorCode::UnknownLanguage,
        ErrorCode::Unauthorized,
        ErrorCode::CrossOrigin,
        ErrorCode::UnknownAct,
        ErrorCode::NotFound,
        ErrorCode::MethodNotAllowed,
        ErrorCode::TooManyAttempts,
        ErrorCode::Internal,
        ErrorCode::CorpusUnwritable,
        ErrorCode::MalformedJson,
        ErrorCode::MissingType,
        ErrorCode::UnknownType,
        ErrorCode::BadFrame,
        ErrorCode::FrameTooLarge,
        ErrorCode::BinaryFrame,
        ErrorCode::HelloFirst,
        ErrorCode::AlreadyIntroduced,
        ErrorCode::NoVerbs,
        ErrorCode::Forbidden,
        ErrorCode::NotOffered,
        ErrorCode::RateLimited,
        ErrorCode::UnknownPage,
        ErrorCode::AlreadySpeaking,
        ErrorCode::UnknownCommand,
        ErrorCode::UnknownProposal,
        ErrorCode::TooManyProposals,
        ErrorCode::NoSession,
        ErrorCode::BadMark,
        ErrorCode::ConfirmationRequired,
        ErrorCode::BadSignal,
        ErrorCode::UnknownClient,
        ErrorCode::VerbNotRouted,
        ErrorCode::UnknownSession,
        ErrorCode::SessionRecording,
        ErrorCode::UnknownTier,
        ErrorCode::UnknownCode,
        ErrorCode::BadTime,
        ErrorCode::UnknownAnnotation,
        ErrorCode::AnnotationsUnwritable,
        ErrorCode::BadTicket,
        ErrorCode::SessionDamaged,
        ErrorCode::ChunkOutOfOrder,
        ErrorCode::RecordingGone,
        ErrorCode::RecordingLimit,
        ErrorCode::BrokerDown,
        ErrorCode::RobotSilent,
        ErrorCode::RobotRefused,
        ErrorCode::UnsignedCommand,
        ErrorCode::BadSignature,
        ErrorCode::StaleCommand,
        ErrorCode::ReplayedCommand,
        ErrorCode::NoCredential,
        ErrorCode::MediaConverting,
        ErrorCode::MediaUnconvertible,
    ];

    /// The code as sent (the same string serde writes), for events and logs.
    pub const fn as_str(self) -> &'static str {
        match self {
            ErrorCode::BadRequest => "bad-request",
            ErrorCode::BodyNotObject => "body-not-object",
            ErrorCode::ConflictingLength => "conflicting-length",
            ErrorCode::BodyTimeout => "body-timeout",
            ErrorCode::BodyTooLarge => "body-too-large",
            ErrorCode::TooManyConnections => "too-many-connections",
            ErrorCode::UnknownContext => "unknown-context",
            ErrorCode::UnknownLanguage => "unknown-language",
            ErrorCode::Unauthorized => "unauthorized",
            ErrorCode::CrossOrigin => "cross-origin",
            ErrorCode::UnknownAct => "unknown-act",
            ErrorCode::NotFound => "not-found",
            ErrorCode::MethodNotAllowed => "method-not-allowed",
            ErrorCode::TooManyAttempts => "too-many-attempts",
            ErrorCode::Internal => "internal",
            ErrorCode::CorpusUnwritable => "corpus-unwritable",
            ErrorCode::MalformedJson => "malformed-json",
            ErrorCode::MissingType => "missing-type",
            ErrorCode::UnknownType => "unknown-type",
            ErrorCode::BadFrame => "bad-frame",
            ErrorCode::FrameTooLarge => "frame-too-large",
            ErrorCode::BinaryFrame => "binary-frame",
            ErrorCode::HelloFirst => "hello-first",
            ErrorCode::AlreadyIntroduced => "already-introduced",
            ErrorCode::NoVerbs => "no-verbs",
            ErrorCode::Forbidden => "forbidden",
            ErrorCode::NotOffered => "not-offered",
            ErrorCode::RateLimited => "rate-limited",
            ErrorCode::UnknownPage => "unknown-page",
            ErrorCode::AlreadySpeaking => "already-speaking",
            ErrorCode::UnknownCommand => "unknown-command",
            ErrorCode::UnknownProposal => "unknown-proposal",
            ErrorCode::TooManyProposals => "too-many-proposals",
            ErrorCode::NoSession => "no-session",
            ErrorCode::BadMark => "bad-mark",
            ErrorCode::ConfirmationRequired => "confirmation-required",
            ErrorCode::BadSignal => "bad-signal",
            ErrorCode::UnknownClient => "unknown-client",
            ErrorCode::VerbNotRouted => "verb-not-routed",
            ErrorCode::UnknownSession => "unknown-session",
            ErrorCode::SessionRecording => "session-recording",
            ErrorCode::UnknownTier => "unknown-tier",
            ErrorCode::UnknownCode => "unknown-code",
            ErrorCode::BadTime => "bad-time",
            ErrorCode::UnknownAnnotation => "unknown-annotation",
            ErrorCode::AnnotationsUnwritable => "annotations-unwritable",
            ErrorCode::BadTicket => "bad-ticket",
            ErrorCode::SessionDamaged => "session-damaged",
            ErrorCode::ChunkOutOfOrder => "chunk-out-of-order",
            ErrorCode::RecordingGone => "recording-gone",
            ErrorCode::RecordingLimit => "recording-limit",
            ErrorCode::BrokerDown => "broker-down",
            ErrorCode::RobotSilent => "robot-silent",
            ErrorCode::RobotRefused => "robot-refused",
            ErrorCode::UnsignedCommand => "unsigned-command",
            ErrorCode::BadSignature => "bad-signature",
            ErrorCode::StaleCommand => "stale-command",
            ErrorCode::ReplayedCommand => "replayed-command",
            ErrorCode::NoCredential => "no-credential",
            ErrorCode::MediaConverting => "media-converting",
            ErrorCode::MediaUnconvertible => "media-unconvertible",
        }
    }
}

impl std::fmt::Display for ErrorCode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;

    use super::ErrorCode;

    #[test]
    fn every_code_serialises_to_its_kebab_case_string() {
        for code in ErrorCode::ALL {
            let json = serde_json::to_value(code).expect("a code serialises");
            assert_eq!(json, serde_json::Value::from(code.as_str()), "{code:?}");
        }
        assert_eq!(ErrorCode::BadRequest.as_str(), "bad-request");
        assert_eq!(ErrorCode::BodyNotObject.as_str(), "body-not-object");
        assert_eq!(ErrorCode::ConflictingLength.as_str(), "conflicting-length");
        assert_eq!(ErrorCode::BodyTimeout.as_str(), "body-timeout");
        assert_eq!(ErrorCode::BodyTooLarge.as_str(), "body-too-large");
        assert_eq!(
            ErrorCode::TooManyConnections.as_str(),
            "too-many-connections"
        );
        assert_eq!(ErrorCode::UnknownContext.as_str(), "unknown-context");
        assert_eq!(ErrorCode::Unauthorized.as_str(), "unauthorized");
        assert_eq!(ErrorCode::CrossOrigin.as_str(), "cross-origin");
        assert_eq!(ErrorCode::UnknownAct.as_str(), "unknown-act");
        assert_eq!(ErrorCode::NotFound.as_str(), "not-found");
        assert_eq!(ErrorCode::MethodNotAllowed.as_str(), "method-not-allowed");
        assert_eq!(ErrorCode::TooManyAttempts.as_str(), "too-many-attempts");
        assert_eq!(ErrorCode::Internal.as_str(), "internal");
        assert_eq!(ErrorCode::CorpusUnwritable.as_str(), "corpus-unwritable");
        assert_eq!(ErrorCode::MalformedJson.as_str(), "malformed-json");
        assert_eq!(ErrorCode::MissingType.as_str(), "missing-type");
        assert_eq!(ErrorCode::UnknownType.as_str(), "unknown-type");
        assert_eq!(ErrorCode::BadFrame.as_str(), "bad-frame");
        assert_eq!(ErrorCode::FrameTooLarge.as_str(), "frame-too-large");
        assert_eq!(ErrorCode::BinaryFrame.as_str(), "binary-frame");
        assert_eq!(ErrorCode::HelloFirst.as_str(), "hello-first");
        assert_eq!(ErrorCode::AlreadyIntroduced.as_str(), "already-introduced");
        assert_eq!(ErrorCode::NoVerbs.as_str(), "no-verbs");
        assert_eq!(ErrorCode::Forbidden.as_str(), "forbidden");
        assert_eq!(ErrorCode::NotOffered.as_str(), "not-offered");
        assert_eq!(ErrorCode::RateLimited.as_str(), "rate-limited");
        assert_eq!(ErrorCode::UnknownPage.as_str(), "unknown-page");
        assert_eq!(ErrorCode::AlreadySpeaking.as_str(), "already-speaking");
        assert_eq!(ErrorCode::UnknownCommand.as_str(), "unknown-command");
        assert_eq!(ErrorCode::UnknownProposal.as_str(), "unknown-proposal");
        assert_eq!(ErrorCode::TooManyProposals.as_str(), "too-many-proposals");
        assert_eq!(ErrorCode::NoSession.as_str(), "no-session");
        assert_eq!(ErrorCode::BadMark.as_str(), "bad-mark");
        assert_eq!(ErrorCode::BadSignal.as_str(), "bad-signal");
        assert_eq!(ErrorCode::UnknownClient.as_str(), "unknown-client");
        assert_eq!(ErrorCode::VerbNotRouted.as_str(), "verb-not-routed");
        assert_eq!(ErrorCode::UnknownSession.as_str(), "unknown-session");
        assert_eq!(ErrorCode::SessionRecording.as_str(), "session-recording");
        assert_eq!(ErrorCode::UnknownTier.as_str(), "unknown-tier");
        assert_eq!(ErrorCode::UnknownCode.as_str(), "unknown-code");
        assert_eq!(ErrorCode::BadTime.as_str(), "bad-time");
        assert_eq!(ErrorCode::UnknownAnnotation.as_str(), "unknown-annotation");
        assert_eq!(
            ErrorCode::AnnotationsUnwritable.as_str(),
            "annotations-unwritable"
        );
        assert_eq!(ErrorCode::BadTicket.as_str(), "bad-ticket");
        assert_eq!(ErrorCode::SessionDamaged.as_str(), "session-damaged");
        assert_eq!(ErrorCode::ChunkOutOfOrder.as_str(), "chunk-out-of-order");
        assert_eq!(ErrorCode::RecordingGone.as_str(), "recording-gone");
    }

    /// The codes in the first column of `docs/PROTOCOL.md`'s HTTP error table (`| status |
    /// `code` | when |`, code in the second column) and websocket error table (`| `code` |
    /// cause |`).
    fn documented_codes() -> BTreeSet<String> {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/PROTOCOL.md");
        let doc = std::fs::read_to_string(path).expect("docs/PROTOCOL.md is readable");
        let mut codes = BTreeSet::new();
        let mut column = None;
        for line in doc.lines() {
            if line.starts_with("| status | `code` | when |") {
                column = Some(2);
            } else if line.starts_with("| `code` | cause |") {
                column = Some(1);
            } else if !line.starts_with('|') {
                column = None;
            } else if let Some(c) = column {
                let cell = line.split('|').nth(c).unwrap_or_default().trim();
                if let Some(code) = cell.strip_prefix('`').and_then(|s| s.strip_suffix('`')) {
                    codes.insert(code.to_owned());
                }
            }
        }
        codes
    }

    #[test]
    fn the_codes_are_exactly_those_docs_protocol_lists() {
        let documented = documented_codes();
        let ours: BTreeSet<String> = ErrorCode::ALL
            .iter()
            .map(|c| c.as_str().to_owned())
            .collect();
        assert_eq!(ours.len(), ErrorCode::ALL.len(), "no code twice");
        assert!(documented.len() > 30, "both tables parsed: {documented:?}");
        assert_eq!(ours, documented);
    }
}
