//! Where the corpus folder keeps what, the one definition of these names for the writer and
//! for `docent corpus`: one folder per visitor session under `sessions/` (its event log and
//! its manifest), and the events outside any session in day folders under `days/`, one log
//! per server run and day (so no file is ever appended to by two runs).
//!
//! ```text
//! corpus/
//!   days/2026-11-24/09-12-00Z.jsonl             events outside sessions of the run whose
//!                                               first such event that day was at 09:12:00 UTC
//!   sessions/2026-11-24T10-15-02Z/events.jsonl  one session's events
//!   sessions/2026-11-24T10-15-02Z/session.json  its manifest
//! ```

use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// The folder of the day logs.
pub const DAYS_DIR: &str = "days";
/// The folder of the session folders.
pub const SESSIONS_DIR: &str = "sessions";
/// A session's event log, inside its folder.
pub const SESSION_EVENTS: &str = "events.jsonl";
/// A session's manifest, inside its folder.
pub const SESSION_MANIFEST: &str = "session.json";
/// The folder of a session's recordings, inside its folder (`media/audio-1.webm`).
pub const MEDIA_DIR: &str = "media";

/// The UTC date of `time`, `2026-11-24`: every time in the corpus is UTC.
pub fn utc_date(time: SystemTime) -> String {
    let stamp = humantime::format_rfc3339_seconds(time).to_string();
    stamp.get(..10).unwrap_or(&stamp).to_owned()
}

/// A new day log for a run's events outside sessions from `time` on, neither on disk nor
/// `taken`: in the folder of its UTC date, named after the time of day.
pub fn new_day_log(corpus: &Path, time: SystemTime, taken: impl Fn(&Path) -> bool) -> PathBuf {
    let stamp = humantime::format_rfc3339_seconds(time)
        .to_string()
        .replace(':', "-");
    let (date, clock) = stamp.split_at(stamp.find('T').unwrap_or(0));
    let day = corpus.join(DAYS_DIR).join(date);
    let clock = clock.trim_start_matches('T');
    let free = |p: &PathBuf| !p.exists() && !taken(p);
    std::iter::once(day.join(format!("{clock}.jsonl")))
        .chain((1..).map(|n| day.join(format!("{clock}-{n}.jsonl"))))
        .find(free)
        .expect("an endless list has a free name")
}

/// A new folder for a session that started at `started`, neither on disk nor `taken`: named
/// after the start in UTC (`:` is not allowed in Windows file names, so `-`), with `-1`, `-2`,
/// ... when sessions start in the same second.
pub fn new_session_dir(
    corpus: &Path,
    started: SystemTime,
    taken: impl Fn(&Path) -> bool,
) -> PathBuf {
    let stamp = humantime::format_rfc3339_seconds(started)
        .to_string()
        .replace(':', "-");
    let sessions = corpus.join(SESSIONS_DIR);
    let free = |p: &PathBuf| !p.exists() && !taken(p);
    std::iter::once(sessions.join(&stamp))
        .chain((1..).map(|n| sessions.join(format!("{stamp}-{n}"))))
        .find(free)
        .expect("an endless list has a free name")
}

/// Every event log in the corpus folder: the day logs by date and time, then each session's
/// log by the session's start.
pub fn event_logs(corpus: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut logs = day_logs(corpus)?;
    let sessions = sorted_entries(&corpus.join(SESSIONS_DIR))?;
    logs.extend(
        (sessions.into_iter())
            .map(|s| s.join(SESSION_EVENTS))
            .filter(|p| p.is_file()),
    );
    Ok(logs)
}

/// The day logs in the corpus folder, by date and time (files beside the date folders are
/// not day logs).
pub fn day_logs(corpus: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut logs = Vec::new();
    let days = sorted_entries(&corpus.join(DAYS_DIR))?;
    for day in days.into_iter().filter(|d| d.is_dir()) {
        let mut runs = sorted_entries(&day)?;
        runs.retain(|p| p.extension().is_some_and(|e| e == "jsonl"));
        logs.extend(runs);
    }
    Ok(logs)
}

/// The entries of `dir`, sorted by name; none when it does not exist.
fn sorted_entries(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let entries = match std::fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(e),
    };
    let mut paths = entries
        .map(|e| e.map(|e| e.path()))
        .collect::<std::io::Result<Vec<_>>>()?;
    paths.sort();
    Ok(paths)
}

#[cfg(test)]
mod tests {
    use std::time::{Duration, UNIX_EPOCH};

    use super::*;

    #[test]
    fn day_logs_are_named_by_utc_date_and_sessions_by_their_start() {
        let corpus = tempfile::tempdir().unwrap();
        let time = UNIX_EPOCH + Duration::from_secs(1_795_000_000);
        let day = new_day_log(corpus.path(), time, |_| false);
        assert_eq!(day, corpus.path().join("days/2026-11-18/11-06-40Z.jsonl"));
        let again = new_day_log(corpus.path(), time, |p| p == day);
        assert_eq!(
            again,
            corpus.path().join("days/2026-11-18/11-06-40Z-1.jsonl")
        );
        assert_eq!(utc_date(time), "2026-11-18");
        let first = new_session_dir(corpus.path(), time, |_| false);
        assert_eq!(first, corpus.path().join("sessions/2026-11-18T11-06-40Z"));
        std::fs::create_dir_all(&first).unwrap();
        let second = new_session_dir(corpus.path(), time, |_| false);
        assert_eq!(
            second,
            corpus.path().join("sessions/2026-11-18T11-06-40Z-1")
        );
        let third = new_session_dir(corpus.path(), time, |p| p == second);
        assert_eq!(third, corpus.path().join("sessions/2026-11-18T11-06-40Z-2"));
    }
}
