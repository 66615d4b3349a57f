//! The dispatcher's side of the channels (`channels.rs` decides): hands a command to its
//! adapter when its channel is free, learns when it ended, starts the next one, cancels what a
//! policy, a priority, an interruption, a visitor or a page change removes, and tells the
//! client that triggered a command when it will not be carried out. Nothing here holds the
//! lanes' lock while it submits, cancels or reports; the order lock is held from a decision
//! to its last hand-over (adapters never call back into the dispatcher, so it cannot nest).

use std::sync::Arc;

use tokio::sync::oneshot;

use crate::adapters::{CancelScope, Command, Outcome, Reply};
use crate::content::config::Channel;
use crate::dispatch::Dispatcher;
use crate::dispatch::channels::{Decision, LaneStatus, Waiting};
use crate::events::{EventKind, Source};
use crate::sync::lock;

/// Who speaks now, for the kiosks' "speaking" state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Speaking {
    /// The source of the speech running now.
    pub source: Source,
    /// The client that triggered it, if a websocket client did.
    pub client: Option<u64>,
}

/// Where the dispatcher tells clients about their commands; the websocket layer implements
/// it (the dispatcher knows no wire format).
pub trait Notifier: Send + Sync {
    /// A command triggered by `client` ended without being carried out; `ended_by_visitor`
    /// when a visitor ended it (stopped speech, left the page), so it needs no word to them.
    fn outcome(&self, client: u64, command: &Command, outcome: &Outcome, ended_by_visitor: bool);
    /// Speech started (`Some`) or stopped (`None`). Called under the dispatcher's lock: it
    /// must only queue (never wait, never call back into the dispatcher).
    fn speaking(&self, now: Option<Speaking>);
    /// The visitor's language changed: the kiosks show their page in it. Called under the
    /// dispatcher's language lock: it must only queue.
    fn language(&self, language: &crate::content::Language);
}

impl Dispatcher {
    /// Sends `command` through its channel; `waiter` learns its outcome.
    pub(crate) fn send(
        self: &Arc<Self>,
        command: Command,
        waiter: Option<oneshot::Sender<Outcome>>,
    ) {
        let adapter = self.router.adapter_for(&command.verb);
        self.hub.publish(EventKind::CommandSent {
            command: command.id,
            act: Arc::clone(&command.act),
            verb: command.verb.to_string(),
            arg: command.arg.as_deref().map(str::to_owned),
            args: Arc::clone(&command.args),
            adapter: adapter.map_or("none", |a| a.name()).into(),
        });
        let channel = Channel::of(&command.verb);
        let (Some(_), Some(channel)) = (adapter, channel) else {
            let reason = format!("no adapter serves {}", command.verb);
            return self.report(command, waiter, Outcome::Failed(reason));
        };
        let bundle = self.bundle();
        let policy = bundle.config.channels.of(&channel);
        let priority = self.priority(command.act.source);
        let new = Waiting {
            command,
            waiter,
            priority,
        };
        let _order = lock(&self.order);
        let decision = {
            let mut lanes = lock(&self.lanes);
            let lane = lanes.entry(channel.clone()).or_default();
            lane.admit(new, &channel, policy)
        };
        self.carry_out(&channel, decision);
    }

    /// The priority of `source` in the live bundle's settings.
    pub(crate) fn priority(&self, source: Source) -> u8 {
        let priorities = self.bundle.load().config.priorities;
        match source {
            Source::Kiosk => priorities.kiosk,
            // A reaction acts on its own, as a dialog manager does.
            Source::Dm | Source::Robot => priorities.dm,
            Source::Http => priorities.http,
            Source::Operator | Source::Projector | Source::Adapter | Source::Server => {
                priorities.operator
            }
        }
    }

    /// Acts on a decision: reports the dropped, cancels the running, starts the next.
    fn carry_out(self: &Arc<Self>, channel: &Channel, decision: Decision) {
        for (waiting, reason) in decision.dropped {
            self.report(waiting.command, waiting.waiter, Outcome::Cancelled(reason));
        }
        if let Some((verb, reason)) = decision.cancel_running
            && let Some(adapter) = self.router.adapter_for(&verb)
        {
            adapter.cancel(CancelScope::Verb(&verb), &reason);
        }
        if let Some(next) = decision.run {
            self.launch(channel.clone(), next);
        }
    }

    /// Hands a command to its adapter and follows it to its end.
    fn launch(self: &Arc<Self>, channel: Channel, waiting: Waiting) {
        let Waiting {
            command, waiter, ..
        } = waiting;
        let Some(adapter) = self.router.adapter_for(&command.verb) else {
            // Checked on arrival; routes do not change while serving.
            return self.report(command, waiter, Outcome::Failed("no adapter".into()));
        };
        if channel == Channel::Speech {
            self.tell_speaking();
        }
        let (tx, rx) = oneshot::channel();
        adapter.submit(
            command.clone(),
            Reply::new(self.hub.clone(), command.clone(), Some(tx)),
        );
        let me = Arc::clone(self);
        let shutdown = self.life.shutdown.clone();
        self.life.spawn(async move {
            let outcome = tokio::select! {
                outcome = rx => outcome.unwrap_or_else(|_| Outcome::Failed("lost".into())),
                // Adapters answer everything on shutdown; nothing is left to start.
                () = shutdown.cancelled() => return,
            };
            me.ended(&channel, &command, outcome, waiter);
        });
    }

    /// A command's adapter answered: pass the outcome on and start the channel's next command.
    fn ended(
        self: &Arc<Self>,
        channel: &Channel,
        command: &Command,
        outcome: Outcome,
        waiter: Option<oneshot::Sender<Outcome>>,
    ) {
        self.tell_sender(command, &outcome);
        if let Some(waiter) = waiter {
            let _ = waiter.send(outcome);
        }
        let _order = lock(&self.order);
        let next = lock(&self.lanes)
            .get_mut(channel)
            .and_then(|lane| lane.finished(command.id));
        match next {
            Some(next) => self.launch(channel.clone(), next),
            None if *channel == Channel::Speech => self.tell_speaking(),
            None => {}
        }
    }

    /// Reports the outcome of a command that never reached its adapter.
    pub(crate) fn report(
        &self,
        command: Command,
        waiter: Option<oneshot::Sender<Outcome>>,
        outcome: Outcome,
    ) {
        self.tell_sender(&command, &outcome);
        Reply::new(self.hub.clone(), command, waiter).finish(outcome);
    }

    /// Cancels the commands on `channel` (every channel when `None`) that `pred` selects.
    pub(crate) fn cancel_where(
        self: &Arc<Self>,
        channel: Option<&Channel>,
        pred: impl Fn(&Command, u8) -> bool,
        reason: &str,
    ) {
        let _order = lock(&self.order);
        let decisions: Vec<(Channel, Decision)> = {
            let mut lanes = lock(&self.lanes);
            lanes
                .iter_mut()
                .filter(|(c, _)| channel.is_none_or(|wanted| wanted == *c))
                .map(|(c, lane)| (c.clone(), lane.cancel_where(&pred, reason)))
                .collect()
        };
        for (channel, decision) in decisions {
            self.carry_out(&channel, decision);
        }
    }

    /// Whether speech of act `label` is running or waiting.
    pub(crate) fn speaking_act(&self, label: &str) -> bool {
        lock(&self.lanes)
            .get(&Channel::Speech)
            .is_some_and(|lane| lane.holds(|c| &*c.act.label == label))
    }

    /// Sets where clients are told about their commands (once, at start-up).
    pub fn set_notifier(&self, notifier: Arc<dyn Notifier>) {
        let _ = self.notifier.set(notifier);
    }

    fn tell_sender(&self, command: &Command, outcome: &Outcome) {
        if matches!(outcome, Outcome::Done) {
            return;
        }
        if let (Some(client), Some(notifier)) = (command.act.client, self.notifier.get()) {
            // Everything of a visitor's act older than their stop or page change ended by it.
            let ended_by_visitor = self.visitor_cut_off(&command.act).is_some();
            notifier.outcome(client, command, outcome, ended_by_visitor);
        }
    }

    /// Tells the kiosks who speaks now. Read and sent under the lanes' lock, so that two
    /// changes racing on two threads reach the kiosks in the order they happened.
    fn tell_speaking(&self) {
        let Some(notifier) = self.notifier.get() else {
            return;
        };
        let lanes = lock(&self.lanes);
        let running = lanes.get(&Channel::Speech).and_then(|lane| lane.running());
        let now = running.map(|c| Speaking {
            source: c.act.source,
            client: c.act.client,
        });
        // A cancelled command ends after its successor started: kiosks hear only changes.
        let mut told = lock(&self.speaking_told);
        if *told != now {
            *told = now;
            notifier.speaking(now);
        }
    }

    /// Every channel that has carried a command: what runs and what waits, by channel name.
    pub fn channel_status(&self) -> std::collections::BTreeMap<String, LaneStatus> {
        (lock(&self.lanes).iter())
            .map(|(channel, lane)| (channel.to_string(), lane.status()))
            .collect()
    }

    /// Hands `tell` who speaks now, as the kiosks were last told, under the lock the changes
    /// are sent under: a kiosk that joined the notices first never gets it after a newer one.
    pub fn tell_speaking_now(&self, tell: impl FnOnce(Option<Speaking>)) {
        let _lanes = lock(&self.lanes);
        tell(*lock(&self.speaking_told));
    }
}
