//! Signed fleet commands and replies: a credential never travels over the broker, where anyone
//! allowed to read `docent/+/cmd` would see it. A command on `docent/ID/cmd` is an envelope
//! `{"robot", "role", "ref", "ts", "frame", "mac"}`: `frame` the websocket client frame as JSON
//! text, `ts` milliseconds since the Unix epoch, `ref` an unguessable random reference, and
//! `mac` HMAC-SHA256, keyed by the role's credential, over [`command_text`]. Each answer on
//! `docent/ID/reply` is `{"robot", "ref", "frame", "mac"}`, its `mac` over [`reply_text`] with
//! the same credential; an answer to a command that did not verify carries no `mac` (the robot
//! cannot know whom it answers, and signing it would let anyone have the robot sign an answer
//! to a reference of their choosing).
//!
//! Why HMAC rather than the raw token on per-robot topics with broker ACLs: ACLs depend on
//! every site configuring its broker right, and a mistake there would hand out the credential;
//! a MAC is worthless to a reader. ACLs stay documented (docs/FLEET.md) as defence in depth.
//! Why the frame as text: the MAC is over the exact bytes sent, so no JSON canonical form is
//! needed on either side.

use std::collections::HashMap;
use std::time::{Duration, SystemTime, UNIX_EPOCH};

use hmac::{Hmac, KeyInit, Mac};
use rand::RngExt;
use serde::{Deserialize, Serialize};
use sha2::Sha256;

use crate::access::Secret;

/// How far a command's `ts` may be from the robot's clock (either way).
pub const FRESHNESS: Duration = Duration::from_secs(30);
/// References remembered at most (those within [`FRESHNESS`]); more fresh commands than this
/// are refused until some grow old.
const MAX_REMEMBERED: usize = 10_000;
/// The shortest `ref` taken: 16 characters, so that a sender's random ones are not guessable.
const MIN_REF: usize = 16;
/// The longest `ref` taken.
const MAX_REF: usize = 128;

/// A command as published on `docent/ID/cmd`.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SignedCommand {
    /// The robot it is for.
    pub robot: String,
    /// `operator` or `dm`: whose credential signed it.
    pub role: String,
    /// The sender's unguessable reference, echoed by each answer.
    #[serde(rename = "ref")]
    pub reference: String,
    /// When it was signed, in milliseconds since the Unix epoch.
    pub ts: u64,
    /// The websocket client frame, as JSON text.
    pub frame: String,
    /// HMAC-SHA256 of [`command_text`], in lowercase hex.
    pub mac: String,
}

/// An answer as published on `docent/ID/reply`.
#[derive(Clone, Debug, Deserialize, Serialize)]
pub struct SignedReply {
    /// The robot that answers.
    pub robot: String,
    /// The command's `ref` (`null` when the command had none that could be read).
    #[serde(rename = "ref")]
    pub reference: Option<String>,
    /// The answer frame, as JSON text.
    pub frame: String,
    /// HMAC-SHA256 of [`reply_text`]; absent on an answer to a command that did not verify.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mac: Option<String>,
}

/// What a command's MAC is computed over: a version line, then one field a line (`robot`,
/// `role`, `ref` and `ts` cannot hold a line break; `frame`, last, may).
pub fn command_text(robot: &str, role: &str, reference: &str, ts: u64, frame: &str) -> String {
    format!("docent-command-v1\n{robot}\n{role}\n{reference}\n{ts}\n{frame}")
}

/// What an answer's MAC is computed over.
pub fn reply_text(robot: &str, reference: &str, frame: &str) -> String {
    format!("docent-reply-v1\n{robot}\n{reference}\n{frame}")
}

fn hmac(key: &Secret) -> Hmac<Sha256> {
    // HMAC takes a key of any length; the error is for fixed-size MACs only.
    <Hmac<Sha256> as KeyInit>::new_from_slice(key.expose().as_bytes())
        .unwrap_or_else(|_| unreachable!("HMAC keys may have any length"))
}

/// The MAC of `text` with `key`, in lowercase hex.
pub fn mac(key: &Secret, text: &str) -> String {
    let mut mac = hmac(key);
    mac.update(text.as_bytes());
    mac.finalize()
        .into_bytes()
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// Whether `presented` (hex) is the MAC of `text` with `key`; compared in constant time.
pub fn verifies(key: &Secret, text: &str, presented: &str) -> bool {
    let Some(bytes) = from_hex(presented) else {
        return false;
    };
    let mut mac = hmac(key);
    mac.update(text.as_bytes());
    mac.verify_slice(&bytes).is_ok()
}

fn from_hex(text: &str) -> Option<Vec<u8>> {
    if !text.len().is_multiple_of(2) || !text.is_ascii() {
        return None;
    }
    (0..text.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&text[i..i + 2], 16).ok())
        .collect()
}

/// A fresh unguessable reference: 128 random bits in hex.
pub fn fresh_reference() -> String {
    let bits: u128 = rand::rng().random();
    format!("{bits:032x}")
}

/// Milliseconds since the Unix epoch now.
pub fn now_ms() -> u64 {
    let since = SystemTime::now().duration_since(UNIX_EPOCH);
    since.map_or(0, |d| u64::try_from(d.as_millis()).unwrap_or(u64::MAX))
}

/// Why a command whose MAC verified is still not taken.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unfresh {
    /// Its `ts` is more than [`FRESHNESS`] from this robot's clock.
    Stale,
    /// Its `ref` was taken already within [`FRESHNESS`].
    Replayed,
    /// More fresh commands than can be remembered: refused until some grow old.
    TooMany,
}

/// Whether `reference` has the shape of a random reference (letters, digits, `-`, `_`; 16 to
/// 128 of them).
pub fn reference_problem(reference: &str) -> Option<String> {
    let shaped = reference
        .bytes()
        .all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'_');
    let long = (MIN_REF..=MAX_REF).contains(&reference.len());
    (!shaped || !long).then(|| {
        format!(
            "\"ref\" is {MIN_REF} to {MAX_REF} letters, digits, - or _, random for each command"
        )
    })
}

/// The references of the commands taken within [`FRESHNESS`], so that a command read off the
/// broker and published again is not run twice.
#[derive(Debug, Default)]
pub struct Replays {
    seen: HashMap<String, u64>,
}

impl Replays {
    /// Takes a command signed at `ts` with `reference` at `now` (both in ms), or says why not.
    pub fn take(&mut self, reference: &str, ts: u64, now: u64) -> Result<(), Unfresh> {
        let window = u64::try_from(FRESHNESS.as_millis()).unwrap_or(u64::MAX);
        if ts.abs_diff(now) > window {
            return Err(Unfresh::Stale);
        }
        if self.seen.contains_key(reference) {
            return Err(Unfresh::Replayed);
        }
        if self.seen.len() >= MAX_REMEMBERED {
            // A remembered command older than the window would be refused as stale anyway.
            self.seen.retain(|_, at| at.abs_diff(now) <= window);
            if self.seen.len() >= MAX_REMEMBERED {
                return Err(Unfresh::TooMany);
            }
        }
        self.seen.insert(reference.to_owned(), ts);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mac_verifies_only_with_the_same_key_and_text() {
        let key = Secret::new("operator-credential-1");
        let text = command_text(
            "hall-1",
            "operator",
            "0123456789abcdef",
            5,
            "{\"type\":\"stop\"}",
        );
        let sum = mac(&key, &text);
        assert_eq!(sum.len(), 64);
        assert!(verifies(&key, &text, &sum));
        assert!(!verifies(
            &Secret::new("operator-credential-2"),
            &text,
            &sum
        ));
        let other = command_text(
            "hall-2",
            "operator",
            "0123456789abcdef",
            5,
            "{\"type\":\"stop\"}",
        );
        assert!(!verifies(&key, &other, &sum));
        assert!(!verifies(&key, &text, "zz"));
        assert!(!verifies(&key, &text, &sum[..62]));
    }

    #[test]
    fn the_mac_is_standard_hmac_sha256() {
        // RFC 4231, test case 2.
        let key = Secret::new("Jefe");
        assert_eq!(
            mac(&key, "what do ya want for nothing?"),
            "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843"
        );
    }

    #[test]
    fn a_command_is_taken_once_and_only_while_fresh() {
        let mut replays = Replays::default();
        let now = 1_000_000;
        assert_eq!(replays.take("a", now - 1_000, now), Ok(()));
        assert_eq!(replays.take("a", now - 1_000, now), Err(Unfresh::Replayed));
        assert_eq!(replays.take("b", now - 31_000, now), Err(Unfresh::Stale));
        assert_eq!(replays.take("c", now + 31_000, now), Err(Unfresh::Stale));
        assert_eq!(replays.take("d", now + 29_000, now), Ok(()));
    }

    #[test]
    fn remembered_references_stay_bounded() {
        let mut replays = Replays::default();
        let now = 1_000_000;
        for i in 0..MAX_REMEMBERED {
            assert_eq!(replays.take(&i.to_string(), now, now), Ok(()));
        }
        assert_eq!(replays.take("more", now, now), Err(Unfresh::TooMany));
        let later = now + 31_000;
        assert_eq!(replays.take("more", later, later), Ok(()));
        assert_eq!(replays.seen.len(), 1);
    }

    #[test]
    fn references_are_random_and_well_shaped() {
        let (a, b) = (fresh_reference(), fresh_reference());
        assert_ne!(a, b);
        assert_eq!(reference_problem(&a), None);
        assert!(reference_problem("fleet-stop-1").is_some());
        assert!(reference_problem("0123456789abcdef\nx").is_some());
    }
}
