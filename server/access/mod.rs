//! Who may do what. Operator and dialog-manager clients prove themselves with a credential
//! (websocket `hello.token`, HTTP `Authorization: Bearer`); kiosks and projectors need none
//! but a kiosk may trigger only what its pages offer (checked in `ws::triggers`), at a rate
//! limited per client address ([`Access::kiosk_allowance`]). A development server started
//! with `--open` on loopback needs no credentials at all.
//!
//! - `secret`: [`Secret`], a credential that never prints and compares in constant time.
//! - `attempts`: [`Attempts`], the wait after repeated wrong credentials from one address
//!   (never for the right credential).
//! - `proxies`: [`TrustedProxies`] and [`ClientAddress`]: who a request really comes from.
//! - `refusals`: [`RefusalLog`], the shared allowance of logged credential refusals.
//! - `rate`: [`TokenBucket`], the allowance behind the wait and the signalling relay.
//! - `setup`: [`decide_access`], the mode and credentials chosen at start-up.

mod attempts;
mod proxies;
mod rate;
mod refusals;
mod secret;
mod setup;

use std::collections::HashMap;
use std::net::{IpAddr, Ipv4Addr};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use crate::sync::lock;
use crate::wire::ErrorCode;

/// Kiosk addresses whose allowance is remembered at most (full ones are forgotten first).
const MAX_KIOSK_ADDRESSES: usize = 10_000;

pub use attempts::{Attempts, Counted, MAX_FAILURES, REFILL, counted_as};
pub use proxies::{ClientAddress, TrustedProxies};
pub use rate::{KIOSK_BURST, KIOSK_PER_SECOND, RECORDING_BURST, RECORDING_PER_SECOND, TokenBucket};
pub use refusals::{REFUSALS_LOGGED_AT_ONCE, REFUSALS_LOGGED_PER_SECOND, RefusalLog};
pub use secret::Secret;
pub use setup::{AccessSetup, DM_TOKEN_ENV, OPERATOR_TOKEN_ENV, Origin, SetupError, decide_access};

/// The credentials a guarded server checks.
#[derive(Clone, Debug)]
pub struct Credentials {
    /// For operator consoles.
    pub operator: Secret,
    /// For dialog managers (and external adapters not on this machine).
    pub dm: Secret,
}

/// Whether credentials are checked.
#[derive(Clone, Debug)]
pub enum AccessMode {
    /// `--open`: a loopback-only development server; nobody needs a credential.
    Open,
    /// Operator and dialog-manager clients need their credential.
    Guarded(Credentials),
}

/// Which credential a request must carry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Needed {
    /// The operator's (an operator console).
    Operator,
    /// The dialog manager's (a dialog manager, a remote adapter).
    Dm,
    /// Either (the HTTP trigger API).
    Either,
}

/// Why a credential was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Refusal {
    /// None was given.
    Missing,
    /// The one given is wrong.
    Wrong,
    /// This wrong attempt used up the address's failures; it may try again after this long.
    TooManyAttempts(Duration),
    /// A wrong attempt from an address that had used up its failures already; not counted,
    /// not worth logging again. (The right credential is never refused so.)
    Locked(Duration),
}

impl Refusal {
    /// The error code on the wire.
    pub fn code(self) -> ErrorCode {
        match self {
            Refusal::Missing | Refusal::Wrong => ErrorCode::Unauthorized,
            Refusal::TooManyAttempts(_) | Refusal::Locked(_) => ErrorCode::TooManyAttempts,
        }
    }

    /// What the client is told. Never echoes the credential.
    pub fn message(self, needed: Needed) -> String {
        let which = match needed {
            Needed::Operator => "the operator credential (DOCENT_OPERATOR_TOKEN)",
            Needed::Dm => "the dialog-manager credential (DOCENT_DM_TOKEN)",
            Needed::Either => "the operator or dialog-manager credential",
        };
        match self {
            Refusal::Missing => format!("this needs {which}"),
            Refusal::Wrong => format!("that is not {which}"),
            Refusal::TooManyAttempts(wait) | Refusal::Locked(wait) => format!(
                "too many wrong or missing credentials from this address; try again in {} s \
                 (the right credential is always taken)",
                whole_seconds(wait)
            ),
        }
    }
}

/// The server's access policy and its memory of failed attempts.
#[derive(Debug)]
pub struct Access {
    mode: AccessMode,
    proxies: TrustedProxies,
    attempts: Attempts,
    refusals: RefusalLog,
    kiosks: Mutex<HashMap<(IpAddr, KioskAllowance), TokenBucket>>,
}

/// Which of a kiosk address's two allowances a frame takes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum KioskAllowance {
    /// A visitor's doing: triggers, and page reports of touches and page scripts.
    Visitor,
    /// The shell's own doing: attract loop reports and pages shown by the attract loop, the
    /// schedule or the idle return. Kept apart so that the shell cannot spend the visitor's
    /// taps (a loop cycling fast would otherwise refuse the touch that ends it).
    Shell,
    /// Recording reports (`recording-started`, `recording-failed`): each is logged and shown
    /// to the operators, so a faulty or hostile kiosk must not send them at will.
    Recording,
}

impl Access {
    /// A policy in `mode`, believing `X-Forwarded-For` only from `proxies`.
    pub fn new(mode: AccessMode, proxies: TrustedProxies) -> Self {
        Access {
            mode,
            proxies,
            attempts: Attempts::default(),
            refusals: RefusalLog::default(),
            kiosks: Mutex::default(),
        }
    }

    /// The reverse proxies whose `X-Forwarded-For` is believed.
    pub fn proxies(&self) -> &TrustedProxies {
        &self.proxies
    }

    /// Whether to log a counted credential refusal now (see [`RefusalLog::admit`]): `Some`
    /// with the number of refusals left out of the log since the last one logged.
    pub fn admit_refusal_log(&self) -> Option<u64> {
        self.refusals.admit()
    }

    /// Takes one frame from the `which` allowance of the kiosk address `peer` (all kiosks at
    /// one address share it, so opening more connections gains nothing); otherwise how long
    /// until the next is allowed.
    pub fn kiosk_allowance(
        &self,
        peer: Option<IpAddr>,
        which: KioskAllowance,
        now: Instant,
    ) -> Result<(), Duration> {
        let peer = (peer.unwrap_or(IpAddr::V4(Ipv4Addr::UNSPECIFIED)), which);
        let mut kiosks = lock(&self.kiosks);
        if kiosks.len() >= MAX_KIOSK_ADDRESSES && !kiosks.contains_key(&peer) {
            kiosks.retain(|_, b| !b.is_full(now));
            if kiosks.len() >= MAX_KIOSK_ADDRESSES {
                return Err(Duration::from_secs(1));
            }
        }
        kiosks
            .entry(peer)
            .or_insert_with(|| match which {
                KioskAllowance::Visitor => TokenBucket::kiosk(now),
                KioskAllowance::Shell => TokenBucket::shell(now),
                KioskAllowance::Recording => TokenBucket::recording(now),
            })
            .take(now)
    }

    /// Whether this is an `--open` development server.
    pub fn is_open(&self) -> bool {
        matches!(self.mode, AccessMode::Open)
    }

    /// The credential `needed` is checked against (`None` on an `--open` server, or for
    /// [`Needed::Either`], which is two). Fleet commands are signed with it.
    pub fn credential(&self, needed: Needed) -> Option<&Secret> {
        let AccessMode::Guarded(credentials) = &self.mode else {
            return None;
        };
        match needed {
            Needed::Operator => Some(&credentials.operator),
            Needed::Dm => Some(&credentials.dm),
            Needed::Either => None,
        }
    }

    /// Checks a credential presented by `client`. The right credential is always taken,
    /// whatever wrong ones came before from the same address: only wrong or missing ones are
    /// counted against `client.ip`, and only they are refused once its failures are used up.
    pub fn check(
        &self,
        client: ClientAddress,
        needed: Needed,
        token: Option<&str>,
    ) -> Result<(), Refusal> {
        let peer = client.ip;
        let AccessMode::Guarded(credentials) = &self.mode else {
            // Open is for this machine only, even when a proxy or tunnel forwards the port.
            return match peer {
                Some(_) if !client.local => Err(Refusal::Missing),
                _ => Ok(()),
            };
        };
        let token = token.filter(|t| !t.is_empty());
        // Both comparisons always run, so timing does not tell which role a token was near.
        let operator = token.is_some_and(|t| credentials.operator.matches(t));
        let dm = token.is_some_and(|t| credentials.dm.matches(t));
        let ok = match needed {
            Needed::Operator => operator,
            Needed::Dm => dm,
            Needed::Either => operator | dm,
        };
        if ok {
            return Ok(());
        }
        let given = if token.is_some() {
            Refusal::Wrong
        } else {
            Refusal::Missing
        };
        // A missing credential counts too: asking without one, again and again, is a flood.
        match peer {
            Some(peer) => Err(self.failed(Counted::address(peer), given)),
            None => Err(given),
        }
    }

    /// Counts a failed attempt (`given`: [`Refusal::Wrong`] or [`Refusal::Missing`]) under
    /// `key`: the refusal to answer with, `too-many-attempts` once its failures are used up.
    pub fn failed(&self, key: Counted, given: Refusal) -> Refusal {
        let now = Instant::now();
        if let Some(wait) = self.attempts.locked(key, now) {
            return Refusal::Locked(wait);
        }
        match self.attempts.failed(key, now) {
            Some(wait) => {
                tracing::warn!(
                    ?key,
                    "too many wrong credentials; wrong ones from there wait {}s",
                    wait.as_secs()
                );
                Refusal::TooManyAttempts(wait)
            }
            None => given,
        }
    }
}

/// A wait in whole seconds, rounded up (a client that waits what it is told must not be
/// refused again for the missing fraction).
pub fn whole_seconds(wait: Duration) -> u64 {
    let rounded = wait.as_secs() + u64::from(wait.subsec_nanos() > 0);
    rounded.max(1)
}

/// Whether `peer` is this machine (only then may an adapter connect without a credential).
pub fn is_loopback(peer: Option<IpAddr>) -> bool {
    peer.is_some_and(|p| match p {
        IpAddr::V4(v4) => v4.is_loopback(),
        IpAddr::V6(v6) => {
            v6.is_loopback() || v6.to_ipv4_mapped().is_some_and(|v4| v4.is_loopback())
        }
    })
}

#[cfg(test)]
mod tests;
