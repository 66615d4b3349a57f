//! Shutdown plumbing shared by every long-lived task: one cancellation token that says "stop
//! now" and one task tracker that lets shutdown wait for every spawned task.

use std::future::Future;

use tokio_util::sync::CancellationToken;
use tokio_util::task::TaskTracker;

/// Handles every spawner needs. Cheap to clone.
#[derive(Clone, Default)]
pub struct Lifecycle {
    /// Cancelled when the server shuts down.
    pub shutdown: CancellationToken,
    /// Every task spawned for the server; shutdown waits for it.
    pub tracker: TaskTracker,
}

impl Lifecycle {
    /// A fresh lifecycle.
    pub fn new() -> Self {
        Self::default()
    }

    /// Spawns a tracked task.
    pub fn spawn<F>(&self, task: F)
    where
        F: Future<Output = ()> + Send + 'static,
    {
        self.tracker.spawn(task);
    }
}
