//! A token bucket: how often a kiosk may trigger. A visitor's taps come in short bursts; a
//! stuck finger, a page script in a loop or a stranger on the network must not flood the
//! robot with acts.

use std::time::{Duration, Instant};

/// Triggers a kiosk may send at once.
pub const KIOSK_BURST: f64 = 5.0;
/// Triggers per second a kiosk may keep up.
pub const KIOSK_PER_SECOND: f64 = 4.0;
/// Reports of the kiosk shell's own doing (the attract loop, the schedule, the idle return)
/// a kiosk may send at once: a separate allowance, so that a loop that just cycled does not
/// spend the visitor's taps.
pub const SHELL_BURST: f64 = 8.0;
/// Reports of the shell's own doing per second a kiosk may keep up.
pub const SHELL_PER_SECOND: f64 = 2.0;
/// Recording reports (`recording-started`, `recording-failed`) a kiosk may send at once: a
/// recording needs one or two, and each is logged and shown on every console.
pub const RECORDING_BURST: f64 = 10.0;
/// Recording reports per second a kiosk may keep up.
pub const RECORDING_PER_SECOND: f64 = 1.0;
/// Signalling frames a client may relay at once.
pub const SIGNAL_BURST: f64 = 200.0;
/// Signalling frames per second a client may keep up.
pub const SIGNAL_PER_SECOND: f64 = 50.0;

/// One client's allowance.
#[derive(Debug)]
pub struct TokenBucket {
    capacity: f64,
    per_second: f64,
    tokens: f64,
    last: Instant,
}

impl TokenBucket {
    /// A full bucket.
    pub fn new(capacity: f64, per_second: f64, now: Instant) -> Self {
        TokenBucket {
            capacity,
            per_second,
            tokens: capacity,
            last: now,
        }
    }

    /// The trigger allowance of one kiosk address.
    pub fn kiosk(now: Instant) -> Self {
        Self::new(KIOSK_BURST, KIOSK_PER_SECOND, now)
    }

    /// The allowance of one kiosk address for reports of the shell's own doing.
    pub fn shell(now: Instant) -> Self {
        Self::new(SHELL_BURST, SHELL_PER_SECOND, now)
    }

    /// The allowance of one kiosk address for its recording reports.
    pub fn recording(now: Instant) -> Self {
        Self::new(RECORDING_BURST, RECORDING_PER_SECOND, now)
    }

    /// The allowance of relayed WebRTC signalling frames of one connection: a call needs a
    /// few dozen (offer, answer, candidates), a flood must not bury the other side.
    pub fn signalling(now: Instant) -> Self {
        Self::new(SIGNAL_BURST, SIGNAL_PER_SECOND, now)
    }

    /// Takes one token if there is one; otherwise says how long until the next.
    pub fn take(&mut self, now: Instant) -> Result<(), Duration> {
        self.peek(now)?;
        self.tokens -= 1.0;
        Ok(())
    }

    /// Whether a token is there, without taking it; otherwise how long until one is.
    pub fn peek(&mut self, now: Instant) -> Result<(), Duration> {
        self.refill(now);
        if self.tokens >= 1.0 {
            return Ok(());
        }
        Err(Duration::from_secs_f64(
            (1.0 - self.tokens) / self.per_second,
        ))
    }

    /// Whether the bucket has refilled completely (nothing left to remember about it).
    pub fn is_full(&mut self, now: Instant) -> bool {
        self.refill(now);
        self.tokens >= self.capacity
    }

    fn refill(&mut self, now: Instant) {
        let elapsed = now.saturating_duration_since(self.last).as_secs_f64();
        self.tokens = (self.tokens + elapsed * self.per_second).min(self.capacity);
        self.last = now;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_burst_passes_then_the_steady_rate() {
        let start = Instant::now();
        let mut bucket = TokenBucket::kiosk(start);
        for _ in 0..5 {
            assert_eq!(bucket.take(start), Ok(()));
        }
        let wait = bucket.take(start).expect_err("sixth at once");
        assert_eq!(wait, Duration::from_millis(250));
        assert!(bucket.take(start + Duration::from_millis(249)).is_err());
        assert_eq!(bucket.take(start + Duration::from_millis(500)), Ok(()));
        // Idle time refills up to the burst, never beyond.
        let later = start + Duration::from_secs(60);
        for _ in 0..5 {
            assert_eq!(bucket.take(later), Ok(()));
        }
        assert!(bucket.take(later).is_err());
    }
}
