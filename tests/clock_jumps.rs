//! The wall clock jumping an hour back or forward under the real `docent` binary, moved by
//! Debian's libfaketime (`LD_PRELOAD`, its offset read from a file the test rewrites, the
//! monotonic clock left alone): durations keep real time (a visitor session's idle end, an
//! act's `WAIT`), `mono_us` only grows, an event goes to the day log of its wall-clock date,
//! and opening hours follow the new wall time. Every test first shows that the server's wall
//! clock did move, so none passes because the preload did nothing.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Child, Command};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use common::process::{serve_args, start, stop};
use common::{TempBundle, WsClient, json_lines};
use serde_json::{Value, json};

const HOUR: i64 = 3600;
const DAY: i64 = 86_400;

const ACTS: &str = "
- Label: WELCOME
  Text: [Hello!]
- Label: PAUSE
  Cmds:
    - WAIT 2s
    - SAY after the pause
";

/// libfaketime's thread-safe library where Debian puts it (`/usr/lib/<arch>/faketime/`).
fn libfaketime() -> PathBuf {
    let found = std::fs::read_dir("/usr/lib").ok().and_then(|dirs| {
        (dirs.flatten())
            .map(|d| d.path().join("faketime/libfaketimeMT.so.1"))
            .find(|p| p.is_file())
    });
    found.expect("libfaketime is not installed: run scripts/install-test-deps.sh")
}

/// The server's wall clock: real time plus an offset the test sets while it runs.
struct FakeClock {
    dir: tempfile::TempDir,
}

impl FakeClock {
    fn new() -> Self {
        let clock = FakeClock {
            dir: tempfile::tempdir().expect("a folder for the clock"),
        };
        clock.set(0);
        clock
    }

    fn file(&self) -> PathBuf {
        self.dir.path().join("faketime.rc")
    }

    /// Moves the server's wall clock to real time plus `seconds`, at once: the file is
    /// replaced in one step, and the server reads it at every clock reading.
    fn set(&self, seconds: i64) {
        let staged = self.dir.path().join("staged");
        std::fs::write(&staged, format!("{seconds:+}\n")).expect("stage the offset");
        std::fs::rename(&staged, self.file()).expect("set the offset");
    }

    /// `docent serve` on this clock, in UTC.
    fn serve(&self, bundle: &Path, corpus: &Path) -> (Child, String) {
        let mut command = Command::new(env!("CARGO_BIN_EXE_docent"));
        command
            .args(serve_args(bundle, corpus))
            .env("LD_PRELOAD", libfaketime())
            .env("FAKETIME_TIMESTAMP_FILE", self.file())
            .env("FAKETIME_NO_CACHE", "1")
            .env("FAKETIME_DONT_FAKE_MONOTONIC", "1")
            .env("TZ", "UTC");
        start(command)
    }
}

fn unix_now() -> i64 {
    let since = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .expect("after 1970");
    i64::try_from(since.as_secs()).expect("seconds")
}

/// Seconds between the real clock and `target` (Unix time).
fn offset_to(target: i64) -> i64 {
    target - unix_now()
}

/// An event's `time`, in whole seconds since the epoch.
fn wall(event: &Value) -> i64 {
    let text = event["time"].as_str().expect("a time");
    let time = humantime::parse_rfc3339_weak(text).expect("RFC 3339");
    let since = time.duration_since(UNIX_EPOCH).expect("after 1970");
    i64::try_from(since.as_secs()).expect("seconds")
}

fn mono_us(event: &Value) -> u64 {
    event["mono_us"].as_u64().expect("mono_us")
}

/// A visitor's tap (starting a session) and an operator's PAUSE, then the wall clock moved by
/// `jump`: the session ends 2 s after the tap and the PAUSE speaks 2 s after it began, by real
/// time, with events stamped on the moved clock. Returns the events from the tap on.
async fn tap_pause_and_jump(
    clock: &FakeClock,
    jump_to: i64,
    addr: &str,
    op: &mut WsClient,
    kiosk: &mut WsClient,
    tap: &str,
) -> Vec<Value> {
    let tapped = Instant::now();
    kiosk
        .send(json!({"type": "trigger", "label": "WELCOME", "ref": tap}))
        .await;
    kiosk.recv_type("triggered").await;
    // Over HTTP: the operator's websocket reads only events, none skipped.
    http_trigger(&reqwest::Client::new(), addr, "PAUSE", tap).await;
    clock.set(jump_to);
    let mut events = Vec::new();
    while !(events.iter().any(is_pause_said(tap)) && events.iter().any(is_idle_end)) {
        events.push(op.event_where(|_| true).await);
    }
    let waited = tapped.elapsed();
    assert!(waited >= Duration::from_secs(2), "over after {waited:?}");
    // Not an hour later, as on a wall clock moved back (wide: a busy machine is slow).
    assert!(
        waited < Duration::from_secs(15),
        "over only after {waited:?}"
    );
    events
}

fn is_pause_said(tap: &str) -> impl Fn(&Value) -> bool {
    move |e| {
        e["type"] == "command.sent"
            && e["label"] == "PAUSE"
            && e["verb"] == "SAY"
            && e["ref"] == tap
    }
}

fn is_idle_end(e: &Value) -> bool {
    e["type"] == "session.ended"
}

fn find(events: &[Value], what: impl Fn(&Value) -> bool) -> &Value {
    events.iter().find(|e| what(e)).expect("the event")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn session_idle_ends_and_waits_keep_real_time_when_the_wall_clock_jumps_an_hour() {
    let b = TempBundle::new(ACTS)
        .with_file(
            "docent.yaml",
            "speech: {adapter: log}\ncorpus: {session_idle: 2s}\n",
        )
        .with_file(
            "pages/index.html",
            r#"<html><body><button data-act="WELCOME">Hello</button></body></html>"#,
        );
    let corpus = tempfile::tempdir().expect("corpus folder");
    let clock = FakeClock::new();
    let (child, addr) = clock.serve(b.path(), corpus.path());
    let mut op = WsClient::operator_at(&addr).await;
    let mut kiosk = WsClient::connect(&format!("ws://{addr}/ws")).await;
    kiosk.send(json!({"type": "hello", "role": "kiosk"})).await;
    kiosk.recv_type("welcome").await;

    // Back an hour: nothing waits an hour longer.
    let back = tap_pause_and_jump(&clock, -HOUR, &addr, &mut op, &mut kiosk, "back").await;
    let started = find(&back, |e| e["type"] == "session.started");
    let ended = find(&back, |e| e["type"] == "session.ended");
    assert_eq!(ended["reason"], "idle", "{ended}");
    let moved = wall(started) - wall(ended);
    assert!(
        (HOUR - 5..=HOUR).contains(&moved),
        "the wall clock moved {moved} s back"
    );
    let idle_us = mono_us(ended) - mono_us(started);
    assert!(idle_us >= 2_000_000, "ended {idle_us} µs after it started");

    // Forward an hour (back to real time): nothing ends or fires at once.
    let forward = tap_pause_and_jump(&clock, 0, &addr, &mut op, &mut kiosk, "forward").await;
    let started = find(&forward, |e| e["type"] == "session.started");
    let ended = find(&forward, |e| e["type"] == "session.ended");
    let moved = wall(ended) - wall(started);
    assert!(
        (HOUR..=HOUR + 5).contains(&moved),
        "the wall clock moved {moved} s on"
    );
    assert!(mono_us(ended) - mono_us(started) >= 2_000_000, "{ended}");

    for (events, tap) in [(&back, "back"), (&forward, "forward")] {
        let act = find(events, |e| {
            e["type"] == "act.triggered" && e["label"] == "PAUSE" && e["ref"] == tap
        });
        let said = find(events, is_pause_said(tap));
        let paused_us = mono_us(said) - mono_us(act);
        assert!(
            (2_000_000..3_000_000).contains(&paused_us),
            "WAIT 2s took {paused_us} µs"
        );
    }
    stop(child);
    let log = common::read_corpus(corpus.path());
    assert_mono_only_grows(&log);
}

/// In `seq` order, `mono_us` never goes back, whatever the wall clock did.
fn assert_mono_only_grows(log: &[Value]) {
    let mut events: Vec<&Value> = log.iter().collect();
    events.sort_by_key(|e| e["seq"].as_u64());
    for pair in events.windows(2) {
        assert!(
            mono_us(pair[0]) <= mono_us(pair[1]),
            "{} then {}",
            pair[0],
            pair[1]
        );
    }
}

/// `YYYY-MM-DD` of a Unix time.
fn date(unix: i64) -> String {
    let time = UNIX_EPOCH + Duration::from_secs(u64::try_from(unix).expect("after 1970"));
    humantime::format_rfc3339_seconds(time).to_string()[..10].to_owned()
}

/// The day log (`days/DATE/FILE`) that holds the `act.triggered` of `reference`.
fn day_log_of(corpus: &Path, reference: &str) -> PathBuf {
    let logs = docent::corpus::layout::event_logs(corpus).expect("corpus folder");
    let holds = |log: &PathBuf| {
        (json_lines(log).iter()).any(|e| e["type"] == "act.triggered" && e["ref"] == reference)
    };
    logs.into_iter()
        .find(holds)
        .expect("a log with the trigger")
}

async fn http_trigger(http: &reqwest::Client, addr: &str, label: &str, reference: &str) {
    let answer = http
        .post(format!("http://{addr}/api/acts/{label}/trigger"))
        .json(&json!({"ref": reference}))
        .send()
        .await
        .expect("POST");
    assert_eq!(answer.status(), 202);
}

#[tokio::test]
async fn an_event_goes_to_the_day_log_of_its_wall_clock_date_across_midnight_and_back() {
    let b = TempBundle::new(ACTS).with_file("docent.yaml", "speech: {adapter: log}\n");
    let corpus = tempfile::tempdir().expect("corpus folder");
    let clock = FakeClock::new();
    // Two minutes before the next midnight (UTC).
    let midnight = unix_now() - unix_now().rem_euclid(DAY) + DAY;
    let before = offset_to(midnight - 120);
    clock.set(before);
    let (child, addr) = clock.serve(b.path(), corpus.path());
    let http = reqwest::Client::new();
    http_trigger(&http, &addr, "WELCOME", "before").await;
    clock.set(before + HOUR);
    http_trigger(&http, &addr, "WELCOME", "after").await;
    clock.set(before);
    http_trigger(&http, &addr, "WELCOME", "back").await;
    stop(child);

    let (today, tomorrow) = (date(midnight - 1), date(midnight));
    let folder = |reference: &str| {
        let log = day_log_of(corpus.path(), reference);
        let day = log
            .parent()
            .and_then(|d| d.file_name())
            .expect("a date folder");
        day.to_string_lossy().into_owned()
    };
    assert_eq!(folder("before"), today);
    assert_eq!(folder("after"), tomorrow);
    // Back before midnight: the day of its `time`, in a log of its own.
    assert_eq!(folder("back"), today);
    assert_ne!(
        day_log_of(corpus.path(), "back"),
        day_log_of(corpus.path(), "before")
    );
    assert_mono_only_grows(&common::read_corpus(corpus.path()));
}

#[tokio::test]
async fn opening_hours_follow_the_wall_clock_when_it_jumps() {
    let b = TempBundle::new(ACTS)
        .with_file(
            "docent.yaml",
            "speech: {adapter: log}\n\
             schedule: {closed: closed.html, open: [{days: daily, hours: '10:00-11:00'}]}\n",
        )
        .with_file("pages/index.html", "<title>home</title>")
        .with_file("pages/closed.html", "<title>closed</title>");
    let corpus = tempfile::tempdir().expect("corpus folder");
    let clock = FakeClock::new();
    // Half past ten today (UTC): open.
    let today = unix_now() - unix_now().rem_euclid(DAY);
    let half_past_ten = offset_to(today + 10 * HOUR + 30 * 60);
    clock.set(half_past_ten);
    let (child, addr) = clock.serve(b.path(), corpus.path());
    let http = reqwest::Client::new();
    let showing = async |offset: i64| {
        clock.set(offset);
        let state: Value = (http.get(format!("http://{addr}/api/state")).send().await)
            .expect("GET /api/state")
            .json()
            .await
            .expect("JSON");
        state["schedule"]["state"]
            .as_str()
            .expect("a state")
            .to_owned()
    };
    assert_eq!(showing(half_past_ten).await, "open");
    assert_eq!(
        showing(half_past_ten + HOUR).await,
        "closed",
        "half past eleven"
    );
    assert_eq!(
        showing(half_past_ten).await,
        "open",
        "back to half past ten"
    );
    assert_eq!(
        showing(half_past_ten - HOUR).await,
        "closed",
        "half past nine"
    );
    stop(child);
}
