//! How long the rosbridge link waits before trying again: exponential from 100 ms, doubled per
//! failed attempt, capped at [`MAX_DELAY`] so that the link is back within a few seconds of
//! rosbridge returning, each wait jittered (half to all of it) so that several Docents do not
//! knock on a restarted robot in step.

use std::time::Duration;

use rand::RngExt;

/// The first wait after a lost link.
pub const FIRST_DELAY: Duration = Duration::from_millis(100);
/// The longest wait: with jitter, the link is back at most this long after rosbridge is.
pub const MAX_DELAY: Duration = Duration::from_millis(1000);

/// The waits between attempts.
#[derive(Debug, Default)]
pub struct Backoff {
    attempts: u32,
}

impl Backoff {
    /// The wait before the next attempt, one attempt further.
    pub fn next_delay(&mut self) -> Duration {
        let full = self.ceiling();
        self.attempts = self.attempts.saturating_add(1);
        let half = full / 2;
        half + full.mul_f64(rand::rng().random_range(0.0..=0.5))
    }

    /// A connection worked: start again from the first wait.
    pub fn reset(&mut self) {
        self.attempts = 0;
    }

    fn ceiling(&self) -> Duration {
        let factor = 2u32.saturating_pow(self.attempts.min(16));
        FIRST_DELAY.saturating_mul(factor).min(MAX_DELAY)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn waits_double_up_to_the_cap_with_jitter_and_reset() {
        let mut backoff = Backoff::default();
        let mut ceiling = FIRST_DELAY;
        for _ in 0..40 {
            let wait = backoff.next_delay();
            assert!(
                wait >= ceiling / 2 && wait <= ceiling,
                "{wait:?} vs {ceiling:?}"
            );
            ceiling = (ceiling * 2).min(MAX_DELAY);
        }
        backoff.reset();
        assert!(backoff.next_delay() <= FIRST_DELAY);
    }
}
