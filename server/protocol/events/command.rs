//! What the corpus says about a command of an act: handed to its adapter, started, done,
//! failed or cancelled (`command.*`), each with its trigger and act.

use std::borrow::Cow;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use super::origin::ActRef;
use docent_content::Args;

/// The fields of a `command.sent` event ([`super::EventKind::CommandSent`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct CommandSent {
    /// Command id.
    pub command: u64,
    /// The trigger and act.
    #[serde(flatten)]
    pub act: Arc<ActRef>,
    /// Verb.
    pub verb: String,
    /// Argument as written.
    pub arg: Option<String>,
    /// The argument parsed (the `args` of `command` frames; format 2). Not read back: read
    /// as none (`Args::None`), as format 1 lines, which lack it, are.
    #[serde(skip_deserializing, default = "no_args")]
    pub args: Arc<Args>,
    /// The adapter it went to.
    pub adapter: Cow<'static, str>,
}

/// The fields of a `command.started` event ([`super::EventKind::CommandStarted`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct CommandStarted {
    /// Command id.
    pub command: u64,
    /// The trigger and act.
    #[serde(flatten)]
    pub act: Arc<ActRef>,
    /// Verb.
    pub verb: String,
}

/// The fields of a `command.done` event ([`super::EventKind::CommandDone`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct CommandDone {
    /// Command id.
    pub command: u64,
    /// The trigger and act.
    #[serde(flatten)]
    pub act: Arc<ActRef>,
    /// Verb.
    pub verb: String,
}

/// The fields of a `command.failed` event ([`super::EventKind::CommandFailed`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct CommandFailed {
    /// Command id.
    pub command: u64,
    /// The trigger and act.
    #[serde(flatten)]
    pub act: Arc<ActRef>,
    /// Verb.
    pub verb: String,
    /// Why, in words.
    pub reason: String,
}

/// The fields of a `command.cancelled` event ([`super::EventKind::CommandCancelled`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct CommandCancelled {
    /// Command id.
    pub command: u64,
    /// The trigger and act.
    #[serde(flatten)]
    pub act: Arc<ActRef>,
    /// Verb.
    pub verb: String,
    /// Why.
    pub reason: String,
}

/// What a line without `args` reads as.
fn no_args() -> Arc<Args> {
    Arc::new(Args::None {})
}
