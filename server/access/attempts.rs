//! Slowing down wrong credentials, never the right one. Each counted key (a client address,
//! an IPv6 /64 counting as one since one machine can hold all of it, or the MQTT commands all
//! together) has a bucket of [`MAX_FAILURES`] failures that refills one every [`REFILL`]. Once
//! it is empty, wrong or missing credentials from there are refused with `too-many-attempts`
//! until a failure has refilled; the right credential is compared first and always admitted
//! (`Access::check`), so nobody who can reach the server (or publish to the broker on the
//! robot's own machine) can lock the holder of the credential out of Stop. What bounds
//! guessing is the credential's length (16+ characters, generated ones about 190 bits); the
//! bucket bounds what wrong attempts cost the server (logging, work), and tells a
//! misconfigured client plainly to stop.

use std::collections::HashMap;
use std::net::IpAddr;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use crate::access::TokenBucket;
use crate::sync::lock;

/// Wrong or missing credentials tolerated from one key in a row.
pub const MAX_FAILURES: u32 = 5;
/// How long until one more failure is tolerated.
pub const REFILL: Duration = Duration::from_secs(10);
/// Keys remembered at most; beyond it those with a full bucket are forgotten first, so a
/// flood of addresses cannot grow memory without bound.
const MAX_ADDRESSES: usize = 10_000;

/// What failures are counted under.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Counted {
    /// A client address, as [`counted_as`] gives it.
    Address(IpAddr),
    /// Commands over MQTT. The broker does not say who published a message, and its address
    /// may be this machine's (127.0.0.1): counted under it, a flood of bad commands through
    /// the broker would make the local console wait. Kept apart, it reaches nothing else.
    Mqtt,
}

impl Counted {
    /// The key `peer`'s failures count under.
    pub fn address(peer: IpAddr) -> Self {
        Counted::Address(counted_as(peer))
    }
}

/// Failed attempts per counted key.
#[derive(Debug, Default)]
pub struct Attempts {
    buckets: Mutex<HashMap<Counted, TokenBucket>>,
}

/// The key an address is counted under: IPv4 as is, IPv6 by its /64 network (one machine can
/// hold a whole /64, so its addresses are one client).
pub fn counted_as(peer: IpAddr) -> IpAddr {
    match peer {
        IpAddr::V6(v6) => match v6.to_ipv4_mapped() {
            Some(v4) => IpAddr::V4(v4),
            None => IpAddr::V6((u128::from(v6) & !u128::from(u64::MAX)).into()),
        },
        v4 => v4,
    }
}

fn bucket(now: Instant) -> TokenBucket {
    TokenBucket::new(f64::from(MAX_FAILURES), 1.0 / REFILL.as_secs_f64(), now)
}

impl Attempts {
    /// How long `key` must still wait, if its failures are used up.
    pub fn locked(&self, key: Counted, now: Instant) -> Option<Duration> {
        let mut buckets = lock(&self.buckets);
        buckets.get_mut(&key)?.peek(now).err()
    }

    /// Records a wrong or missing credential counted under `key`; returns how long it must
    /// wait when this one used up its failures.
    pub fn failed(&self, key: Counted, now: Instant) -> Option<Duration> {
        let mut buckets = lock(&self.buckets);
        if buckets.len() >= MAX_ADDRESSES && !buckets.contains_key(&key) {
            buckets.retain(|_, b| !b.is_full(now));
            if buckets.len() >= MAX_ADDRESSES {
                // Still full of fresh failures: a flood. Forget one to stay bounded.
                let any = buckets.keys().next().copied();
                any.map(|k| buckets.remove(&k));
            }
        }
        let bucket = buckets.entry(key).or_insert_with(|| bucket(now));
        match bucket.take(now) {
            Ok(()) => bucket.peek(now).err(),
            Err(wait) => Some(wait),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const PEER: Counted = Counted::Address(IpAddr::V4(std::net::Ipv4Addr::new(10, 0, 0, 7)));
    const OTHER: Counted = Counted::Address(IpAddr::V4(std::net::Ipv4Addr::new(10, 0, 0, 8)));

    #[test]
    fn the_fifth_failure_in_a_row_makes_the_address_wait() {
        let attempts = Attempts::default();
        let start = Instant::now();
        for _ in 1..MAX_FAILURES {
            assert_eq!(attempts.failed(PEER, start), None);
            assert_eq!(attempts.locked(PEER, start), None);
        }
        assert_eq!(attempts.failed(PEER, start), Some(REFILL));
        assert_eq!(attempts.locked(PEER, start), Some(REFILL));
        assert_eq!(attempts.locked(OTHER, start), None);
        let later = start + REFILL - Duration::from_secs(1);
        assert_eq!(attempts.locked(PEER, later), Some(Duration::from_secs(1)));
        // One failure's worth refilled: one more try, then the wait again.
        assert_eq!(attempts.locked(PEER, start + REFILL), None);
        assert_eq!(attempts.failed(PEER, start + REFILL), Some(REFILL));
    }

    #[test]
    fn failures_slower_than_the_refill_never_lock() {
        let attempts = Attempts::default();
        let start = Instant::now();
        for i in 0..(3 * MAX_FAILURES) {
            let at = start + REFILL * i;
            assert_eq!(attempts.failed(PEER, at), None, "failure {i}");
        }
    }

    #[test]
    fn failures_over_mqtt_never_count_against_this_machine() {
        let attempts = Attempts::default();
        let now = Instant::now();
        for _ in 0..(2 * MAX_FAILURES) {
            attempts.failed(Counted::Mqtt, now);
        }
        assert!(attempts.locked(Counted::Mqtt, now).is_some());
        let local = Counted::address(IpAddr::V4(std::net::Ipv4Addr::LOCALHOST));
        assert_eq!(attempts.locked(local, now), None);
    }

    #[test]
    fn an_ipv6_network_counts_as_one_address() {
        let attempts = Attempts::default();
        let now = Instant::now();
        for i in 0..MAX_FAILURES {
            let peer: IpAddr = format!("2001:db8:1:2::{i:x}").parse().unwrap();
            attempts.failed(Counted::address(peer), now);
        }
        let fresh: IpAddr = "2001:db8:1:2:ffff::1".parse().unwrap();
        assert!(attempts.locked(Counted::address(fresh), now).is_some());
        let elsewhere: IpAddr = "2001:db8:1:3::1".parse().unwrap();
        assert_eq!(attempts.locked(Counted::address(elsewhere), now), None);
    }

    #[test]
    fn many_addresses_do_not_grow_memory_without_bound() {
        let attempts = Attempts::default();
        let now = Instant::now();
        for i in 0..(MAX_ADDRESSES as u32 + 50) {
            attempts.failed(Counted::Address(IpAddr::V4(i.into())), now);
        }
        assert!(lock(&attempts.buckets).len() <= MAX_ADDRESSES);
    }
}
