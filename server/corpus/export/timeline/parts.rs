//! What a session's timeline is made of: utterances, other commands, pages, touches and marks,
//! each on the session clock, as `timeline.rs` reads them from the log and every export writes
//! them.

use std::collections::BTreeSet;

use docent_protocol::events::Source;

/// How a command ended, as its outcome event said.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// `command.done`.
    Done,
    /// `command.failed`, with its reason.
    Failed(String),
    /// `command.cancelled`, with its reason.
    Cancelled(String),
    /// No outcome in the log (the session was cut off by a kill or a crash).
    Open,
}

/// The text of a `SAY` sent before the session began (queued, then begun within it): the
/// session's log does not have it, the day log does.
pub const UNKNOWN_TEXT: &str = "(text not in this session's log: the SAY was sent before the \
                                session began; see the day log)";

/// A `SAY` the speech device began: from its `command.started` to its outcome.
#[derive(Clone, Debug, PartialEq)]
pub struct Utterance {
    /// Its `command.started`.
    pub start_us: u64,
    /// Its outcome (the session's end when it has none).
    pub end_us: u64,
    /// The exact text handed to the speech device (the `SAY`'s argument).
    pub text: String,
    /// The act whose command it was.
    pub label: String,
    /// Who triggered the act (`kiosk`, `operator`, `dm`, `http`).
    pub source: Source,
    /// The variant chosen, when this `SAY` says the act's chosen text.
    pub variant: Option<String>,
    /// The alternative chosen within the variant, likewise.
    pub alternative: Option<u64>,
    /// How it ended.
    pub outcome: Outcome,
}

/// Any other command (and a `SAY` that never began): from its start to its outcome.
#[derive(Clone, Debug, PartialEq)]
pub struct CommandRun {
    /// Its `command.started`, else its `command.sent`, else its outcome (the only event of a
    /// command dropped before it was sent).
    pub start_us: u64,
    /// Its outcome (the session's end when it has none).
    pub end_us: u64,
    /// The verb.
    pub verb: String,
    /// The argument as written, when the log has it.
    pub arg: Option<String>,
    /// How it ended.
    pub outcome: Outcome,
}

/// A page the touchscreen showed, until the next one.
#[derive(Clone, Debug, PartialEq)]
pub struct PageShown {
    /// The `display.changed` that showed it.
    pub start_us: u64,
    /// The next page change, or the session's end.
    pub end_us: u64,
    /// The page, relative to `pages/`.
    pub page: String,
}

/// A visitor's touch on the kiosk.
#[derive(Clone, Debug, PartialEq)]
pub struct Touch {
    /// When its event was logged.
    pub at_us: u64,
    /// What the touch did.
    pub what: Touched,
}

/// What a touch did.
#[derive(Clone, Debug, PartialEq)]
pub enum Touched {
    /// Triggered an act (its `act.triggered`, source `kiosk`).
    Act {
        /// The act's label.
        label: String,
    },
    /// Asked for an act that was refused (`trigger.refused`, source `kiosk`).
    Refused {
        /// The label asked for.
        label: String,
        /// The refusal's code (`rate-limited`, `not-offered`, ...).
        code: String,
    },
    /// Went to a page on its own (a link): a page change no `DISPLAY_PAGE` asked for.
    Page {
        /// The page, relative to `pages/`.
        page: String,
    },
}

/// An operator's mark.
#[derive(Clone, Debug, PartialEq)]
pub struct Mark {
    /// When it was logged.
    pub at_us: u64,
    /// What was marked.
    pub what: Marked,
}

/// What an operator marked.
#[derive(Clone, Debug, PartialEq)]
pub enum Marked {
    /// A dialog situation (`question`, `laughter`, ...).
    Situation(String),
    /// An operator's note, in their words.
    Note(String),
    /// Who the visitors are (`single`, `group`, `children`).
    Group(String),
}

/// Everything the exports draw from one session's log, on the session clock.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Timeline {
    /// The session's length: its `session.ended`, or its last line when it has none.
    pub end_us: u64,
    /// Whether the log has the session's `session.ended`.
    pub ended: bool,
    /// The robot's utterances, by start.
    pub utterances: Vec<Utterance>,
    /// The other commands, by start.
    pub commands: Vec<CommandRun>,
    /// The pages shown, by start.
    pub pages: Vec<PageShown>,
    /// The visitors' touches, in log order.
    pub touches: Vec<Touch>,
    /// The operator's marks, in log order.
    pub marks: Vec<Mark>,
    /// Every act label the session's log names.
    pub labels: BTreeSet<String>,
}

/// Why a line could not be read; the caller adds the file and line number.
#[derive(Debug, PartialEq, Eq)]
pub struct LineProblem(pub String);
