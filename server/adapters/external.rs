//! [`ExternalAdapters`], the adapter named `ws` in `docent.yaml`: commands for external adapter
//! processes (a robot's own speech or drive module, in any language) connected over the
//! websocket with role `adapter`.
//!
//! Each command goes, as soon as it is dispatched, to every connected adapter that declared its
//! verb; each adapter receives its commands in dispatch order and carries them out in that
//! order. The first `done` completes a command (later answers from other adapters are accepted
//! and ignored); it fails when every recipient failed, left or timed out.
//!
//! The answer clock catches missing or dead adapters, not long work: each connection has one
//! clock, on the oldest command it still owes an answer for, started when that command became
//! the oldest. `started` stops it (the adapter has taken the command on; a dead process is then
//! caught by the websocket's ping timeout); `done` or `failed` moves it to the next command.

use std::collections::{HashMap, VecDeque};
use std::sync::{Arc, Mutex, Weak};
use std::time::Duration;

use tokio::sync::Notify;
use tokio::time::Instant;
use tokio_util::sync::CancellationToken;

use crate::adapters::{Adapter, AdapterStatus, CancelScope, Command, Outcome, Reply};
use crate::lifecycle::Lifecycle;
use crate::sync::lock;
use crate::wire::outbox::{Frame, Outbox};
use docent_protocol::frames::cancel_frame;

/// How many settled command ids are remembered for late answers.
const RECENTLY_SETTLED: usize = 1024;

/// A connected adapter process.
struct Connection {
    client: u64,
    verbs: Vec<String>,
    outbox: Outbox,
    /// Commands it owes an answer for, oldest first.
    owed: VecDeque<u64>,
    /// When the oldest owed command became the oldest.
    head_since: Instant,
    /// Wakes the connection's clock when its oldest owed command changes.
    wake: Arc<Notify>,
}

impl Connection {
    fn owe(&mut self, id: u64) {
        self.owed.push_back(id);
        if self.owed.len() == 1 {
            self.head_since = Instant::now();
            self.wake.notify_one();
        }
    }

    fn forget(&mut self, id: u64) {
        let was_head = self.owed.front() == Some(&id);
        self.owed.retain(|&o| o != id);
        if was_head {
            self.head_since = Instant::now();
            self.wake.notify_one();
        }
    }
}

struct Pending {
    reply: Reply,
    recipients: Vec<u64>,
    started: bool,
}

#[derive(Default)]
struct Registry {
    connections: Vec<Connection>,
    pending: HashMap<u64, Pending>,
    /// Ids of commands settled lately, so that a second adapter's answer is not an error.
    recently_settled: VecDeque<u64>,
}

impl Registry {
    fn connection(&mut self, client: u64) -> Option<&mut Connection> {
        self.connections.iter_mut().find(|c| c.client == client)
    }

    /// Takes `client`'s answer to `id`; returns the entry when that settles the command.
    fn take_answer(&mut self, client: u64, id: u64, outcome: &Outcome) -> Option<Pending> {
        let entry = self.pending.get_mut(&id)?;
        entry.recipients.retain(|&c| c != client);
        if let Some(conn) = self.connection(client) {
            conn.forget(id);
        }
        let entry = self.pending.get(&id)?;
        if !matches!(outcome, Outcome::Done) && !entry.recipients.is_empty() {
            return None;
        }
        self.settle(id)
    }

    /// Removes a command from the books; the caller reports its outcome.
    fn settle(&mut self, id: u64) -> Option<Pending> {
        let entry = self.pending.remove(&id)?;
        for &client in &entry.recipients {
            if let Some(conn) = self.connection(client) {
                conn.forget(id);
            }
        }
        if self.recently_settled.len() == RECENTLY_SETTLED {
            self.recently_settled.pop_front();
        }
        self.recently_settled.push_back(id);
        Some(entry)
    }
}

/// The registry of adapter connections and the commands they owe an answer for.
pub struct ExternalAdapters {
    inner: Arc<Inner>,
}

struct Inner {
    registry: Mutex<Registry>,
    timeout: Duration,
    /// The site's speech rate, for a `SAY`'s `speaking_ms`.
    rate_wpm: u32,
    life: Lifecycle,
}

/// Why an adapter's answer was not taken.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum AnswerError {
    /// No command with this id is waiting for this client's answer.
    #[error("no command {0} is waiting for an answer from this adapter")]
    UnknownCommand(u64),
}

impl ExternalAdapters {
    /// An empty registry; commands nobody takes on fail after `timeout`; a `SAY` is sent
    /// with its speaking time at `rate_wpm` words a minute.
    pub fn new(timeout: Duration, rate_wpm: u32, life: Lifecycle) -> Self {
        let inner = Inner {
            registry: Mutex::default(),
            timeout,
            rate_wpm,
            life,
        };
        ExternalAdapters {
            inner: Arc::new(inner),
        }
    }

    /// Registers a connected adapter serving `verbs` and starts its answer clock.
    pub fn connect(&self, client: u64, verbs: Vec<String>, outbox: Outbox) {
        let wake = Arc::new(Notify::new());
        let conn = Connection {
            client,
            verbs,
            outbox,
            owed: VecDeque::new(),
            head_since: Instant::now(),
            wake: Arc::clone(&wake),
        };
        lock(&self.inner.registry).connections.push(conn);
        let clock = run_clock(
            Arc::downgrade(&self.inner),
            client,
            wake,
            self.inner.life.shutdown.clone(),
        );
        self.inner.life.spawn(clock);
    }

    /// Forgets a connection; commands only it was carrying out fail.
    pub fn disconnect(&self, client: u64) {
        let mut registry = lock(&self.inner.registry);
        let Some(at) = registry.connections.iter().position(|c| c.client == client) else {
            return;
        };
        let conn = registry.connections.remove(at);
        conn.wake.notify_one();
        let outcome = Outcome::Failed("the adapter disconnected".into());
        let settled: Vec<Pending> = conn
            .owed
            .iter()
            .filter_map(|&id| registry.take_answer(client, id, &outcome))
            .collect();
        drop(registry);
        for entry in settled {
            entry.reply.finish(outcome.clone());
        }
    }

    /// Takes an adapter's `started` report.
    pub fn started(&self, client: u64, id: u64) -> Result<(), AnswerError> {
        let mut registry = lock(&self.inner.registry);
        let Some(entry) = registry
            .pending
            .get_mut(&id)
            .filter(|p| p.recipients.contains(&client))
        else {
            return late_answer(&registry, id);
        };
        let first = !std::mem::replace(&mut entry.started, true);
        if let Some(conn) = registry.connection(client) {
            conn.wake.notify_one();
        }
        if first && let Some(entry) = registry.pending.get(&id) {
            entry.reply.started();
        }
        Ok(())
    }

    /// Takes an adapter's `done` or `failed` answer.
    pub fn answer(&self, client: u64, id: u64, outcome: Outcome) -> Result<(), AnswerError> {
        let mut registry = lock(&self.inner.registry);
        if !registry
            .pending
            .get(&id)
            .is_some_and(|p| p.recipients.contains(&client))
        {
            return late_answer(&registry, id);
        }
        let settled = registry.take_answer(client, id, &outcome);
        drop(registry);
        if let Some(entry) = settled {
            entry.reply.finish(outcome);
        }
        Ok(())
    }
}

/// An answer for a command no longer waiting: fine if it was settled lately (another adapter
/// answered first, or it was cancelled or timed out), an error otherwise.
fn late_answer(registry: &Registry, id: u64) -> Result<(), AnswerError> {
    // Still pending for others (this adapter timed out on it, say), or settled lately.
    match registry.pending.contains_key(&id) || registry.recently_settled.contains(&id) {
        true => Ok(()),
        false => Err(AnswerError::UnknownCommand(id)),
    }
}

/// One connection's answer clock: fails the oldest command the connection owes, for that
/// connection, when it has neither been answered nor started within the timeout.
async fn run_clock(
    inner: Weak<Inner>,
    client: u64,
    wake: Arc<Notify>,
    shutdown: CancellationToken,
) {
    loop {
        let deadline = {
            let Some(inner) = inner.upgrade() else { return };
            let mut registry = lock(&inner.registry);
            let Some(conn) = registry.connection(client) else {
                return;
            };
            let (head, since) = (conn.owed.front().copied(), conn.head_since);
            match head {
                Some(id) if registry.pending.get(&id).is_some_and(|p| !p.started) => {
                    Some((id, since + inner.timeout))
                }
                _ => None,
            }
        };
        let expired = async {
            match deadline {
                Some((id, at)) => {
                    tokio::time::sleep_until(at).await;
                    id
                }
                None => std::future::pending().await,
            }
        };
        tokio::select! {
            () = wake.notified() => continue,
            () = shutdown.cancelled() => return,
            id = expired => {
                let Some(inner) = inner.upgrade() else { return };
                let reason = format!("no adapter answered within {:?}", inner.timeout);
                let outcome = Outcome::Failed(reason);
                let settled = lock(&inner.registry).take_answer(client, id, &outcome);
                if let Some(entry) = settled {
                    entry.reply.finish(outcome);
                }
            }
        }
    }
}

impl Adapter for ExternalAdapters {
    fn name(&self) -> &'static str {
        "ws"
    }

    fn submit(&self, command: Command, reply: Reply) {
        let id = command.id;
        let verb = command.verb.as_str();
        let mut registry = lock(&self.inner.registry);
        let recipients: Vec<u64> = (registry.connections.iter())
            .filter(|c| c.verbs.iter().any(|v| v == verb))
            .map(|c| c.client)
            .collect();
        if recipients.is_empty() {
            drop(registry);
            let reason = format!("no adapter for {verb} is connected");
            return reply.finish(Outcome::Failed(reason));
        }
        // On the books before the frame goes out, so that a fast answer, a stop or a
        // disconnect always finds it.
        let frame = Frame::from(command.frame_at_rate(self.inner.rate_wpm));
        registry.pending.insert(
            id,
            Pending {
                reply,
                recipients: recipients.clone(),
                started: false,
            },
        );
        let mut unreachable = Vec::new();
        for &client in &recipients {
            let Some(conn) = registry.connection(client) else {
                continue;
            };
            conn.owe(id);
            if !conn.outbox.send(frame.clone()) {
                unreachable.push(client);
            }
        }
        let outcome =
            Outcome::Failed("the adapter could not take the command (gone or too slow)".into());
        let settled: Vec<Pending> = unreachable
            .into_iter()
            .filter_map(|client| registry.take_answer(client, id, &outcome))
            .collect();
        drop(registry);
        for entry in settled {
            entry.reply.finish(outcome.clone());
        }
    }

    fn cancel(&self, scope: CancelScope<'_>, reason: &str) {
        let verbs: Option<Vec<String>> = match scope {
            CancelScope::All => None,
            CancelScope::Verb(v) => Some(vec![v.to_string()]),
        };
        let frame = Frame::from(cancel_frame(verbs.as_deref(), reason));
        let mut registry = lock(&self.inner.registry);
        for c in &registry.connections {
            if verbs
                .as_ref()
                .is_none_or(|vs| vs.iter().any(|v| c.verbs.contains(v)))
            {
                c.outbox.send(frame.clone());
            }
        }
        let mut ids: Vec<u64> = (registry.pending.iter())
            .filter(|(_, p)| match scope {
                CancelScope::All => true,
                CancelScope::Verb(v) => &p.reply.command().verb == v,
            })
            .map(|(&id, _)| id)
            .collect();
        // In dispatch order, so the log reads naturally.
        ids.sort_unstable();
        let cancelled: Vec<Pending> = ids
            .into_iter()
            .filter_map(|id| registry.settle(id))
            .collect();
        drop(registry);
        for entry in cancelled {
            entry.reply.finish(Outcome::Cancelled(reason.to_owned()));
        }
    }

    fn status(&self) -> AdapterStatus {
        let registry = lock(&self.inner.registry);
        let oldest = registry
            .pending
            .keys()
            .min()
            .and_then(|id| registry.pending.get(id));
        AdapterStatus {
            queued: registry.pending.len(),
            current: oldest.map(|p| p.reply.command().current()),
        }
    }
}
