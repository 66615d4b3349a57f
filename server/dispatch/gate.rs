//! The dispatcher's side of the channels (`channels.rs` decides): hands a command to its
//! adapter when its channel is free, learns when it ended, starts the next one, cancels what a
//! policy, a priority, an interruption, a visitor or a page change removes, and tells the
//! client that triggered a command when it will not be carried out. Everything here runs
//! within a [`Turn`], from a decision to its last hand-over (adapters never call back into the
//! dispatcher, so it cannot nest).

use std::sync::Arc;

use tokio::sync::{mpsc, oneshot};

use crate::adapters::{CancelScope, Command, Outcome, Reply};
use crate::content::config::Channel;
use crate::dispatch::channels::{Decision, LaneStatus, Waiting};
use crate::dispatch::state::{State, Turn};
use crate::dispatch::{Dispatcher, priority};
use crate::events::{CommandSent, EventKind};
use crate::sync::lock;
pub use docent_protocol::server_frames::Speaking;

/// The client that asked for a change, answered with the notice of it: after every screen was
/// told, as the protocol promises.
#[derive(Debug, Clone)]
pub struct Answer {
    /// The websocket client.
    pub client: u64,
    /// The `ref` of its frame.
    pub reference: Option<String>,
}

/// What the dispatcher tells clients outside an answer: a closed set of messages, queued in
/// the turn that decided them (so in the order things happened) and delivered by the websocket
/// layer's own task (`ws::notices`). The dispatcher never calls into the websocket layer.
#[derive(Debug)]
pub enum Notice {
    /// A command triggered by `client` ended without being carried out; `ended_by_visitor`
    /// when a visitor ended it (stopped speech, left the page), so it needs no word to them.
    NotCarriedOut {
        /// The websocket client that triggered it.
        client: u64,
        /// The command.
        command: Command,
        /// How it ended (cancelled or failed).
        outcome: Outcome,
        /// Whether a visitor ended it.
        ended_by_visitor: bool,
    },
    /// Speech started (`Some`) or stopped (`None`): the kiosks show it.
    Speaking(Option<Speaking>),
    /// The visitor's language changed (event `seq` logs it): the kiosks and projectors show
    /// their page in it, and the client that asked, if one did, is answered after them.
    Language {
        /// The language now.
        language: crate::content::Language,
        /// The sequence number of its `language.changed` event.
        seq: u64,
        /// Who asked for it, to be answered once every screen was told.
        answer: Option<Answer>,
    },
    /// A kiosk joined: it is to be told who speaks now, in its place among the changes, so
    /// it never gets an older state after a newer one.
    KioskJoined(u64),
}

impl Dispatcher {
    /// Sends `command` through its channel; `waiter` learns its outcome.
    pub(crate) fn send(
        self: &Arc<Self>,
        turn: &mut Turn,
        command: Command,
        waiter: Option<oneshot::Sender<Outcome>>,
    ) {
        let adapter = self.router.adapter_for(&command.verb);
        self.hub.publish(EventKind::CommandSent(CommandSent {
            command: command.id,
            act: Arc::clone(&command.act),
            verb: command.verb.to_string(),
            arg: command.arg.as_deref().map(str::to_owned),
            args: Arc::clone(&command.args),
            adapter: adapter.map_or("none", |a| a.name()).into(),
        }));
        let channel = Channel::of(&command.verb);
        let (Some(_), Some(channel)) = (adapter, channel) else {
            let reason = format!("no adapter serves {}", command.verb);
            return self.report(&turn.state, command, waiter, Outcome::Failed(reason));
        };
        let policy = turn.bundle.config.channels.of(&channel);
        let priority = priority(&turn.bundle, command.act.source);
        let new = Waiting {
            command,
            waiter,
            priority,
        };
        let lane = turn.state.lanes.entry(channel.clone()).or_default();
        let decision = lane.admit(new, &channel, policy);
        self.carry_out(&mut turn.state, &channel, decision);
    }

    /// Acts on a decision: reports the dropped, cancels the running, starts the next.
    fn carry_out(self: &Arc<Self>, state: &mut State, channel: &Channel, decision: Decision) {
        for (waiting, reason) in decision.dropped {
            let outcome = Outcome::Cancelled(reason);
            self.report(state, waiting.command, waiting.waiter, outcome);
        }
        if let Some((verb, reason)) = decision.cancel_running
            && let Some(adapter) = self.router.adapter_for(&verb)
        {
            adapter.cancel(CancelScope::Verb(&verb), &reason);
        }
        if let Some(next) = decision.run {
            self.launch(state, channel.clone(), next);
        }
    }

    /// Hands a command to its adapter and follows it to its end.
    fn launch(self: &Arc<Self>, state: &mut State, channel: Channel, waiting: Waiting) {
        let Waiting {
            command, waiter, ..
        } = waiting;
        let Some(adapter) = self.router.adapter_for(&command.verb) else {
            // Checked on arrival; routes do not change while serving.
            let outcome = Outcome::Failed("no adapter".into());
            return self.report(state, command, waiter, outcome);
        };
        if channel == Channel::Speech {
            self.tell_speaking(state);
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
        let mut state = lock(&self.state);
        self.tell_sender(&state, command, &outcome);
        if let Some(waiter) = waiter {
            let _ = waiter.send(outcome);
        }
        let next = (state.lanes.get_mut(channel)).and_then(|lane| lane.finished(command.id));
        match next {
            Some(next) => self.launch(&mut state, channel.clone(), next),
            None if *channel == Channel::Speech => self.tell_speaking(&mut state),
            None => {}
        }
    }

    /// Reports the outcome of a command that never reached its adapter.
    pub(crate) fn report(
        &self,
        state: &State,
        command: Command,
        waiter: Option<oneshot::Sender<Outcome>>,
        outcome: Outcome,
    ) {
        self.tell_sender(state, &command, &outcome);
        Reply::new(self.hub.clone(), command, waiter).finish(outcome);
    }

    /// Cancels the commands on `channel` (every channel when `None`) that `pred` selects.
    pub(crate) fn cancel_where(
        self: &Arc<Self>,
        turn: &mut Turn,
        channel: Option<&Channel>,
        pred: impl Fn(&Command, u8) -> bool,
        reason: &str,
    ) {
        let decisions: Vec<(Channel, Decision)> = (turn.state.lanes.iter_mut())
            .filter(|(c, _)| channel.is_none_or(|wanted| wanted == *c))
            .map(|(c, lane)| (c.clone(), lane.cancel_where(&pred, reason)))
            .collect();
        for (channel, decision) in decisions {
            self.carry_out(&mut turn.state, &channel, decision);
        }
    }

    /// The notices from now on, in the order they were decided (taken once, at start-up, by
    /// the websocket layer; until then, and for a second taker, none are kept).
    pub fn notices(&self) -> mpsc::UnboundedReceiver<Notice> {
        let (sender, receiver) = mpsc::unbounded_channel();
        let _ = self.notices.set(sender);
        receiver
    }

    /// Queues `notice` (called within a turn, so notices keep the order of the decisions).
    pub(crate) fn notify(&self, notice: Notice) {
        if let Some(notices) = self.notices.get() {
            let _ = notices.send(notice);
        }
    }

    fn tell_sender(&self, state: &State, command: &Command, outcome: &Outcome) {
        if matches!(outcome, Outcome::Done) {
            return;
        }
        if let Some(client) = command.act.client {
            // Everything of a visitor's act older than their stop or page change ended by it.
            let ended_by_visitor = state.visitor_cuts.cut_off(&command.act).is_some();
            self.notify(Notice::NotCarriedOut {
                client,
                command: command.clone(),
                outcome: outcome.clone(),
                ended_by_visitor,
            });
        }
    }

    /// Tells the kiosks who speaks now, in the turn that changed it: two changes racing on
    /// two threads reach the kiosks in the order they happened.
    fn tell_speaking(&self, state: &mut State) {
        let running = (state.lanes.get(&Channel::Speech)).and_then(|lane| lane.running());
        let now = running.map(|c| Speaking {
            source: c.act.source,
            client: c.act.client,
        });
        // A cancelled command ends after its successor started: kiosks hear only changes.
        if state.speaking_told != now {
            state.speaking_told = now;
            self.notify(Notice::Speaking(now));
        }
    }

    /// The `SAY` on the speech channel now (its id and text), if one runs: what a caption
    /// that fell behind the events shows instead of guessing (`ws::captions`).
    pub fn saying_now(&self) -> Option<(u64, Arc<str>)> {
        let state = lock(&self.state);
        let running = state.lanes.get(&Channel::Speech)?.running()?;
        let text = running.args.say_text().or(running.arg.as_deref())?;
        Some((running.id, Arc::from(text)))
    }

    /// Every channel that has carried a command: what runs and what waits, by channel name.
    pub fn channel_status(&self) -> std::collections::BTreeMap<String, LaneStatus> {
        (lock(&self.state).lanes.iter())
            .map(|(channel, lane)| (channel.to_string(), lane.status()))
            .collect()
    }

    /// Kiosk `client` joined: it is told who speaks now among the notices, after the changes
    /// decided before it and before those decided after (queued within a turn).
    pub fn kiosk_joined(&self, client: u64) {
        let _turn = lock(&self.state);
        self.notify(Notice::KioskJoined(client));
    }
}
