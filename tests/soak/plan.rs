//! What one soak runs: its length, its load and its pacing. Two hours of a museum's day are
//! compressed twelvefold (ten minutes for the bench), so what happens every minute of the day
//! happens every 5 s here; the one-minute run of the test command keeps the same pacing and
//! only ends sooner, so both lengths meet the same load and are judged by the same rules.

use std::path::PathBuf;
use std::time::Duration;

/// How much faster than a real day the soak goes: 2 hours in 10 minutes.
pub const COMPRESSION: u32 = 12;

/// The run's settings; [`Plan::from_env`] reads the bench's overrides.
#[derive(Clone, Debug)]
pub struct Plan {
    /// The `docent` binary to serve with (debug for the test, release for the bench).
    pub docent: PathBuf,
    /// How long the load runs.
    pub length: Duration,
    /// Kiosk clients, each from its own loopback address.
    pub kiosks: usize,
    /// How often each kiosk taps while visitors are there.
    pub tap_every: Duration,
    /// How often the operator and the dialog manager each trigger.
    pub staff_every: Duration,
    /// How often a storm drops kiosks (30 s of the day).
    pub storm_every: Duration,
    /// How many kiosks a storm drops at least, and at most.
    pub storm_size: (usize, usize),
    /// How often the acts file is saved anew (a minute of the day).
    pub reload_every: Duration,
    /// How long visitors tap, then how long the kiosks stay untouched; the pause is longer
    /// than the bundle's `session_idle`, so each visit is one session.
    pub visit: Duration,
    /// See `visit`.
    pub pause: Duration,
    /// How often a recording kiosk uploads a chunk.
    pub chunk_every: Duration,
    /// Bytes per recording chunk.
    pub chunk_bytes: usize,
    /// Where the bench keeps its samples, table and plot (`DOCENT_SOAK_OUT`); none in tests.
    pub out: Option<PathBuf>,
}

impl Plan {
    /// One minute against the debug binary, unless `DOCENT_SOAK_SECONDS`, `DOCENT_SOAK_BIN`
    /// and `DOCENT_SOAK_OUT` say otherwise (`bench/soak.sh` sets them).
    pub fn from_env() -> Plan {
        let seconds = std::env::var("DOCENT_SOAK_SECONDS")
            .ok()
            .map(|s| {
                s.parse::<u64>()
                    .expect("DOCENT_SOAK_SECONDS is whole seconds")
            })
            .unwrap_or(60);
        let docent = std::env::var_os("DOCENT_SOAK_BIN").map_or_else(
            || PathBuf::from(env!("CARGO_BIN_EXE_docent")),
            PathBuf::from,
        );
        Plan {
            docent,
            length: Duration::from_secs(seconds),
            kiosks: 50,
            tap_every: Duration::from_secs(2),
            staff_every: Duration::from_millis(200),
            storm_every: Duration::from_secs(30) / COMPRESSION,
            storm_size: (20, 50),
            reload_every: Duration::from_secs(60) / COMPRESSION,
            visit: Duration::from_secs(12),
            pause: Duration::from_secs(7),
            chunk_every: Duration::from_secs(1),
            chunk_bytes: 2048,
            out: std::env::var_os("DOCENT_SOAK_OUT").map(PathBuf::from),
        }
    }

    /// The length of one window of the report: a tenth of the run (a minute of the bench).
    pub fn window(&self) -> Duration {
        self.length / 10
    }

    /// What is not judged: the first tenth of the run, and at least 30 s, in which the
    /// server's bounded tables fill (the 200 events of history, the 1,024 settled commands
    /// per connection, allocator arenas): in one-minute runs RSS rose 2 MB in the first 30 s,
    /// then under 1 MB in the next 30.
    pub fn warmup(&self) -> Duration {
        (self.length / 10).max(Duration::from_secs(30))
    }

    /// The spans whose RSS and descriptor counts are compared: a tenth of the run, and at
    /// least one visit and its pause, since the descriptors follow the visits (a session's
    /// recordings hold a file and an upload connection per kiosk: 219 open during a visit,
    /// 119 in a pause, in one-minute runs).
    pub fn growth_span(&self) -> Duration {
        (self.length / 10).max(self.visit + self.pause)
    }
}
