//! Who speaks when: each output channel (speech, touchscreen, projector, drive, each site
//! verb) carries out one command at a time. A command arriving while another runs is decided
//! here, by the channel's policy (`queue`, `replace`, `drop`) and the sources' priorities:
//!
//! - an act's own commands always wait their turn behind each other (they were written in
//!   order);
//! - a higher priority takes the channel over: what runs is cancelled, lower-priority waiting
//!   commands are cancelled, and the new command runs next;
//! - an equal priority follows the channel's policy;
//! - a lower priority never interrupts: it waits (queue policy) or is cancelled.
//!
//! Every queue is bounded by its `queue_limit`; whatever is pushed out, refused or cancelled is
//! handed back with a reason, for the dispatcher to report as `command.cancelled`.
//!
//! Cancelling what runs frees the channel at once: the next in line starts without waiting for
//! the cancelled command's end. Adapters carry out what they are handed in order (a
//! cancellation before the command that follows it), and the dispatcher hands decisions over
//! in the order they were made, so the device stops the old before it starts the new. A
//! replaced page or speech thus takes one hop, not a round trip to the device. This file
//! decides only; the dispatcher acts (submits, cancels, reports) outside the lanes' lock.

use std::collections::{HashMap, VecDeque};

use tokio::sync::oneshot;

use crate::adapters::{Command, Outcome};
use crate::content::Verb;
use crate::content::config::{Channel, ChannelPolicy, WhenBusy};
use crate::events::Source;

/// A command that has not reached its adapter yet.
pub(crate) struct Waiting {
    /// The command.
    pub command: Command,
    /// Who learns its outcome (a `WAIT` of its act).
    pub waiter: Option<oneshot::Sender<Outcome>>,
    /// Its source's priority.
    pub priority: u8,
}

/// What to do after a command arrived or ended.
#[derive(Default)]
pub(crate) struct Decision {
    /// Hand this one to its adapter now.
    pub run: Option<Waiting>,
    /// Cancel the running command (its verb) for this reason.
    pub cancel_running: Option<(Verb, String)>,
    /// These never run: report them cancelled, each with its reason.
    pub dropped: Vec<(Waiting, String)>,
}

struct Running {
    command: Command,
    priority: u8,
}

/// One channel: what runs and what waits, highest priority first, then in arrival order.
#[derive(Default)]
pub(crate) struct Lane {
    running: Option<Running>,
    waiting: VecDeque<Waiting>,
}

impl Lane {
    /// Decides what `new` does on `channel` under `policy`.
    pub fn admit(&mut self, new: Waiting, channel: &Channel, policy: ChannelPolicy) -> Decision {
        let mut decision = Decision::default();
        let Some((running, theirs)) =
            (self.running.as_ref()).map(|r| (r.command.clone(), r.priority))
        else {
            self.running = Some(Running {
                command: new.command.clone(),
                priority: new.priority,
            });
            decision.run = Some(new);
            return decision;
        };
        let trigger = new.command.act.trigger;
        let own_act = running.act.trigger == trigger
            || self
                .waiting
                .iter()
                .any(|w| w.command.act.trigger == trigger);
        if own_act {
            self.insert(new);
            return decision;
        }
        let mine = new.priority;
        let asker = who(new.command.act.source);
        if mine > theirs {
            let reason = format!("{asker} took over the {channel}");
            decision.dropped = self.drain(|w| w.priority < mine, &reason);
            self.insert(new);
            self.cancel_running(reason, &mut decision);
            return decision;
        }
        let busy = format!(
            "the {channel} was busy with {} ({}), so this was not carried out (its policy: {})",
            running.describe(),
            who(running.act.source),
            policy.when_busy.as_str(),
        );
        match (policy.when_busy, mine == theirs) {
            (WhenBusy::Replace, true) => {
                let label = &new.command.act.label;
                let reason = format!("replaced by act {label} from {asker}");
                decision.dropped = self.drain(|w| w.priority <= mine, &reason);
                self.insert(new);
                self.cancel_running(reason, &mut decision);
            }
            (WhenBusy::Queue, _) => self.enqueue(new, channel, policy.queue_limit, &mut decision),
            _ => decision.dropped.push((new, busy)),
        }
        decision
    }

    /// Queues `new` within `limit`: a full queue pushes out its last command if that one has a
    /// lower priority, and refuses `new` otherwise.
    fn enqueue(&mut self, new: Waiting, channel: &Channel, limit: usize, out: &mut Decision) {
        if self.waiting.len() >= limit {
            let last_lower = self
                .waiting
                .back()
                .is_some_and(|w| w.priority < new.priority);
            if !last_lower {
                let reason = format!(
                    "the {channel} queue was full ({limit} waiting), so this was not carried out"
                );
                out.dropped.push((new, reason));
                return;
            }
            if let Some(last) = self.waiting.pop_back() {
                let reason = format!(
                    "pushed out of the full {channel} queue by a command from {}",
                    who(new.command.act.source)
                );
                out.dropped.push((last, reason));
            }
        }
        self.insert(new);
    }

    /// Inserts behind everything of its priority or higher.
    fn insert(&mut self, new: Waiting) {
        let at = (self.waiting.iter())
            .position(|w| w.priority < new.priority)
            .unwrap_or(self.waiting.len());
        self.waiting.insert(at, new);
    }

    fn drain(&mut self, pred: impl Fn(&Waiting) -> bool, reason: &str) -> Vec<(Waiting, String)> {
        let (gone, kept): (VecDeque<_>, VecDeque<_>) = std::mem::take(&mut self.waiting)
            .into_iter()
            .partition(pred);
        self.waiting = kept;
        gone.into_iter().map(|w| (w, reason.to_owned())).collect()
    }

    /// Cancels the running command for `reason` and starts the next in line at once.
    fn cancel_running(&mut self, reason: String, decision: &mut Decision) {
        if let Some(running) = self.running.take() {
            decision.cancel_running = Some((running.command.verb, reason));
        }
        decision.run = self.start_next();
    }

    /// The first waiting command becomes the running one.
    fn start_next(&mut self) -> Option<Waiting> {
        let next = self.waiting.pop_front()?;
        self.running = Some(Running {
            command: next.command.clone(),
            priority: next.priority,
        });
        Some(next)
    }

    /// Command `id` ended: the next waiting one runs. A command cancelled earlier no longer
    /// runs here; its end changes nothing.
    pub fn finished(&mut self, id: u64) -> Option<Waiting> {
        if self.running.as_ref().is_none_or(|r| r.command.id != id) {
            return None;
        }
        self.running = None;
        self.start_next()
    }

    /// Cancels the commands `pred` selects, running or waiting; the next one left starts.
    pub fn cancel_where(&mut self, pred: impl Fn(&Command, u8) -> bool, reason: &str) -> Decision {
        let mut decision = Decision {
            dropped: self.drain(|w| pred(&w.command, w.priority), reason),
            ..Decision::default()
        };
        if let Some(running) = &self.running
            && pred(&running.command, running.priority)
        {
            self.cancel_running(reason.to_owned(), &mut decision);
        }
        decision
    }

    /// Whether a command `pred` selects is running or waiting here.
    pub fn holds(&self, pred: impl Fn(&Command) -> bool) -> bool {
        self.running.as_ref().is_some_and(|r| pred(&r.command))
            || self.waiting.iter().any(|w| pred(&w.command))
    }

    /// The running command.
    pub fn running(&self) -> Option<&Command> {
        self.running.as_ref().map(|r| &r.command)
    }

    /// How many commands wait.
    #[cfg(test)]
    pub fn waiting(&self) -> usize {
        self.waiting.len()
    }

    /// What runs and what waits, for `GET /api/state`.
    pub fn status(&self) -> LaneStatus {
        LaneStatus {
            running: (self.running.as_ref()).map(|r| LaneEntry::of(&r.command)),
            waiting: (self.waiting.iter())
                .map(|w| LaneEntry::of(&w.command))
                .collect(),
        }
    }
}

/// A channel's commands as `GET /api/state` shows them.
#[derive(Clone, Debug, serde::Serialize)]
pub struct LaneStatus {
    /// The command carried out now (`null` when the channel is free).
    pub running: Option<LaneEntry>,
    /// The commands waiting their turn, next first.
    pub waiting: Vec<LaneEntry>,
}

/// One command on a channel.
#[derive(Clone, Debug, serde::Serialize)]
pub struct LaneEntry {
    /// The command's id.
    pub command: u64,
    /// `VERB argument`.
    pub what: String,
    /// The act it belongs to.
    pub act: String,
    /// Who triggered it.
    pub source: Source,
}

impl LaneEntry {
    fn of(command: &Command) -> Self {
        LaneEntry {
            command: command.id,
            what: command.describe(),
            act: command.act.label.to_string(),
            source: command.act.source,
        }
    }
}

/// Every channel's lane.
pub(crate) type Lanes = HashMap<Channel, Lane>;

/// A source in words, for reasons people read.
pub(crate) fn who(source: Source) -> &'static str {
    match source {
        Source::Operator => "the operator",
        Source::Dm => "the dialog manager",
        Source::Kiosk => "the touchscreen",
        Source::Http => "the HTTP API",
        Source::Projector => "the projector",
        Source::Adapter => "an adapter",
        Source::Robot => "a reaction to a robot event",
        Source::Server => "Docent",
    }
}

#[cfg(test)]
mod tests;
