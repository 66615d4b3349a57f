//! Sending an act's commands in order. Commands before the first `WAIT` go out at once, on the
//! trigger's own path; the rest run in a task: `WAIT` alone waits until all of the act's
//! earlier commands have ended, `WAIT 2s` pauses. A stop ends the sequence and reports its
//! unsent commands as cancelled; so does a failed earlier command at a `WAIT`, or a drive that
//! another act's replaced (the rest would act on a false premise, e.g. show an exhibit's page
//! although the robot never drove there).
//! A `DRIVE_STOP` after a `WAIT` preempts everything when it is reached; an interrupting
//! trigger drops the speech this sequence has not sent yet.

use std::sync::Arc;

use futures_util::future::join_all;
use tokio::sync::oneshot;
use tokio_util::sync::CancellationToken;

use crate::adapters::{Command, Outcome, Reply};
use crate::content::{Args, Verb};
use crate::dispatch::Dispatcher;
use crate::dispatch::state::{State, Turn};
use crate::events::{CommandSent, EventKind};

/// One act's commands on their way out.
pub struct Sequence {
    dispatcher: Arc<Dispatcher>,
    /// Cancelled by a stop.
    stop: CancellationToken,
    /// Cancelled by an interrupting trigger: unsent speech is dropped.
    speech: CancellationToken,
    /// Outcomes of sent commands, for a later `WAIT` (only kept when the act has one).
    outstanding: Option<Vec<(String, oneshot::Receiver<Outcome>)>>,
}

impl Sequence {
    /// A sequence for an act; `waits` says whether it has a `WAIT`.
    pub fn new(
        dispatcher: Arc<Dispatcher>,
        stop: CancellationToken,
        speech: CancellationToken,
        waits: bool,
    ) -> Self {
        Sequence {
            dispatcher,
            stop,
            speech,
            outstanding: waits.then(Vec::new),
        }
    }

    /// Sends `commands` up to the first `WAIT` in the trigger's own turn, then hands the
    /// rest to a task.
    pub fn start(mut self, turn: &mut Turn, commands: Vec<Command>) {
        let mut rest = commands.into_iter();
        while let Some(command) = rest.next() {
            if command.verb == Verb::Wait {
                let life = self.dispatcher.life().clone();
                life.spawn(self.run(command, rest));
                return;
            }
            self.send(turn, command);
        }
    }

    fn send(&mut self, turn: &mut Turn, command: Command) {
        if command.verb == Verb::Say && self.speech.is_cancelled() {
            let reason = "interrupted by a later act before it was said".to_owned();
            return self.drop_unsent(&turn.state, command, reason);
        }
        if command.verb == Verb::Say
            && let Some(reason) = turn.state.visitor_cuts.cut_off(&command.act)
        {
            return self.drop_unsent(&turn.state, command, reason);
        }
        match &mut self.outstanding {
            Some(outstanding) => {
                let (tx, rx) = oneshot::channel();
                outstanding.push((command.verb.to_string(), rx));
                self.dispatcher.send(turn, command, Some(tx));
            }
            None => self.dispatcher.send(turn, command, None),
        }
    }

    fn drop_unsent(&self, state: &State, command: Command, reason: String) {
        self.dispatcher
            .report(state, command, None, Outcome::Cancelled(reason));
    }

    async fn run(mut self, first_wait: Command, mut rest: std::vec::IntoIter<Command>) {
        let dispatcher = Arc::clone(&self.dispatcher);
        let mut next = Some(first_wait);
        let abandoned = loop {
            let Some(command) = next.take().or_else(|| rest.next()) else {
                return;
            };
            if self.stop.is_cancelled() {
                next = Some(command);
                break "stopped before it was sent".to_owned();
            }
            match command.verb {
                Verb::Wait => {
                    if let Err(reason) = self.wait(command).await {
                        break reason;
                    }
                }
                Verb::DriveStop => {
                    // What this act started before is stopped on purpose: a later WAIT does
                    // not wait for it, nor take its cancellation for a failure.
                    if let Some(outstanding) = &mut self.outstanding {
                        outstanding.clear();
                    }
                    let mut turn = dispatcher.turn();
                    let act = &command.act;
                    let reason = format!("DRIVE_STOP in act {}", act.label);
                    dispatcher.stop_in(&mut turn, act.source, &reason);
                    // This act goes on after its own stop.
                    self.stop = turn.state.epoch.clone();
                    self.send(&mut turn, command);
                }
                _ => self.send(&mut dispatcher.turn(), command),
            }
        };
        let turn = dispatcher.turn();
        for command in next.into_iter().chain(rest) {
            self.drop_unsent(&turn.state, command, abandoned.clone());
        }
    }

    /// Runs one `WAIT`; on a stop or an earlier failure, why the rest is not sent.
    async fn wait(&mut self, command: Command) -> Result<(), String> {
        let hub = self.dispatcher.hub().clone();
        hub.publish(EventKind::CommandSent(CommandSent {
            command: command.id,
            act: Arc::clone(&command.act),
            verb: command.verb.to_string(),
            arg: command.arg.as_deref().map(str::to_owned),
            args: Arc::clone(&command.args),
            adapter: "dispatcher".into(),
        }));
        let pause = match *command.args {
            Args::Wait { pause } => pause,
            _ => None,
        };
        let reply = Reply::new(hub, command, None);
        reply.started();
        // A pause leaves earlier commands outstanding for a later plain WAIT to wait for.
        let earlier = match pause {
            Some(_) => Vec::new(),
            None => self
                .outstanding
                .as_mut()
                .map(std::mem::take)
                .unwrap_or_default(),
        };
        let waited = async {
            match pause {
                Some(pause) => {
                    tokio::time::sleep(pause).await;
                    Ok(())
                }
                None => first_failure(earlier).await,
            }
        };
        // A stop cancels the earlier commands too: it must win over "they all ended".
        let result = tokio::select! {
            biased;
            () = self.stop.cancelled() => Err(None),
            result = waited => result.map_err(Some),
        };
        match result {
            Ok(()) => {
                reply.finish(Outcome::Done);
                Ok(())
            }
            Err(Some(outcome)) => {
                let why = match &outcome {
                    Outcome::Failed(why) | Outcome::Cancelled(why) => why.clone(),
                    Outcome::Done => String::new(),
                };
                reply.finish(outcome);
                Err(format!("not sent: {why}"))
            }
            Err(None) => {
                reply.finish(Outcome::Cancelled("stopped".into()));
                Err("stopped before it was sent".to_owned())
            }
        }
    }
}

/// The drive verbs whose cancellation ends the rest of their act at a `WAIT`.
const DRIVES: [&str; 2] = ["SET_WAYPOINT", "DRIVE_START"];

/// Waits for every earlier command; the first that failed, or a drive that was cancelled
/// (replaced by another act's: the rest would act on a false premise), as the `WAIT`'s own
/// outcome.
async fn first_failure(earlier: Vec<(String, oneshot::Receiver<Outcome>)>) -> Result<(), Outcome> {
    let (verbs, outcomes): (Vec<String>, Vec<_>) = earlier.into_iter().unzip();
    let outcomes = join_all(outcomes).await;
    for (verb, outcome) in verbs.iter().zip(outcomes) {
        match outcome {
            // Speech cut short by an interrupting trigger still ended; a stop is seen
            // through the stop token.
            Ok(Outcome::Done) => {}
            // A drive cancelled by another act's (its channel replaces) leaves the robot
            // elsewhere than this act expects; anything else cut short still ended.
            Ok(Outcome::Cancelled(why)) if DRIVES.contains(&verb.as_str()) => {
                return Err(Outcome::Cancelled(format!(
                    "an earlier {verb} of this act was cancelled ({why})"
                )));
            }
            Ok(Outcome::Cancelled(_)) => {}
            Ok(Outcome::Failed(why)) => {
                return Err(Outcome::Failed(format!(
                    "an earlier {verb} of this act did not succeed ({why})"
                )));
            }
            Err(_) => {
                return Err(Outcome::Failed(format!(
                    "an earlier {verb} of this act was lost"
                )));
            }
        }
    }
    Ok(())
}
