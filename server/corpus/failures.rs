//! The corpus writer's write failures (a full disk, say): counted, said loudly at once and
//! then at most every 10 s, retried at a bounded pace, and summed up at the end of the run.
//! The writer keeps going, since space may come back.

use std::io;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// How often writing is tried again after it failed.
const RETRY_INTERVAL: Duration = Duration::from_secs(1);

/// Write failures (a full disk, say): the writer keeps going, since space may come back, and
/// says so loudly at once, then at most every 10 s.
#[derive(Default)]
pub(super) struct Failures {
    pub(super) count: u64,
    /// Events dropped because too much waited unwritten.
    pub(super) lost: u64,
    reported: Option<Instant>,
    /// The current failure, while writing fails.
    pub(super) current: Option<Arc<str>>,
    /// When writing last failed.
    failed_at: Option<Instant>,
}

impl Failures {
    /// Whether to write now: always, unless the last attempt failed less than
    /// [`RETRY_INTERVAL`] ago.
    pub(super) fn may_retry(&self) -> bool {
        self.current.is_none() || self.failed_at.is_none_or(|t| t.elapsed() >= RETRY_INTERVAL)
    }

    pub(super) fn note(&mut self, error: &io::Error) -> Arc<str> {
        self.count += 1;
        self.failed_at = Some(Instant::now());
        if self
            .reported
            .is_none_or(|t| t.elapsed() >= Duration::from_secs(10))
        {
            tracing::error!(
                %error,
                failures = self.count,
                lost = self.lost,
                "cannot write the corpus log: events wait in memory and new triggers are refused"
            );
            self.reported = Some(Instant::now());
        }
        let message: Arc<str> = error.to_string().into();
        self.current = Some(Arc::clone(&message));
        message
    }

    pub(super) fn recovered(&mut self) {
        if self.current.take().is_some() {
            tracing::warn!(
                failures = self.count,
                lost = self.lost,
                "the corpus log can be written again"
            );
        }
    }

    pub(super) fn summary(&self) -> String {
        let mut text = format!("{} corpus writes failed", self.count);
        if self.lost > 0 {
            text += &format!(" and {} events were lost", self.lost);
        }
        text + "; see the server log"
    }
}
