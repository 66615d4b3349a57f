//! The corpus writer's write failures (a full disk, a read-only one): counted, said loudly at
//! once and then at most every 10 s, retried every second, and summed up at the end of the
//! run. The writer keeps going, since space may come back; the run ends with an error only
//! when events were lost (dropped, or still unwritten at the end).

use std::io;
use std::path::Path;
use std::sync::Arc;
use std::time::{Duration, Instant};

use docent_protocol::events::{CorpusFault, CorpusUnwritable};

/// How often writing is tried again after it failed.
const RETRY_INTERVAL: Duration = Duration::from_secs(1);

/// Write failures over the run, and the current one.
#[derive(Default)]
pub(super) struct Failures {
    pub(super) count: u64,
    /// Events lost: dropped because too much waited unwritten, or unwritten at the end.
    pub(super) lost: u64,
    reported: Option<Instant>,
    /// The current failure, while writing fails.
    pub(super) current: Option<Current>,
    /// When writing last failed.
    failed_at: Option<Instant>,
}

/// The failure that stops the log now.
pub(super) struct Current {
    pub(super) fault: CorpusFault,
    /// The operating system's error.
    pub(super) error: Arc<str>,
    /// What the operator is told.
    pub(super) alert: Arc<str>,
    since: Instant,
}

impl Failures {
    /// Whether to write now: always, unless the last attempt failed less than
    /// [`RETRY_INTERVAL`] ago.
    pub(super) fn may_retry(&self) -> bool {
        self.current.is_none() || self.failed_at.is_none_or(|t| t.elapsed() >= RETRY_INTERVAL)
    }

    /// Notes that writing into the corpus folder `dir` failed with `error`; returns the
    /// event to publish when writing was fine until now.
    pub(super) fn note(&mut self, error: &io::Error, dir: &Path) -> Option<CorpusUnwritable> {
        self.count += 1;
        self.failed_at = Some(Instant::now());
        if (self.reported).is_none_or(|t| t.elapsed() >= Duration::from_secs(10)) {
            tracing::error!(
                %error,
                failures = self.count,
                lost = self.lost,
                "cannot write the corpus log: events wait in memory and new triggers are refused"
            );
            self.reported = Some(Instant::now());
        }
        let fault = CorpusFault::of(error.kind());
        let text = error.to_string();
        if let Some(current) = &mut self.current
            && current.fault == fault
        {
            current.error = text.into();
            return None;
        }
        let path = dir.display().to_string();
        let message = fault.operator_words(&path, &text);
        let since = self.current.as_ref().map_or_else(Instant::now, |c| c.since);
        self.current = Some(Current {
            fault,
            error: text.as_str().into(),
            alert: message.as_str().into(),
            since,
        });
        Some(CorpusUnwritable {
            fault,
            path,
            error: text,
            message,
        })
    }

    /// The failure's error and words for the writer's report, while it lasts.
    pub(super) fn report(&self) -> Option<(Arc<str>, Arc<str>)> {
        (self.current.as_ref()).map(|c| (Arc::clone(&c.error), Arc::clone(&c.alert)))
    }

    /// Notes that writing works again; returns how long it failed, and with which fault,
    /// when it did.
    pub(super) fn recovered(&mut self) -> Option<(Duration, CorpusFault)> {
        let current = self.current.take()?;
        tracing::warn!(
            failures = self.count,
            lost = self.lost,
            "the corpus log can be written again"
        );
        Some((current.since.elapsed(), current.fault))
    }

    /// Lets the next write be tried at once (tests, which do not wait a second).
    #[cfg(test)]
    pub(super) fn retry_now(&mut self) {
        self.failed_at = None;
    }

    pub(super) fn summary(&self) -> String {
        let mut text = format!("{} corpus writes failed", self.count);
        if self.lost > 0 {
            text += &format!(" and {} events were lost", self.lost);
        }
        text + "; see the server log"
    }
}
