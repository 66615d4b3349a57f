//! The frames Docent sends a websocket client (`welcome`, answers, notices, events), each
//! built by one function into its JSON text; the frames clients send are in
//! `client_frames.rs`, the state they are welcomed with in `state.rs`.

use serde::Serialize;

use docent_content::Language;

use crate::PROTOCOL_VERSION;
use crate::client_frames::MarkKind;
use crate::error_code::ErrorCode;
use crate::events::{ClientRole, Event, Source};
use crate::state::StateView;

#[derive(Serialize)]
#[serde(tag = "type", rename_all = "lowercase")]
enum ServerFrame<'a> {
    Welcome {
        protocol: u32,
        client: u64,
        role: ClientRole,
        state: &'a StateView,
    },
    State {
        state: &'a StateView,
    },
    Triggered {
        #[serde(rename = "ref")]
        reference: Option<&'a str>,
        trigger: u64,
        label: &'a str,
        context: &'a str,
        variant: Option<&'a str>,
        alternative: Option<usize>,
        text: Option<&'a str>,
        commands: &'a [ResolvedCommand],
    },
    Stopped {
        #[serde(rename = "ref")]
        reference: Option<&'a str>,
    },
    Context {
        #[serde(rename = "ref")]
        reference: Option<&'a str>,
        context: &'a str,
    },
    Language {
        #[serde(rename = "ref", skip_serializing_if = "Option::is_none")]
        reference: Option<&'a str>,
        language: &'a Language,
    },
    Proposed {
        #[serde(rename = "ref")]
        reference: Option<&'a str>,
        proposal: u64,
    },
    Dismissed {
        #[serde(rename = "ref")]
        reference: Option<&'a str>,
        proposal: u64,
    },
    Marked {
        #[serde(rename = "ref")]
        reference: Option<&'a str>,
        mark: MarkKind,
        value: Option<&'a str>,
        session: Option<u64>,
    },
    Signal {
        from: u64,
        role: ClientRole,
        data: &'a serde_json::Value,
    },
    Changed {
        pages: &'a [&'a str],
        shell: bool,
    },
    Media {
        files: &'a [crate::state::MediaView],
    },
    Outcome(&'a OutcomeFrame<'a>),
    Speaking {
        speaking: bool,
        source: Option<Source>,
        client: Option<u64>,
        stoppable: bool,
    },
    Caption {
        text: Option<&'a str>,
        command: Option<u64>,
    },
    Error {
        code: ErrorCode,
        message: &'a str,
        #[serde(rename = "ref")]
        reference: Option<&'a str>,
        suggestion: Option<&'a str>,
    },
}

/// One resolved command, as reported to the caller.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ResolvedCommand {
    /// The command's id (matches `command` frames and events).
    pub id: u64,
    /// The verb.
    pub verb: String,
    /// The argument, `null` when there is none.
    pub arg: Option<String>,
}

/// The outcome of a successful trigger: the `triggered` frame's fields, and the HTTP trigger's
/// `202` answer.
#[derive(Clone, Debug, Serialize)]
pub struct Triggered {
    /// The trigger's id.
    pub trigger: u64,
    /// The caller's reference, echoed.
    #[serde(rename = "ref")]
    pub reference: Option<String>,
    /// The act's label.
    pub label: String,
    /// The context that applied.
    pub context: String,
    /// The variant whose text was chosen (`Text` on fallback); `null` when the act has none.
    pub variant: Option<String>,
    /// Index of the chosen alternative.
    pub alternative: Option<usize>,
    /// The chosen text.
    pub text: Option<String>,
    /// The language of the chosen text (the default one when it has no translation into the
    /// visitor's); `null` when the act has no text.
    pub language: Option<Language>,
    /// Every command in order, the implicit `SAY` first.
    pub commands: Vec<ResolvedCommand>,
}

/// What an `outcome` frame says: a command the client triggered ended without being carried
/// out. The runtime fills it from its command.
#[derive(Debug, Serialize)]
pub struct OutcomeFrame<'a> {
    /// The command's id.
    pub command: u64,
    /// Its trigger's id.
    pub trigger: u64,
    /// The trigger's `ref`.
    #[serde(rename = "ref")]
    pub reference: Option<&'a str>,
    /// Its act's label.
    pub label: &'a str,
    /// Its verb.
    pub verb: &'a str,
    /// Cancelled or failed.
    pub outcome: NotCarriedOut,
    /// Why, in words.
    pub reason: &'a str,
    /// A visitor ended it (stopped speech, left the page): it needs no word to them.
    pub ended_by_visitor: bool,
}

/// Who speaks now, for the kiosks' `speaking` frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Speaking {
    /// The source of the speech running now.
    pub source: Source,
    /// The client that triggered it, if a websocket client did.
    pub client: Option<u64>,
}

/// How a command ended without being carried out, in an `outcome` frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum NotCarriedOut {
    /// Dropped, replaced, interrupted or stopped.
    Cancelled,
    /// The device could not carry it out.
    Failed,
}

fn encode(frame: &ServerFrame<'_>) -> String {
    // Plain data with string keys: serialization cannot fail.
    serde_json::to_string(frame).unwrap_or_default()
}

/// `welcome`: protocol version, the client's id and role, and the current state.
pub fn welcome_frame(client: u64, role: ClientRole, state: &StateView) -> String {
    encode(&ServerFrame::Welcome {
        protocol: PROTOCOL_VERSION,
        client,
        role,
        state,
    })
}

/// `state`: a fresh snapshot for a client that fell behind.
pub fn state_frame(state: &StateView) -> String {
    encode(&ServerFrame::State { state })
}

/// `triggered`: the answer to a trigger.
pub fn triggered_frame(t: &Triggered) -> String {
    encode(&ServerFrame::Triggered {
        reference: t.reference.as_deref(),
        trigger: t.trigger,
        label: &t.label,
        context: &t.context,
        variant: t.variant.as_deref(),
        alternative: t.alternative,
        text: t.text.as_deref(),
        commands: &t.commands,
    })
}

/// `stopped`: the answer to `stop`.
pub fn stopped_frame(reference: Option<&str>) -> String {
    encode(&ServerFrame::Stopped { reference })
}

/// `context`: the answer to a context change.
pub fn context_frame(reference: Option<&str>, context: &str) -> String {
    encode(&ServerFrame::Context { reference, context })
}

/// `language`: the answer to a language change, and what kiosks are told of every change.
pub fn language_frame(reference: Option<&str>, language: &Language) -> String {
    encode(&ServerFrame::Language {
        reference,
        language,
    })
}

/// `proposed`: the answer to `propose`.
pub fn proposed_frame(reference: Option<&str>, proposal: u64) -> String {
    encode(&ServerFrame::Proposed {
        reference,
        proposal,
    })
}

/// `dismissed`: the answer to `dismiss`.
pub fn dismissed_frame(reference: Option<&str>, proposal: u64) -> String {
    encode(&ServerFrame::Dismissed {
        reference,
        proposal,
    })
}

/// `marked`: the answer to `mark`, with the session the mark belongs to.
pub fn marked_frame(
    reference: Option<&str>,
    mark: MarkKind,
    value: Option<&str>,
    session: Option<u64>,
) -> String {
    encode(&ServerFrame::Marked {
        reference,
        mark,
        value,
        session,
    })
}

/// `signal`: signalling data relayed from client `from`.
pub fn signal_frame(from: u64, role: ClientRole, data: &serde_json::Value) -> String {
    encode(&ServerFrame::Signal { from, role, data })
}

/// `changed`: a saved bundle went live; `pages` are the files under `pages/` changed since the
/// last one, `shell` says the kiosk shell's own settings changed (it reloads itself).
pub fn changed_frame(pages: &[&str], shell: bool) -> String {
    encode(&ServerFrame::Changed { pages, shell })
}

/// `media`: to operators, the bundle's media files still converting or that failed, every
/// time one moves on (empty once all are ready).
pub fn media_frame(files: &[crate::state::MediaView]) -> String {
    encode(&ServerFrame::Media { files })
}

/// `error`: what went wrong with a client's frame; the connection stays open.
pub fn error_frame(
    code: ErrorCode,
    message: &str,
    reference: Option<&str>,
    suggestion: Option<&str>,
) -> String {
    encode(&ServerFrame::Error {
        code,
        message,
        reference,
        suggestion,
    })
}

/// `outcome`: a command the client triggered ended without being carried out, and why.
pub fn outcome_frame(outcome: &OutcomeFrame<'_>) -> String {
    encode(&ServerFrame::Outcome(outcome))
}

/// `speaking`: speech started (who asked for it; `stoppable` when visitors started it and may
/// stop it) or stopped.
pub fn speaking_frame(now: Option<Speaking>) -> String {
    encode(&ServerFrame::Speaking {
        speaking: now.is_some(),
        source: now.map(|n| n.source),
        client: now.and_then(|n| n.client),
        stoppable: now.is_some_and(|n| n.source == Source::Kiosk),
    })
}

/// `caption`: the text the robot is saying now (its `SAY` command's id), shown from the
/// speech device's start to its end; `None` when nothing is being said or shown.
pub fn caption_frame(now: Option<(u64, &str)>) -> String {
    encode(&ServerFrame::Caption {
        text: now.map(|(_, text)| text),
        command: now.map(|(id, _)| id),
    })
}

/// `event`: one event, for operator and dialog-manager clients.
pub fn event_frame(event: &Event) -> String {
    format!("{{\"type\":\"event\",\"event\":{}}}", event.json())
}
