//! The `ws` adapter: commands for external adapter processes (a robot's own speech or drive
//! module, in any language) connected over the websocket with role `adapter`.
//!
//! Each command goes, as soon as it is dispatched, to every connected adapter that declared its
//! verb; they receive commands in dispatch order and must carry them out in that order. The
//! first `done` completes the command (later answers from other adapters are accepted and
//! ignored); it fails when every recipient failed or left, or when none answers (`started`,
//! `done` or `failed`) within the configured time once it is that command's turn: the clock of
//! a command starts when the previous command of the same verb was answered or started.

use std::collections::{HashMap, VecDeque};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use tokio::sync::{mpsc, oneshot};

use crate::adapters::{Adapter, AdapterStatus, CancelScope, Command, Outcome, Reply};
use crate::content::Verb;
use crate::lifecycle::Lifecycle;
use crate::sync::lock;
use crate::ws::outbox::{Frame, Outbox};
use crate::ws::protocol::{cancel_frame, command_frame};

/// A connected adapter process.
struct Connection {
    client: u64,
    verbs: Vec<String>,
    outbox: Outbox,
}

struct Pending {
    reply: Reply,
    recipients: Vec<u64>,
    started: bool,
    settled: Option<oneshot::Sender<()>>,
}

/// How many settled command ids are remembered for late answers.
const RECENTLY_SETTLED: usize = 1024;

/// A command id and the signal that it was answered.
type Clocked = (u64, oneshot::Receiver<()>);

/// The registry of adapter connections and the commands they owe an answer for.
pub struct WsAdapters {
    inner: Arc<Inner>,
}

struct Inner {
    connections: Mutex<Vec<Connection>>,
    pending: Mutex<HashMap<u64, Pending>>,
    /// Ids of commands settled lately, so that a second adapter's answer is not an error.
    recently_settled: Mutex<VecDeque<u64>>,
    /// Per verb, the queue of commands whose answer clocks run one after another.
    clocks: Mutex<HashMap<Verb, mpsc::UnboundedSender<Clocked>>>,
    timeout: Duration,
    life: Lifecycle,
}

/// Why an adapter's answer was not taken.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum AnswerError {
    /// No command with this id is waiting for this client's answer.
    #[error("no command {0} is waiting for an answer from this adapter")]
    UnknownCommand(u64),
}

impl WsAdapters {
    /// An empty registry; unanswered commands fail after `timeout`.
    pub fn new(timeout: Duration, life: Lifecycle) -> Self {
        let inner = Inner {
            connections: Mutex::new(Vec::new()),
            pending: Mutex::new(HashMap::new()),
            recently_settled: Mutex::new(VecDeque::with_capacity(RECENTLY_SETTLED)),
            clocks: Mutex::new(HashMap::new()),
            timeout,
            life,
        };
        WsAdapters {
            inner: Arc::new(inner),
        }
    }

    /// Registers a connected adapter serving `verbs`.
    pub fn connect(&self, client: u64, verbs: Vec<String>, outbox: Outbox) {
        lock(&self.inner.connections).push(Connection {
            client,
            verbs,
            outbox,
        });
    }

    /// Forgets a connection; commands only it was carrying out fail.
    pub fn disconnect(&self, client: u64) {
        lock(&self.inner.connections).retain(|c| c.client != client);
        let owed: Vec<u64> = lock(&self.inner.pending)
            .iter()
            .filter(|(_, p)| p.recipients.contains(&client))
            .map(|(&id, _)| id)
            .collect();
        for id in owed {
            let _ = self.answer(
                client,
                id,
                Outcome::Failed("the adapter disconnected".into()),
            );
        }
    }

    /// Takes an adapter's `started` report.
    pub fn started(&self, client: u64, id: u64) -> Result<(), AnswerError> {
        let mut pending = lock(&self.inner.pending);
        let Some(entry) = pending
            .get_mut(&id)
            .filter(|p| p.recipients.contains(&client))
        else {
            return self.inner.late_answer(id);
        };
        if !entry.started {
            entry.started = true;
            entry.reply.started();
            // The adapter has taken the command on: the answer clock (which catches missing or
            // dead adapters) stops, and the next command's clock starts. A long drive or
            // utterance may take as long as it takes; a disconnect or a stop still ends it.
            if let Some(settled) = entry.settled.take() {
                let _ = settled.send(());
            }
        }
        Ok(())
    }

    /// Takes an adapter's `done` or `failed` answer.
    pub fn answer(&self, client: u64, id: u64, outcome: Outcome) -> Result<(), AnswerError> {
        let mut pending = lock(&self.inner.pending);
        let Some(entry) = pending
            .get_mut(&id)
            .filter(|p| p.recipients.contains(&client))
        else {
            return self.inner.late_answer(id);
        };
        entry.recipients.retain(|&c| c != client);
        let settles = matches!(outcome, Outcome::Done) || entry.recipients.is_empty();
        if settles && let Some(entry) = pending.remove(&id) {
            drop(pending);
            self.inner.settle(id, entry, outcome);
        }
        Ok(())
    }
}

impl Inner {
    /// Starts the answer clock of command `id` behind earlier commands of the same verb.
    fn start_clock(self: &Arc<Self>, verb: &Verb, id: u64, settled: oneshot::Receiver<()>) {
        let mut clocks = lock(&self.clocks);
        let queue = clocks.entry(verb.clone()).or_insert_with(|| {
            let (tx, rx) = mpsc::unbounded_channel();
            self.life.spawn(run_clock(
                Arc::downgrade(self),
                rx,
                self.life.shutdown.clone(),
            ));
            tx
        });
        let _ = queue.send((id, settled));
    }

    fn expire(&self, id: u64) {
        let mut pending = lock(&self.pending);
        // A command an adapter has started is no longer on the clock.
        if pending.get(&id).is_some_and(|p| !p.started)
            && let Some(entry) = pending.remove(&id)
        {
            drop(pending);
            let reason = format!("no adapter answered within {:?}", self.timeout);
            self.settle(id, entry, Outcome::Failed(reason));
        }
    }

    fn settle(&self, id: u64, mut entry: Pending, outcome: Outcome) {
        if let Some(settled) = entry.settled.take() {
            let _ = settled.send(());
        }
        entry.reply.finish(outcome);
        let mut recent = lock(&self.recently_settled);
        if recent.len() == RECENTLY_SETTLED {
            recent.pop_front();
        }
        recent.push_back(id);
    }

    /// An answer for a command no longer waiting: fine if another adapter already settled it
    /// (several adapters may serve one verb), an error otherwise.
    fn late_answer(&self, id: u64) -> Result<(), AnswerError> {
        match lock(&self.recently_settled).contains(&id) {
            true => Ok(()),
            false => Err(AnswerError::UnknownCommand(id)),
        }
    }
}

async fn run_clock(
    inner: std::sync::Weak<Inner>,
    mut queue: mpsc::UnboundedReceiver<Clocked>,
    shutdown: tokio_util::sync::CancellationToken,
) {
    loop {
        let (id, settled) = tokio::select! {
            next = queue.recv() => match next { Some(next) => next, None => return },
            () = shutdown.cancelled() => return,
        };
        let Some(timeout) = inner.upgrade().map(|i| i.timeout) else {
            return;
        };
        let answered = tokio::select! {
            r = tokio::time::timeout(timeout, settled) => r.is_ok(),
            () = shutdown.cancelled() => return,
        };
        if !answered && let Some(inner) = inner.upgrade() {
            inner.expire(id);
        }
    }
}

impl Adapter for WsAdapters {
    fn name(&self) -> &'static str {
        "ws"
    }

    fn submit(&self, command: Command, reply: Reply) {
        let verb = command.verb.as_str();
        let frame: Frame = Frame::from(command_frame(&command));
        let recipients: Vec<u64> = lock(&self.inner.connections)
            .iter()
            .filter(|c| c.verbs.iter().any(|v| v == verb))
            .filter(|c| c.outbox.send(frame.clone()))
            .map(|c| c.client)
            .collect();
        if recipients.is_empty() {
            let reason = format!("no adapter for {verb} is connected");
            return reply.finish(Outcome::Failed(reason));
        }
        let (settled_tx, settled_rx) = oneshot::channel();
        let id = command.id;
        let pending = Pending {
            reply,
            recipients,
            started: false,
            settled: Some(settled_tx),
        };
        lock(&self.inner.pending).insert(id, pending);
        self.inner.start_clock(&command.verb, id, settled_rx);
    }

    fn cancel(&self, scope: CancelScope<'_>, reason: &str) {
        let verbs: Option<Vec<String>> = match scope {
            CancelScope::All => None,
            CancelScope::Verb(v) => Some(vec![v.to_string()]),
        };
        let frame: Frame = Frame::from(cancel_frame(verbs.as_deref(), reason));
        for c in lock(&self.inner.connections).iter() {
            if verbs
                .as_ref()
                .is_none_or(|vs| vs.iter().any(|v| c.verbs.contains(v)))
            {
                c.outbox.send(frame.clone());
            }
        }
        let mut pending = lock(&self.inner.pending);
        let mut ids: Vec<u64> = pending
            .iter()
            .filter(|(_, p)| match scope {
                CancelScope::All => true,
                CancelScope::Verb(v) => &p.reply.command().verb == v,
            })
            .map(|(&id, _)| id)
            .collect();
        // In dispatch order, so the log reads naturally.
        ids.sort_unstable();
        let cancelled: Vec<(u64, Pending)> = ids
            .iter()
            .filter_map(|&id| Some((id, pending.remove(&id)?)))
            .collect();
        drop(pending);
        for (id, entry) in cancelled {
            self.inner
                .settle(id, entry, Outcome::Cancelled(reason.to_owned()));
        }
    }

    fn status(&self) -> AdapterStatus {
        let pending = lock(&self.inner.pending);
        let oldest = pending.keys().min().and_then(|id| pending.get(id));
        AdapterStatus {
            queued: pending.len(),
            current: oldest.map(|p| p.reply.command().describe()),
        }
    }
}
