//! The websocket protocol's frames (JSON text, tagged by `type`). A compatibility boundary:
//! documented in `docs/PROTOCOL.md`; change it only with a version bump. The frames adapters
//! send (`command`, `cancel`) are built in `wire::frames`.

use serde::{Deserialize, Serialize};

use crate::adapters::{Command, Display, Pose};
use crate::dispatch::ResolvedCommand;
use crate::events::{ClientRole, Event, Source};
use crate::reload::ReloadView;
use crate::wire::ErrorCode;

/// The protocol version sent in `welcome`. 4: `command` frames carry the parsed `args`.
pub const PROTOCOL_VERSION: u32 = 4;

/// Largest text frame Docent reads; larger ones are answered with an error.
pub const MAX_FRAME_BYTES: usize = 16 * 1024;

/// A frame from a client.
#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum ClientFrame {
    /// First frame: who the client is.
    Hello {
        /// Its role.
        role: ClientRole,
        /// Verbs served (adapters only).
        #[serde(default)]
        verbs: Vec<String>,
        /// A name for logs and the operator's view.
        #[serde(default)]
        name: Option<String>,
        /// The credential (operator and dialog-manager roles; adapters not on this machine).
        #[serde(default)]
        token: Option<String>,
        /// Whether an operator or dialog manager wants the event stream (default true); a
        /// client that only triggers can say false and save both sides the traffic.
        #[serde(default = "yes")]
        events: bool,
    },
    /// Trigger an act.
    Trigger {
        /// The act.
        label: String,
        /// A context variant.
        #[serde(default)]
        context: Option<String>,
        /// Clear speech first.
        #[serde(default)]
        interrupt: bool,
        /// Echoed back.
        #[serde(default, rename = "ref")]
        reference: Option<String>,
    },
    /// Stop everything.
    Stop {
        /// Echoed back.
        #[serde(default, rename = "ref")]
        reference: Option<String>,
    },
    /// Set the current context.
    Context {
        /// The new context.
        context: String,
        /// Echoed back.
        #[serde(default, rename = "ref")]
        reference: Option<String>,
    },
    /// A kiosk shows another page of the bundle on its own (a link, the idle return home).
    Page {
        /// The page, relative to `pages/`.
        page: String,
    },
    /// A dialog manager proposes an act to the operators.
    Propose {
        /// The act.
        label: String,
        /// A context variant (the current one when absent).
        #[serde(default)]
        context: Option<String>,
        /// Why, for the operator.
        #[serde(default)]
        reason: Option<String>,
        /// Echoed back.
        #[serde(default, rename = "ref")]
        reference: Option<String>,
    },
    /// An operator accepts a proposal: its act is triggered.
    Accept {
        /// The proposal's id.
        proposal: u64,
        /// Echoed back.
        #[serde(default, rename = "ref")]
        reference: Option<String>,
    },
    /// An operator dismisses a proposal.
    Dismiss {
        /// The proposal's id.
        proposal: u64,
        /// Echoed back.
        #[serde(default, rename = "ref")]
        reference: Option<String>,
    },
    /// An operator marks the corpus: a visitor session, the visitor group, a situation.
    Mark {
        /// What is marked.
        mark: MarkKind,
        /// The group (`single`, `group`, `children`) or the situation's name.
        #[serde(default)]
        value: Option<String>,
        /// Echoed back.
        #[serde(default, rename = "ref")]
        reference: Option<String>,
    },
    /// WebRTC signalling between an operator and a kiosk, relayed as is.
    Signal {
        /// The receiving client's id.
        to: u64,
        /// Offer, answer, candidate...: opaque to the server.
        data: serde_json::Value,
    },
    /// An adapter began a command.
    Started {
        /// Command id.
        id: u64,
    },
    /// An adapter finished a command (a screen: showed it, or played the film to its end).
    Done {
        /// Command id.
        id: u64,
        /// Projector only: the ended film's last frame stays on screen.
        #[serde(default)]
        held: bool,
    },
    /// An adapter could not carry out a command.
    Failed {
        /// Command id.
        id: u64,
        /// Why.
        #[serde(default)]
        reason: Option<String>,
    },
}

/// What a `mark` frame marks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MarkKind {
    /// A visitor session begins (ending the running one).
    SessionStart,
    /// The visitor session ends.
    SessionEnd,
    /// Who the visitors are: `value` is `single`, `group` or `children`.
    Group,
    /// A dialog situation: `value` is one of the site's situations.
    Situation,
}

fn yes() -> bool {
    true
}

/// The state a client gets on `welcome` and after falling behind.
#[derive(Debug, Serialize)]
pub struct StateView {
    /// What the touchscreen and projector show.
    pub display: Display,
    /// The drive's pose, when simulated.
    pub pose: Option<Pose>,
    /// The current context.
    pub context: String,
    /// Live reload: a refused save's problems, a folder that cannot be watched, settings not
    /// yet in effect (the operator console's banner).
    pub reload: ReloadView,
}

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
    Outcome {
        command: u64,
        trigger: u64,
        #[serde(rename = "ref")]
        reference: Option<&'a str>,
        label: &'a str,
        verb: &'a str,
        outcome: NotCarriedOut,
        reason: &'a str,
        ended_by_visitor: bool,
    },
    Speaking {
        speaking: bool,
        source: Option<Source>,
        client: Option<u64>,
        stoppable: bool,
    },
    Error {
        code: ErrorCode,
        message: &'a str,
        #[serde(rename = "ref")]
        reference: Option<&'a str>,
        suggestion: Option<&'a str>,
    },
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
pub fn triggered_frame(t: &crate::dispatch::Triggered) -> String {
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
pub fn outcome_frame(
    c: &Command,
    outcome: NotCarriedOut,
    reason: &str,
    ended_by_visitor: bool,
) -> String {
    encode(&ServerFrame::Outcome {
        command: c.id,
        trigger: c.act.trigger,
        reference: c.act.reference.as_deref(),
        label: &c.act.label,
        verb: c.verb.as_str(),
        outcome,
        reason,
        ended_by_visitor,
    })
}

/// `speaking`: speech started (who asked for it; `stoppable` when visitors started it and may
/// stop it) or stopped.
pub fn speaking_frame(now: Option<crate::dispatch::Speaking>) -> String {
    encode(&ServerFrame::Speaking {
        speaking: now.is_some(),
        source: now.map(|n| n.source),
        client: now.and_then(|n| n.client),
        stoppable: now.is_some_and(|n| n.source == Source::Kiosk),
    })
}

/// `event`: one event, for operator and dialog-manager clients.
pub fn event_frame(event: &Event) -> String {
    format!("{{\"type\":\"event\",\"event\":{}}}", event.json())
}
