//! What a connection without a credential (one that has not said `hello`, a kiosk, a
//! projector) may send, per connection: every frame takes from [`FRAME_BURST`] at once, then
//! [`FRAMES_PER_SECOND`]; a frame beyond it is dropped unread, the first of a run answered
//! `rate-limited`. Pings and pongs take from their own, smaller allowance, since each ping
//! makes the websocket layer queue a pong whether or not the client reads: beyond it the
//! connection is closed with `1008` (policy violation), so a client that pings and never
//! reads cannot make the server hold its pongs. Operators and dialog managers showed a
//! credential; adapters serve the robot and answer at its pace: neither is held to these.
//!
//! Each kiosk address has, besides, the allowances of `access` for the frames that are
//! logged (triggers, pages, attract reports, recording reports, a visitor's stop).

use std::time::{Duration, Instant};

use axum::extract::ws::close_code;

use crate::access::TokenBucket;
use crate::events::ClientRole;
use crate::ws::violation::{Violation, closed};

/// Frames a connection without a credential may send at once (a call's signalling needs up
/// to `access::SIGNAL_BURST` of them).
pub const FRAME_BURST: f64 = 400.0;
/// Frames per second such a connection may keep up.
pub const FRAMES_PER_SECOND: f64 = 100.0;
/// Pings and pongs such a connection may send at once.
pub const PING_BURST: f64 = 20.0;
/// Pings and pongs per second such a connection may keep up (browsers send none; Docent
/// pings every 20 s).
pub const PINGS_PER_SECOND: f64 = 2.0;

/// The `client.left` reason of a connection closed for its pings.
pub const TOO_MANY_PINGS: &str = "too many pings";

/// What becomes of a frame.
#[derive(Debug, PartialEq)]
pub(super) enum Verdict {
    /// Handled.
    Take,
    /// Dropped; `Some(wait)` for the first of a run, to be answered with how long to wait.
    Drop(Option<Duration>),
    /// The connection ends.
    Close,
}

/// One connection's allowances.
#[derive(Debug)]
pub(super) struct Allowance {
    frames: TokenBucket,
    pings: TokenBucket,
    /// Whether the current run of dropped frames was answered already.
    answered: bool,
}

impl Allowance {
    /// Full allowances.
    pub(super) fn new(now: Instant) -> Self {
        Allowance {
            frames: TokenBucket::new(FRAME_BURST, FRAMES_PER_SECOND, now),
            pings: TokenBucket::new(PING_BURST, PINGS_PER_SECOND, now),
            answered: false,
        }
    }

    /// A text or binary frame from a client with `role` (`None` before `hello`).
    pub(super) fn frame(&mut self, role: Option<ClientRole>, now: Instant) -> Verdict {
        if !held(role) {
            return Verdict::Take;
        }
        match self.frames.take(now) {
            Ok(()) => {
                self.answered = false;
                Verdict::Take
            }
            Err(wait) if !self.answered => {
                self.answered = true;
                Verdict::Drop(Some(wait))
            }
            Err(_) => Verdict::Drop(None),
        }
    }

    /// A ping or pong from a client with `role`.
    pub(super) fn ping(&mut self, role: Option<ClientRole>, now: Instant) -> Verdict {
        if !held(role) || self.pings.take(now).is_ok() {
            return Verdict::Take;
        }
        Verdict::Close
    }
}

/// Whether a client with `role` is held to these allowances: those without a credential.
fn held(role: Option<ClientRole>) -> bool {
    !matches!(
        role,
        Some(ClientRole::Operator | ClientRole::Dm | ClientRole::Adapter)
    )
}

/// The close of a connection over its ping allowance.
pub(super) fn too_many_pings() -> Violation {
    closed(
        TOO_MANY_PINGS,
        close_code::POLICY,
        "too many pings: at most 20 at once, then 2 a second",
    )
}

/// The `rate-limited` answer to the first frame dropped of a run.
pub(super) fn dropped_message(wait: Duration) -> String {
    format!(
        "too many frames from this connection: at most {FRAME_BURST} at once, then \
         {FRAMES_PER_SECOND} a second; frames are dropped for the next {} ms",
        wait.as_millis().max(1)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_beyond_the_burst_are_dropped_and_the_first_of_a_run_answered() {
        let now = Instant::now();
        let mut allowance = Allowance::new(now);
        for _ in 0..400 {
            assert_eq!(allowance.frame(Some(ClientRole::Kiosk), now), Verdict::Take);
        }
        assert!(matches!(allowance.frame(None, now), Verdict::Drop(Some(_))));
        assert_eq!(allowance.frame(None, now), Verdict::Drop(None));
        // An operator is not held to it.
        assert_eq!(
            allowance.frame(Some(ClientRole::Operator), now),
            Verdict::Take
        );
        // A refilled token ends the run; the next run is answered again.
        let later = now + Duration::from_millis(10);
        assert_eq!(allowance.frame(None, later), Verdict::Take);
        assert!(matches!(
            allowance.frame(None, later),
            Verdict::Drop(Some(_))
        ));
    }

    #[test]
    fn pings_beyond_their_burst_close_the_connection() {
        let now = Instant::now();
        let mut allowance = Allowance::new(now);
        for _ in 0..20 {
            assert_eq!(allowance.ping(None, now), Verdict::Take);
        }
        assert_eq!(
            allowance.ping(Some(ClientRole::Projector), now),
            Verdict::Close
        );
        assert_eq!(allowance.ping(Some(ClientRole::Dm), now), Verdict::Take);
    }
}
