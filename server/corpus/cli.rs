//! What `docent corpus list`, `show` and `purge` print: the catalog (`catalog.rs`), one
//! session (`session_folder.rs`) and a purge (`purge.rs`) in words for a researcher. The
//! command line itself (clap) is in `main.rs`; the format and the exit codes are in
//! docs/CORPUS.md, "Command line".

use std::io::{self, Write};
use std::path::Path;

use crate::corpus::catalog::{Catalog, CorpusError, find_session, folder_contents};
use crate::corpus::layout::SESSION_EVENTS;
use crate::corpus::purge::{PurgeError, purge as purge_session};
use crate::corpus::session_folder::{LogLock, SessionFolder, SessionState};

/// Why a `docent corpus` command failed (exit status 1).
#[derive(Debug, thiserror::Error)]
pub enum CommandError {
    /// The corpus or the session could not be read or found.
    #[error(transparent)]
    Corpus(#[from] CorpusError),
    /// The purge was refused or stopped.
    #[error(transparent)]
    Purge(#[from] PurgeError),
    /// The output could not be written (a closed pipe: the reader stopped reading).
    #[error("could not write the output: {0}")]
    Output(#[from] io::Error),
}

/// `docent corpus list`: one line per session, oldest first, then a summary.
pub fn list(corpus: &Path, out: &mut dyn Write) -> Result<(), CommandError> {
    let catalog = Catalog::read(corpus)?;
    if catalog.sessions.is_empty() {
        writeln!(
            out,
            "no sessions in {} ({}, {})",
            corpus.display(),
            count(catalog.day_logs, "day log"),
            size(catalog.bytes)
        )?;
        return Ok(());
    }
    let mut rows = vec![
        [
            "SESSION",
            "STARTED (UTC)",
            "DURATION",
            "STATE",
            "EVENTS",
            "GROUP",
            "PROBLEM",
        ]
        .map(str::to_owned),
    ];
    rows.extend(catalog.sessions.iter().map(row));
    write_table(out, &rows)?;
    let mut states = Vec::new();
    for state in [
        SessionState::Ended,
        SessionState::Recording,
        SessionState::Interrupted,
        SessionState::Damaged,
    ] {
        let n = catalog
            .sessions
            .iter()
            .filter(|s| s.state() == state)
            .count();
        if n > 0 {
            states.push(format!("{n} {}", state.word()));
        }
    }
    writeln!(
        out,
        "{} ({}), {}, {} in {}",
        count(catalog.sessions.len(), "session"),
        states.join(", "),
        count(catalog.day_logs, "day log"),
        size(catalog.bytes),
        corpus.display()
    )?;
    Ok(())
}

fn row(session: &SessionFolder) -> [String; 7] {
    let state = session.state();
    let duration = match state {
        SessionState::Recording => "open".to_owned(),
        SessionState::Interrupted => "interrupted".to_owned(),
        _ => session.duration_us().map_or("-".to_owned(), short_duration),
    };
    let mut problem = match (session.damage.first(), &session.lock) {
        (Some(first), _) => first.to_string(),
        (None, LogLock::Unknown(e)) => format!("cannot tell whether it is locked: {e}"),
        (None, _) => String::new(),
    };
    if session.damage.len() > 1 {
        problem.push_str(&format!(
            " (and {} more: docent corpus show {})",
            session.damage.len() - 1,
            session.name
        ));
    }
    [
        session.name.clone(),
        session.started().map_or("-".to_owned(), minute_and_second),
        duration,
        state.word().to_owned(),
        session.events().to_string(),
        session.group().unwrap_or("-").to_owned(),
        problem,
    ]
}

/// Writes `rows` as columns two spaces apart, the events (column 4) right-aligned, without
/// trailing spaces.
fn write_table(out: &mut dyn Write, rows: &[[String; 7]]) -> io::Result<()> {
    let mut widths = [0; 7];
    for row in rows {
        for (width, cell) in widths.iter_mut().zip(row) {
            *width = (*width).max(cell.chars().count());
        }
    }
    for row in rows {
        let mut line = String::new();
        for (i, (cell, width)) in row.iter().zip(widths).enumerate() {
            let cell = if i == 4 {
                format!("{cell:>width$}")
            } else {
                format!("{cell:<width$}")
            };
            line.push_str(&cell);
            line.push_str("  ");
        }
        writeln!(out, "{}", line.trim_end())?;
    }
    Ok(())
}

/// `docent corpus show SESSION`: the manifest in words, the length, the events by type, the
/// files, and whatever is wrong.
pub fn show(corpus: &Path, arg: &str, out: &mut dyn Write) -> Result<(), CommandError> {
    let (name, dir) = find_session(corpus, arg)?;
    let session = SessionFolder::read(&name, &dir);
    let state = session.state();
    writeln!(out, "session   {name}")?;
    writeln!(out, "folder    {}", dir.display())?;
    writeln!(out, "state     {}", state_in_words(&session))?;
    match &session.manifest {
        Some(m) => {
            writeln!(
                out,
                "bundle    {}",
                m.bundle.as_deref().unwrap_or("unknown")
            )?;
            writeln!(out, "docent    {}", m.docent)?;
            writeln!(out, "started   {} by {}", m.started.time, m.started.source)?;
        }
        None => {
            writeln!(out, "manifest  none readable (see the problems below)")?;
            let started = session.started().unwrap_or("unknown");
            writeln!(out, "started   {started} (from its first line)")?;
        }
    }
    writeln!(out, "ended     {}", ended_in_words(&session, state))?;
    if let Some(m) = &session.manifest {
        writeln!(
            out,
            "group     {}",
            m.group.as_deref().unwrap_or("none noted")
        )?;
        writeln!(out, "context   {}", m.context.as_deref().unwrap_or("none"))?;
    }
    let length = match session.last_session_us() {
        None => "unknown (no line with session_us)".to_owned(),
        Some(us) if session.ended() => long_duration(us),
        Some(us) if state == SessionState::Recording => format!("{} so far", long_duration(us)),
        Some(us) => format!("at least {}: it has no end", long_duration(us)),
    };
    let length = format!("{length} (on the session clock: session_us of its last line)");
    writeln!(out, "duration  {length}")?;
    writeln!(out, "events    {}", session.events())?;
    if let Some(log) = &session.log {
        let width = log.by_type.keys().map(String::len).max().unwrap_or(0);
        for (kind, n) in &log.by_type {
            writeln!(out, "  {kind:<width$}  {n:>6}")?;
        }
    }
    write_files(out, &dir)?;
    if !session.damage.is_empty() {
        writeln!(out, "problems")?;
        for damage in &session.damage {
            writeln!(out, "  {damage}")?;
        }
    }
    if let Some(line) = session.log.as_ref().and_then(|l| l.incomplete_last_line) {
        let why = if state == SessionState::Recording {
            "it is being written"
        } else {
            "a crash cut it short"
        };
        writeln!(
            out,
            "note      {SESSION_EVENTS}:{line}, its last line, is incomplete ({why}); it is not counted"
        )?;
    }
    Ok(())
}

fn state_in_words(session: &SessionFolder) -> String {
    let state = session.state();
    let why = match (state, &session.lock) {
        (SessionState::Recording, LogLock::Held) => "a running server holds its log".to_owned(),
        (SessionState::Recording, LogLock::Newborn) => "a server created its log moments ago".to_owned(),
        (SessionState::Recording, LogLock::Unknown(e)) => {
            format!("perhaps: it has no end, and whether a server holds its log is unknown: {e}")
        }
        (SessionState::Interrupted, _) => {
            "it has no end and no server holds its log: the server was killed or crashed while it ran".to_owned()
        }
        (SessionState::Damaged, _) => "see the problems below".to_owned(),
        _ => return state.word().to_owned(),
    };
    format!("{} ({why})", state.word())
}

fn ended_in_words(session: &SessionFolder, state: SessionState) -> String {
    match session.manifest.as_ref().and_then(|m| m.ended.as_ref()) {
        Some(end) => {
            let why = match end.reason.as_deref() {
                Some("marked") => "its end was marked".to_owned(),
                Some("next-session") => "the next session was started".to_owned(),
                Some("server-stopping") => "the server shut down".to_owned(),
                Some(other) => other.to_owned(),
                None => "no reason given".to_owned(),
            };
            format!("{} by {} ({why})", end.time, end.source)
        }
        None if state == SessionState::Recording => "not yet".to_owned(),
        None if session.ended() => "its log's last line ends it".to_owned(),
        None => "never".to_owned(),
    }
}

fn write_files(out: &mut dyn Write, dir: &Path) -> Result<(), CommandError> {
    let contents = folder_contents(dir)?;
    writeln!(out, "files")?;
    let names: Vec<String> = (contents.files.iter())
        .map(|(path, _)| path.strip_prefix(dir).unwrap_or(path).display().to_string())
        .collect();
    let width = names.iter().map(String::len).max().unwrap_or(0);
    for (name, (_, bytes)) in names.iter().zip(&contents.files) {
        writeln!(out, "  {name:<width$}  {bytes:>10} bytes")?;
    }
    let total: u64 = contents.files.iter().map(|(_, b)| b).sum();
    writeln!(out, "  {}, {total} bytes", count(names.len(), "file"))?;
    Ok(())
}

/// `docent corpus purge SESSION`: removes it, printing each file as it goes, then the total.
pub fn purge(corpus: &Path, arg: &str, out: &mut dyn Write) -> Result<(), CommandError> {
    let mut output = Ok(());
    let result = purge_session(corpus, arg, |file| {
        if output.is_ok() {
            output = writeln!(
                out,
                "removed {}  ({} bytes)",
                file.path.display(),
                file.bytes
            );
        }
    });
    let purged = result?;
    output?;
    writeln!(
        out,
        "purged session {}: {}, {} bytes ({}); {} removed with it, nothing else touched",
        purged.name,
        count(purged.files, "file"),
        purged.bytes,
        size(purged.bytes),
        if purged.folders == 1 {
            format!("its folder {}", purged.folder.display())
        } else {
            format!(
                "{} and {} inside it",
                purged.folder.display(),
                count(purged.folders - 1, "folder")
            )
        }
    )?;
    Ok(())
}

/// `1 session`, `3 sessions`.
fn count(n: usize, thing: &str) -> String {
    if n == 1 {
        format!("1 {thing}")
    } else {
        format!("{n} {thing}s")
    }
}

/// `812 B`, `47.1 KiB`, `3.2 MiB`.
fn size(bytes: u64) -> String {
    let mut value = bytes as f64;
    for unit in ["B", "KiB", "MiB", "GiB"] {
        if value < 1024.0 || unit == "GiB" {
            return if unit == "B" {
                format!("{bytes} B")
            } else {
                format!("{value:.1} {unit}")
            };
        }
        value /= 1024.0;
    }
    unreachable!("GiB returns")
}

/// `2026-11-24T10:15:02.629Z` as `2026-11-24 10:15:02`.
fn minute_and_second(time: &str) -> String {
    match time.get(..19) {
        Some(head) if time.is_char_boundary(19) => head.replacen('T', " ", 1),
        _ => time.to_owned(),
    }
}

/// `4.2s`, `12m 04s`, `1h 02m 03s`.
fn short_duration(us: u64) -> String {
    let seconds = us / 1_000_000;
    match seconds {
        0..60 => format!("{:.1}s", us as f64 / 1e6),
        60..3600 => format!("{}m {:02}s", seconds / 60, seconds % 60),
        _ => format!(
            "{}h {:02}m {:02}s",
            seconds / 3600,
            seconds / 60 % 60,
            seconds % 60
        ),
    }
}

/// `4.183s`, `12m 04.183s`, `1h 02m 03.000s`: to the millisecond.
fn long_duration(us: u64) -> String {
    let minutes = us / 60_000_000;
    let rest = (us % 60_000_000) as f64 / 1e6;
    match minutes {
        0 => format!("{rest:.3}s"),
        1..60 => format!("{minutes}m {rest:06.3}s"),
        _ => format!("{}h {:02}m {rest:06.3}s", minutes / 60, minutes % 60),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_sizes_and_times_read_the_way_a_person_writes_them() {
        assert_eq!(short_duration(4_200_000), "4.2s");
        assert_eq!(short_duration(724_183_000), "12m 04s");
        assert_eq!(short_duration(3_723_000_000), "1h 02m 03s");
        assert_eq!(long_duration(1_776), "0.002s");
        assert_eq!(long_duration(724_183_000), "12m 04.183s");
        assert_eq!(long_duration(3_723_000_000), "1h 02m 03.000s");
        assert_eq!(size(812), "812 B");
        assert_eq!(size(48_213), "47.1 KiB");
        assert_eq!(size(3_355_443), "3.2 MiB");
        assert_eq!(
            minute_and_second("2026-11-24T10:15:02.629Z"),
            "2026-11-24 10:15:02"
        );
        assert_eq!(minute_and_second("yesterday"), "yesterday");
        assert_eq!(
            (count(1, "file"), count(2, "file")),
            ("1 file".into(), "2 files".into())
        );
    }
}
