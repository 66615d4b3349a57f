//! How many refused credentials are written down. Each address stops being logged once it
//! has to wait (see `attempts`), but many addresses (a botnet, IPv6 networks, clients behind
//! a trusted proxy) could still fill the corpus and the server log; so refusals from all
//! addresses together pass a shared allowance, and the first one logged after a gap says how
//! many were left out, so the record stays honest about what happened.

use std::num::NonZeroU32;
use std::sync::atomic::{AtomicU64, Ordering};

use governor::{DefaultDirectRateLimiter, Quota, RateLimiter};

/// Refusals logged at once, from all addresses together.
pub const REFUSALS_LOGGED_AT_ONCE: u32 = 30;
/// Refusals logged per second, from all addresses together, once that is used up.
pub const REFUSALS_LOGGED_PER_SECOND: u32 = 2;

/// The shared allowance of logged refusals.
#[derive(Debug)]
pub struct RefusalLog {
    allowance: DefaultDirectRateLimiter,
    left_out: AtomicU64,
}

impl Default for RefusalLog {
    fn default() -> Self {
        let quota = Quota::per_second(nonzero(REFUSALS_LOGGED_PER_SECOND))
            .allow_burst(nonzero(REFUSALS_LOGGED_AT_ONCE));
        RefusalLog {
            allowance: RateLimiter::direct(quota),
            left_out: AtomicU64::new(0),
        }
    }
}

fn nonzero(n: u32) -> NonZeroU32 {
    NonZeroU32::new(n).unwrap_or(NonZeroU32::MIN)
}

impl RefusalLog {
    /// Whether to log this refusal: `Some(n)` with the number left out since the last one
    /// logged, or `None` when this one is left out (and counted).
    pub fn admit(&self) -> Option<u64> {
        match self.allowance.check() {
            Ok(()) => Some(self.left_out.swap(0, Ordering::Relaxed)),
            Err(_) => {
                self.left_out.fetch_add(1, Ordering::Relaxed);
                None
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_flood_is_logged_up_to_the_allowance_and_the_rest_counted() {
        let log = RefusalLog::default();
        let admitted: Vec<u64> = (0..1000).filter_map(|_| log.admit()).collect();
        // The burst, plus at most what refilled while the loop ran.
        let burst = REFUSALS_LOGGED_AT_ONCE as usize;
        assert!((burst..burst + 3).contains(&admitted.len()), "{admitted:?}");
        // Every refusal is either logged or counted in the next one logged (or still waiting).
        let counted: u64 = admitted.iter().sum::<u64>() + log.left_out.load(Ordering::Relaxed);
        assert_eq!(counted, 1000 - admitted.len() as u64);
    }
}
