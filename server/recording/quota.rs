//! How much a session's recordings may take (`corpus: record_limits`). Kiosks upload without
//! a credential, so the limits are what keeps one (or anyone on its network) from filling the
//! disk the corpus log is written to: every chunk is counted against its session's share and
//! its kiosk's share within the session, and refused when the disk would keep less free than
//! the reserve. A kiosk that reconnects gets a new connection, but the session's share holds.

use std::collections::HashMap;
use std::path::Path;
use std::sync::Mutex;

use crate::content::config::RecordLimits;
use crate::content::size::describe_size;
use crate::events::FailureCode;
use crate::sync::lock;

/// The bytes a session's recordings hold, against its limits. Shared by its recordings.
#[derive(Debug)]
pub struct SessionQuota {
    limits: RecordLimits,
    /// Bytes stored (or being stored) per kiosk connection.
    used: Mutex<HashMap<u64, u64>>,
}

/// A chunk refused for a limit: the code the recording fails with and the words operators and
/// the kiosk are told.
#[derive(Debug, PartialEq, Eq)]
pub struct OverLimit {
    /// `limit-reached` or `disk-full`.
    pub code: FailureCode,
    /// What happened and which setting governs it.
    pub message: String,
}

impl SessionQuota {
    /// Nothing used yet.
    pub fn new(limits: RecordLimits) -> Self {
        SessionQuota {
            limits,
            used: Mutex::default(),
        }
    }

    /// The bytes the session's recordings hold (or are storing) now.
    pub fn used(&self) -> u64 {
        lock(&self.used).values().sum()
    }

    /// Counts `bytes` for kiosk `client`, if its share, the session's share and the disk's
    /// reserve (the free space `available` reports) allow them. Undo with [`Self::give_back`]
    /// when they are not stored after all.
    pub fn take(
        &self,
        client: u64,
        bytes: u64,
        available: impl FnOnce() -> std::io::Result<u64>,
    ) -> Result<(), OverLimit> {
        let mut used = lock(&self.used);
        let session: u64 = used.values().sum();
        let kiosk = used.get(&client).copied().unwrap_or(0);
        let limits = self.limits;
        if session + bytes > limits.per_session {
            return Err(over(format!(
                "the session's recordings reached their limit of {} (`corpus: record_limits: \
                 per_session`): recording stopped; what was stored is kept",
                describe_size(limits.per_session)
            )));
        }
        if kiosk + bytes > limits.per_kiosk {
            return Err(over(format!(
                "this kiosk's recordings of the session reached their limit of {} (`corpus: \
                 record_limits: per_kiosk`): recording stopped; what was stored is kept",
                describe_size(limits.per_kiosk)
            )));
        }
        let free = available().map_err(|e| OverLimit {
            code: FailureCode::DiskError,
            message: format!("the free space on the corpus's disk cannot be read: {e}"),
        })?;
        if free.saturating_sub(bytes) < limits.keep_free {
            return Err(disk_full(free, limits.keep_free));
        }
        *used.entry(client).or_default() += bytes;
        Ok(())
    }

    /// Returns `bytes` counted for `client` that were not stored.
    pub fn give_back(&self, client: u64, bytes: u64) {
        if let Some(used) = lock(&self.used).get_mut(&client) {
            *used = used.saturating_sub(bytes);
        }
    }

    /// Whether a new recording may start: the disk keeps its reserve.
    pub fn room_to_start(&self, folder: &Path) -> Result<(), OverLimit> {
        let free = available_bytes(folder).map_err(|e| OverLimit {
            code: FailureCode::DiskError,
            message: format!("the free space on the corpus's disk cannot be read: {e}"),
        })?;
        if free < self.limits.keep_free {
            return Err(disk_full(free, self.limits.keep_free));
        }
        Ok(())
    }
}

fn over(message: String) -> OverLimit {
    OverLimit {
        code: FailureCode::LimitReached,
        message,
    }
}

fn disk_full(free: u64, keep_free: u64) -> OverLimit {
    OverLimit {
        code: FailureCode::DiskFull,
        message: format!(
            "the corpus's disk has {} free, and {} are kept free for the event log (`corpus: \
             record_limits: keep_free`): recording stopped so that the robot goes on logging; \
             free space on the disk",
            describe_size(free),
            describe_size(keep_free)
        ),
    }
}

/// The bytes an unprivileged process may still write on the file system holding `path`.
pub fn available_bytes(path: &Path) -> std::io::Result<u64> {
    let stat = rustix::fs::statvfs(path)?;
    Ok(stat.f_bavail.saturating_mul(stat.f_frsize))
}

#[cfg(test)]
mod tests {
    use super::*;

    const PLENTY: u64 = u64::MAX / 2;

    fn limits(per_session: u64, per_kiosk: u64, keep_free: u64) -> SessionQuota {
        SessionQuota::new(RecordLimits {
            per_session,
            per_kiosk,
            keep_free,
        })
    }

    #[test]
    fn each_kiosk_has_its_share_and_all_of_them_the_sessions() {
        let quota = limits(10, 6, 0);
        assert_eq!(quota.take(1, 6, || Ok(PLENTY)), Ok(()));
        let kiosk = quota.take(1, 1, || Ok(PLENTY)).unwrap_err();
        assert_eq!(kiosk.code, FailureCode::LimitReached);
        assert!(kiosk.message.contains("per_kiosk"), "{}", kiosk.message);
        assert_eq!(quota.take(2, 4, || Ok(PLENTY)), Ok(()));
        let session = quota.take(3, 1, || Ok(PLENTY)).unwrap_err();
        assert!(
            session.message.contains("per_session"),
            "{}",
            session.message
        );
        quota.give_back(2, 4);
        assert_eq!(quota.take(3, 4, || Ok(PLENTY)), Ok(()), "given back");
    }

    #[test]
    fn a_chunk_that_would_eat_into_the_reserve_is_refused() {
        let quota = limits(PLENTY, PLENTY, 1000);
        assert_eq!(quota.take(1, 10, || Ok(1010)), Ok(()));
        let full = quota.take(1, 11, || Ok(1010)).unwrap_err();
        assert_eq!(full.code, FailureCode::DiskFull);
        assert!(full.message.contains("keep_free"), "{}", full.message);
        assert!(
            quota.room_to_start(Path::new(".")).is_ok(),
            "this disk has 1 kB free"
        );
        let greedy = limits(PLENTY, PLENTY, u64::MAX);
        let refused = greedy.room_to_start(Path::new(".")).unwrap_err();
        assert_eq!(refused.code, FailureCode::DiskFull);
    }

    #[test]
    fn the_free_space_is_the_file_systems() {
        let free = available_bytes(Path::new(".")).unwrap();
        assert!(free > 0);
    }
}
