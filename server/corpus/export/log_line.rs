//! One line of a session's log as the exports read it: the stamps they need (`v`,
//! `session_us`) and the events that make tiers, each with the fields it must have (a line
//! without them is damaged); every other event type is passed over, so a log with event types
//! newer than this reader still exports.

use serde::Deserialize;

/// One line of the log: the stamps every export needs, and the event.
#[derive(Deserialize)]
pub struct LogLine {
    /// The event format version.
    pub v: u32,
    /// Microseconds on the session clock.
    pub session_us: Option<u64>,
    /// The event.
    #[serde(flatten)]
    pub event: Event,
}

/// The fields every `command.*` event carries.
#[derive(Deserialize)]
pub struct CommandFields {
    /// The command id.
    pub command: u64,
    /// The trigger it came from.
    pub trigger: u64,
    /// Its verb.
    pub verb: String,
    /// Its act's label.
    pub label: String,
    /// Who triggered the act.
    pub source: String,
    /// Its argument as written (`command.sent` only).
    pub arg: Option<String>,
    /// Why it failed or was cancelled.
    pub reason: Option<String>,
}

/// The events the exports read (fields as `docs/CORPUS.md` names them); every other type is
/// passed over.
#[derive(Deserialize)]
#[serde(tag = "type")]
pub enum Event {
    /// `act.triggered`: An act was triggered.
    #[serde(rename = "act.triggered")]
    ActTriggered {
        trigger: u64,
        source: String,
        label: String,
        variant: Option<String>,
        alternative: Option<u64>,
        text: Option<String>,
    },
    /// `trigger.refused`: A trigger was refused.
    #[serde(rename = "trigger.refused")]
    TriggerRefused {
        source: String,
        label: String,
        code: String,
    },
    /// `command.sent`: A command went to its adapter.
    #[serde(rename = "command.sent")]
    CommandSent(CommandFields),
    /// `command.started`: Its adapter began it.
    #[serde(rename = "command.started")]
    CommandStarted(CommandFields),
    /// `command.done`: It was carried out.
    #[serde(rename = "command.done")]
    CommandDone(CommandFields),
    /// `command.failed`: It failed.
    #[serde(rename = "command.failed")]
    CommandFailed(CommandFields),
    /// `command.cancelled`: It was dropped or cut short.
    #[serde(rename = "command.cancelled")]
    CommandCancelled(CommandFields),
    /// `display.changed`: What the screens show changed.
    #[serde(rename = "display.changed")]
    DisplayChanged { page: Option<String> },
    /// `situation.marked`: An operator marked a dialog situation.
    #[serde(rename = "situation.marked")]
    SituationMarked { situation: String },
    /// `note.written`: An operator wrote a note.
    #[serde(rename = "note.written")]
    NoteWritten { text: String },
    /// `visitor.group`: An operator noted who the visitors are.
    #[serde(rename = "visitor.group")]
    VisitorGroup { group: String },
    /// `touch`: A visitor touched the kiosk (format 4 on).
    #[serde(rename = "touch")]
    Touch {
        act: Option<String>,
        link: Option<String>,
    },
    /// `session.started`: The session began (`page`: what the touchscreen showed, format 4 on).
    #[serde(rename = "session.started")]
    SessionStarted { page: Option<String> },
    /// `session.ended`: The session ended.
    #[serde(rename = "session.ended")]
    SessionEnded,
    /// Any other event type.
    #[serde(other)]
    Other,
}

/// The newest event format this reader knows (`docs/CORPUS.md`, "Common fields").
pub const KNOWN_FORMAT: u32 = 4;

/// The first event format whose visitors' touches are `touch` events; before it, a kiosk's
/// `act.triggered` and a page change no `DISPLAY_PAGE` asked for are taken for touches.
pub const EXPLICIT_TOUCHES: u32 = 4;

impl LogLine {
    /// Parses one line (without its `\n`); the error says what is wrong, and in which column.
    pub fn parse(line: &[u8]) -> Result<LogLine, String> {
        serde_json::from_slice(line).map_err(|e| plain(&e))
    }
}

/// serde_json's message without its "at line 1 column N" (a log line is one line; the column
/// is given separately).
fn plain(error: &serde_json::Error) -> String {
    let message = error.to_string();
    let cut = message.rfind(" at line ").unwrap_or(message.len());
    format!("{} (column {})", &message[..cut], error.column())
}
