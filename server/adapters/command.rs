//! A dispatched command and the reply handle through which its adapter reports the outcome.
//! Every outcome becomes an event; a reply dropped without an outcome reports a failure, so no
//! command can vanish silently.

use std::fmt;
use std::sync::Arc;

use docent_protocol::frames::{CommandFrame, command_frame};

use tokio::sync::oneshot;

use crate::content::{Args, Verb, speaking_time};
use crate::events::{
    ActRef, CommandCancelled, CommandDone, CommandFailed, CommandStarted, EventKind, Hub,
};

/// A command on its way to an adapter. Cheap to clone.
#[derive(Clone, Debug)]
pub struct Command {
    /// Unique id within this server run.
    pub id: u64,
    /// The trigger and act it came from.
    pub act: Arc<ActRef>,
    /// What to do.
    pub verb: Verb,
    /// Its argument as written (for logs, the corpus and status displays).
    pub arg: Option<Arc<str>>,
    /// Its argument parsed at load: what adapters act on.
    pub args: Arc<Args>,
}

impl Command {
    /// The `command` frame that sends it to a screen.
    pub fn frame(&self) -> String {
        command_frame(&self.frame_fields(None))
    }

    /// The `command` frame that sends it to an adapter process or browser speech: a `SAY`
    /// also says how long saying it takes at `rate_wpm` (`speaking_time`, the one rule), so
    /// that no client works it out again.
    pub fn frame_at_rate(&self, rate_wpm: u32) -> String {
        let speaking_ms = match self.args.as_ref() {
            Args::Say { text, .. } => {
                let ms = speaking_time(text, rate_wpm).as_millis();
                Some(u64::try_from(ms).unwrap_or(u64::MAX))
            }
            _ => None,
        };
        command_frame(&self.frame_fields(speaking_ms))
    }

    fn frame_fields(&self, speaking_ms: Option<u64>) -> CommandFrame<'_> {
        CommandFrame {
            id: self.id,
            trigger: self.act.trigger,
            reference: self.act.reference.as_deref(),
            label: &self.act.label,
            verb: self.verb.as_str(),
            arg: self.arg.as_deref(),
            args: &self.args,
            speaking_ms,
        }
    }

    /// `VERB argument`, for status displays and messages.
    pub fn describe(&self) -> String {
        self.current().to_string()
    }

    /// What an adapter carrying it out reports in its [`AdapterStatus`](super::AdapterStatus).
    pub fn current(&self) -> CurrentCommand {
        CurrentCommand {
            verb: self.verb.clone(),
            arg: self.arg.clone(),
        }
    }
}

/// The command an adapter is carrying out, kept as fields so that Rust reads the verb and the
/// argument instead of splitting the `VERB argument` text it displays as.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CurrentCommand {
    /// Its verb.
    pub verb: Verb,
    /// Its argument as written.
    pub arg: Option<Arc<str>>,
}

impl CurrentCommand {
    /// The text being spoken, when this is a `SAY` with an argument.
    pub fn spoken(&self) -> Option<&str> {
        (self.verb == Verb::Say)
            .then_some(self.arg.as_deref())
            .flatten()
    }
}

impl fmt::Display for CurrentCommand {
    /// `VERB argument`, as status displays show it.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.arg {
            Some(arg) => write!(f, "{} {arg}", self.verb),
            None => write!(f, "{}", self.verb),
        }
    }
}

/// How a command ended.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Carried out.
    Done,
    /// Not carried out, for this reason.
    Failed(String),
    /// Dropped or cut short by a stop or interruption.
    Cancelled(String),
}

/// The one-shot channel an adapter answers on.
pub struct Reply {
    hub: Hub,
    command: Command,
    waiter: Option<oneshot::Sender<Outcome>>,
    answered: bool,
}

impl Reply {
    /// A reply for `command`; `waiter` (if any) learns the outcome too, for `WAIT`.
    pub fn new(hub: Hub, command: Command, waiter: Option<oneshot::Sender<Outcome>>) -> Self {
        Reply {
            hub,
            command,
            waiter,
            answered: false,
        }
    }

    /// The command this reply is for.
    pub fn command(&self) -> &Command {
        &self.command
    }

    /// Reports that execution began.
    pub fn started(&self) {
        self.hub.publish(EventKind::CommandStarted(CommandStarted {
            command: self.command.id,
            act: Arc::clone(&self.command.act),
            verb: self.command.verb.to_string(),
        }));
    }

    /// Reports the outcome.
    pub fn finish(mut self, outcome: Outcome) {
        self.report(outcome);
    }

    fn report(&mut self, outcome: Outcome) {
        self.answered = true;
        let command = self.command.id;
        let act = Arc::clone(&self.command.act);
        let verb = self.command.verb.to_string();
        let kind = match &outcome {
            Outcome::Done => EventKind::CommandDone(CommandDone { command, act, verb }),
            Outcome::Failed(reason) => EventKind::CommandFailed(CommandFailed {
                command,
                act,
                verb,
                reason: reason.clone(),
            }),
            Outcome::Cancelled(reason) => EventKind::CommandCancelled(CommandCancelled {
                command,
                act,
                verb,
                reason: reason.clone(),
            }),
        };
        self.hub.publish(kind);
        if let Some(waiter) = self.waiter.take() {
            let _ = waiter.send(outcome);
        }
    }
}

impl Drop for Reply {
    fn drop(&mut self) {
        if !self.answered {
            self.report(Outcome::Failed(
                "the adapter dropped the command without answering".into(),
            ));
        }
    }
}
