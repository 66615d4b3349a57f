//! `docent corpus show SESSION`: one session in words: its manifest, its length on the
//! session clock, its events by type, its files, and whatever is wrong with it (a damaged
//! session is shown as far as it can be read).

use std::io::Write;
use std::path::Path;

use crate::cli::corpus::CommandError;
use crate::cli::units::{count, long_duration};
use crate::corpus::annotations::{ANNOTATIONS_FILE, read_annotations};
use crate::corpus::catalog::{find_session, folder_contents};
use crate::corpus::layout::SESSION_EVENTS;
use crate::corpus::log_lock::LogLock;
use crate::corpus::session_folder::{SessionFolder, SessionState};

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
            if let Some(hash) = &m.bundle_hash {
                writeln!(out, "content   {hash}")?;
            }
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
        writeln!(out, "consent   {}", m.consent)?;
        for media in &m.media {
            writeln!(
                out,
                "media     {} ({}, its first sample at {} on the session clock)",
                media.file,
                media.track,
                long_duration(media.start_us)
            )?;
        }
    }
    write_annotations(out, &dir)?;
    let clock = "(on the session clock: session_us of its last line)";
    let length = match session.last_session_us() {
        None => "unknown: no line has a session_us".to_owned(),
        Some(us) if session.ended() => format!("{} {clock}", long_duration(us)),
        Some(us) if state == SessionState::Recording => {
            format!("{} so far {clock}", long_duration(us))
        }
        Some(us) => format!("at least {}: it has no end {clock}", long_duration(us)),
    };
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

/// How many annotations the session has, when researchers made any, and any line left out.
fn write_annotations(out: &mut dyn Write, dir: &Path) -> std::io::Result<()> {
    if !dir.join(ANNOTATIONS_FILE).is_file() {
        return Ok(());
    }
    match read_annotations(dir) {
        Ok(read) => {
            let n = read.annotations.len();
            writeln!(
                out,
                "annotations {} ({ANNOTATIONS_FILE})",
                count(n, "annotation")
            )?;
            for (line, problem) in &read.problems {
                writeln!(out, "  {ANNOTATIONS_FILE}:{line} left out: {problem}")?;
            }
        }
        Err(e) => writeln!(out, "annotations unreadable: {ANNOTATIONS_FILE}: {e}")?,
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
                Some("idle") => "no visitor touched the screen for the idle time".to_owned(),
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
