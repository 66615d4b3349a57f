//! Limiting wrong credentials: an address that gets the credential wrong [`MAX_FAILURES`]
//! times within [`WINDOW`] is refused for [`LOCKOUT`], even with the right one, so guessing
//! stays hopeless. Missing credentials do not count (a console before sign-in is no guess).

use std::collections::HashMap;
use std::net::IpAddr;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use crate::sync::lock;

/// Wrong credentials tolerated from one address within [`WINDOW`].
pub const MAX_FAILURES: u32 = 5;
/// The window failures are counted in.
pub const WINDOW: Duration = Duration::from_secs(60);
/// How long an address is refused once it reached [`MAX_FAILURES`].
pub const LOCKOUT: Duration = Duration::from_secs(60);
/// Addresses remembered at most; beyond it the oldest records are dropped, so a flood of
/// addresses cannot grow memory without bound.
const MAX_ADDRESSES: usize = 10_000;

#[derive(Clone, Copy, Debug)]
struct Record {
    failures: u32,
    since: Instant,
    locked_until: Option<Instant>,
}

/// Failed attempts per client address.
#[derive(Debug, Default)]
pub struct Attempts {
    records: Mutex<HashMap<IpAddr, Record>>,
}

impl Attempts {
    /// How long `peer` must still wait, if it is locked out now.
    pub fn locked(&self, peer: IpAddr, now: Instant) -> Option<Duration> {
        let records = lock(&self.records);
        let until = records.get(&peer)?.locked_until?;
        (until > now).then(|| until - now)
    }

    /// Records a wrong credential from `peer`; returns the lockout when this one started it.
    pub fn failed(&self, peer: IpAddr, now: Instant) -> Option<Duration> {
        let mut records = lock(&self.records);
        if records.len() >= MAX_ADDRESSES && !records.contains_key(&peer) {
            records.retain(|_, r| now.duration_since(r.since) < WINDOW.max(LOCKOUT));
            if records.len() >= MAX_ADDRESSES {
                // Still full of fresh records: forget one to make room (this costs a flooder
                // its own history, never a locked-out address its lock for long).
                if let Some(oldest) = records.iter().min_by_key(|(_, r)| r.since).map(|(a, _)| *a) {
                    records.remove(&oldest);
                }
            }
        }
        let record = records.entry(peer).or_insert(Record {
            failures: 0,
            since: now,
            locked_until: None,
        });
        if now.duration_since(record.since) > WINDOW {
            *record = Record {
                failures: 0,
                since: now,
                locked_until: None,
            };
        }
        record.failures += 1;
        if record.failures >= MAX_FAILURES {
            record.locked_until = Some(now + LOCKOUT);
            // The lockout starts a fresh window once it ends.
            record.failures = 0;
            record.since = now + LOCKOUT;
            return Some(LOCKOUT);
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const PEER: IpAddr = IpAddr::V4(std::net::Ipv4Addr::new(10, 0, 0, 7));
    const OTHER: IpAddr = IpAddr::V4(std::net::Ipv4Addr::new(10, 0, 0, 8));

    #[test]
    fn the_fifth_failure_within_a_minute_locks_the_address_out_for_a_minute() {
        let attempts = Attempts::default();
        let start = Instant::now();
        for i in 1..MAX_FAILURES {
            assert_eq!(
                attempts.failed(PEER, start + Duration::from_secs(i.into())),
                None
            );
            assert_eq!(attempts.locked(PEER, start), None);
        }
        let fifth = start + Duration::from_secs(10);
        assert_eq!(attempts.failed(PEER, fifth), Some(LOCKOUT));
        assert_eq!(attempts.locked(PEER, fifth), Some(LOCKOUT));
        assert_eq!(attempts.locked(OTHER, fifth), None);
        let later = fifth + LOCKOUT - Duration::from_secs(1);
        assert_eq!(attempts.locked(PEER, later), Some(Duration::from_secs(1)));
        assert_eq!(attempts.locked(PEER, fifth + LOCKOUT), None);
    }

    #[test]
    fn failures_spread_over_more_than_a_minute_do_not_lock() {
        let attempts = Attempts::default();
        let start = Instant::now();
        for i in 0..(3 * MAX_FAILURES) {
            let at = start + WINDOW.mul_f64(0.4) * i;
            assert_eq!(attempts.failed(PEER, at), None, "failure {i}");
        }
    }

    #[test]
    fn many_addresses_do_not_grow_memory_without_bound() {
        let attempts = Attempts::default();
        let now = Instant::now();
        for i in 0..(MAX_ADDRESSES as u32 + 50) {
            attempts.failed(IpAddr::V4(i.into()), now);
        }
        assert!(lock(&attempts.records).len() <= MAX_ADDRESSES);
    }
}
