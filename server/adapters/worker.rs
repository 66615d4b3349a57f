//! A queue that runs one command at a time, in order, with cancellation by verb or wholesale.
//! The speech, log and drive adapters are all "a worker plus what one command means".
//!
//! The queue is bounded ([`WORKER_CAPACITY`]): the dispatcher hands each channel's commands
//! over one at a time, so a full queue means something is wrong, and the command fails with
//! a reason instead of piling up.

use std::collections::HashMap;
use std::future::Future;
use std::sync::{Arc, Mutex, OnceLock};

use tokio::sync::mpsc;
use tokio_util::sync::CancellationToken;

use crate::adapters::{Adapter, AdapterStatus, CancelScope, Command, Outcome, Reply};
use crate::content::Verb;
use crate::lifecycle::Lifecycle;
use crate::sync::lock;

/// How many commands may wait in one worker's queue.
pub const WORKER_CAPACITY: usize = 64;

/// What one command means to a particular adapter.
pub trait Task: Send + Sync + 'static {
    /// Carries out `command`. Dropping the future must abandon the work (kill a process, stop
    /// the motors): that is how cancellation happens.
    fn run(&self, command: &Command) -> impl Future<Output = Outcome> + Send;
}

/// A cancellation that remembers why it happened.
#[derive(Default)]
struct Cancel {
    token: CancellationToken,
    reason: OnceLock<String>,
}

impl Cancel {
    fn reason(&self) -> String {
        self.reason
            .get()
            .cloned()
            .unwrap_or_else(|| "cancelled".to_owned())
    }
}

struct Job {
    command: Command,
    reply: Reply,
    cancel: Arc<Cancel>,
}

/// A serial queue in front of a [`Task`]; an [`Adapter`] by itself.
pub struct Worker {
    name: &'static str,
    tx: mpsc::Sender<Job>,
    /// One cancellation per verb, replaced after use, so cancelling speech leaves other verbs.
    cancels: Mutex<HashMap<Verb, Arc<Cancel>>>,
    status: Arc<Mutex<AdapterStatus>>,
}

impl Worker {
    /// Starts the worker task for `task`; `name` is the adapter's name.
    pub fn start<T: Task>(name: &'static str, task: T, life: &Lifecycle) -> Self {
        let (tx, rx) = mpsc::channel(WORKER_CAPACITY);
        let status = Arc::new(Mutex::new(AdapterStatus::default()));
        life.spawn(run_queue(
            task,
            rx,
            Arc::clone(&status),
            life.shutdown.clone(),
        ));
        Worker {
            name,
            tx,
            cancels: Mutex::new(HashMap::new()),
            status,
        }
    }

    fn enqueue(&self, command: Command, reply: Reply) {
        let cancel = {
            let mut cancels = lock(&self.cancels);
            Arc::clone(cancels.entry(command.verb.clone()).or_default())
        };
        lock(&self.status).queued += 1;
        let job = Job {
            command,
            reply,
            cancel,
        };
        match self.tx.try_send(job) {
            Ok(()) => {}
            Err(mpsc::error::TrySendError::Full(job)) => {
                lock(&self.status).queued -= 1;
                let reason = format!(
                    "the {} adapter already has {WORKER_CAPACITY} commands waiting",
                    self.name
                );
                job.reply.finish(Outcome::Failed(reason));
            }
            Err(mpsc::error::TrySendError::Closed(job)) => {
                lock(&self.status).queued -= 1;
                job.reply
                    .finish(Outcome::Cancelled("the server is shutting down".into()));
            }
        }
    }

    fn cancel_within(&self, scope: CancelScope<'_>, reason: &str) {
        let mut cancels = lock(&self.cancels);
        let taken: Vec<Arc<Cancel>> = match scope {
            CancelScope::All => cancels.drain().map(|(_, c)| c).collect(),
            CancelScope::Verb(verb) => cancels.remove(verb).into_iter().collect(),
        };
        drop(cancels);
        for cancel in taken {
            let _ = cancel.reason.set(reason.to_owned());
            cancel.token.cancel();
        }
    }
}

impl Adapter for Worker {
    fn name(&self) -> &'static str {
        self.name
    }

    /// Queues a command behind the ones already queued.
    fn submit(&self, command: Command, reply: Reply) {
        self.enqueue(command, reply);
    }

    /// Cancels queued and running commands within `scope`.
    fn cancel(&self, scope: CancelScope<'_>, reason: &str) {
        self.cancel_within(scope, reason);
    }

    /// Queue length and current command.
    fn status(&self) -> AdapterStatus {
        lock(&self.status).clone()
    }
}

async fn run_queue<T: Task>(
    task: T,
    mut rx: mpsc::Receiver<Job>,
    status: Arc<Mutex<AdapterStatus>>,
    shutdown: CancellationToken,
) {
    loop {
        let job = tokio::select! {
            job = rx.recv() => match job { Some(job) => job, None => return },
            () = shutdown.cancelled() => break,
        };
        lock(&status).queued -= 1;
        let Job {
            command,
            reply,
            cancel,
        } = job;
        if cancel.token.is_cancelled() {
            reply.finish(Outcome::Cancelled(cancel.reason()));
            continue;
        }
        lock(&status).current = Some(command.current());
        reply.started();
        let outcome = tokio::select! {
            outcome = task.run(&command) => outcome,
            () = cancel.token.cancelled() => Outcome::Cancelled(cancel.reason()),
            () = shutdown.cancelled() => Outcome::Cancelled("the server is shutting down".into()),
        };
        lock(&status).current = None;
        reply.finish(outcome);
    }
    // Shutting down: answer whatever is still queued so nothing vanishes from the log.
    rx.close();
    while let Ok(job) = rx.try_recv() {
        job.reply
            .finish(Outcome::Cancelled("the server is shutting down".into()));
    }
}
