//! What can stop an export ([`ExportError`]) and what a researcher should know about one that
//! went through ([`ExportWarning`]), each in words that say what to do.

use std::io;
use std::path::PathBuf;

/// Why a session could not be exported.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The folder does not exist.
    #[error(
        "there is no session folder {0}: a session is named by its folder under the corpus \
         folder's `sessions/` (`docent corpus list` names them)"
    )]
    UnknownSession(PathBuf),
    /// The folder exists but holds no session log.
    #[error(
        "{0} is not a session folder: it has no `events.jsonl` (a session folder is one under \
         the corpus folder's `sessions/`)"
    )]
    NotASession(PathBuf),
    /// A running Docent is still writing the session's log.
    #[error(
        "session {0} is still being recorded: a running Docent is writing its log. End the \
         session first (the console's session button, a dialog manager's `session_end` mark, \
         or stopping the server), then export it"
    )]
    Recording(String),
    /// A file of the session could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: io::Error,
    },
    /// A line of the session's log is not a corpus line.
    #[error(
        "{path}:{line}: the session's log is damaged: {problem}. Nothing was exported; \
         repair or remove that line (keep a copy of the original) and export again"
    )]
    DamagedLog {
        /// The log.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong with it.
        problem: String,
    },
    /// The session's manifest is missing or not a manifest.
    #[error(
        "{path}: the session's manifest is missing or damaged ({problem}); nothing was \
         exported"
    )]
    DamagedManifest {
        /// `session.json`.
        path: PathBuf,
        /// What is wrong with it.
        problem: String,
    },
    /// An export file could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The file (or folder).
        path: PathBuf,
        /// The operating system's error.
        source: io::Error,
    },
}

/// Something an export went through with, that the researcher should know.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ExportWarning {
    /// The log ends with a line without its `\n`, cut short by a kill or a power cut.
    #[error(
        "{path}:{line}: the log's last line is incomplete (the server was killed while \
         writing it) and was left out; it had not been acknowledged to anyone"
    )]
    IncompleteLastLine {
        /// The log.
        path: PathBuf,
        /// Its line number.
        line: usize,
    },
    /// The log has no `session.ended`: the server was killed or crashed during the session.
    #[error(
        "the session has no `session.ended` (its server was killed or crashed while it ran): \
         it is taken to end at its last line, {end_s} s after its start, and what was under \
         way then is shown as ending there"
    )]
    NotEnded {
        /// The session's length taken, in seconds.
        end_s: String,
    },
    /// The act vocabulary could not take the bundle's labels.
    #[error("the EAF's vocabulary of act labels holds only the labels this session used: {0}")]
    VocabularyFromSessionOnly(String),
    /// Characters XML cannot hold were replaced.
    #[error(
        "{count} control character(s) in the session's texts cannot be written in XML and \
         were written as U+FFFD in the EAF (the CSV and TextGrid have them as they are)"
    )]
    CharactersReplaced {
        /// How many.
        count: usize,
    },
    /// Lines of `annotations.jsonl` that could not be read were left out.
    #[error("{path}:{line}: left out of the export: {problem}")]
    AnnotationLineLeftOut {
        /// `annotations.jsonl`.
        path: PathBuf,
        /// Its line number.
        line: usize,
        /// Why.
        problem: String,
    },
    /// The visitors did not consent to being recorded (declined, or withdrew): no recording
    /// of them is exported, and none is linked or named.
    #[error(
        "the visitors' consent is {consent:?}, not \"recorded\": no recording of this session \
         is exported, copied or linked{}",
        if *files > 0 {
            format!(" ({files} media file(s) are still in its folder: `docent corpus purge` or \
                     the server's next start removes them)")
        } else {
            String::new()
        }
    )]
    MediaWithheld {
        /// The manifest's consent word.
        consent: String,
        /// Media files left in the session's folder or listed in its manifest.
        files: usize,
    },
    /// An annotation ends after its session's end (written before the server checked that):
    /// left out, so that it cannot stretch every tier past the session.
    #[error(
        "annotations.jsonl: annotation {id} ends at {end_s} s, after the session's end at \
         {session_end_s} s, and was left out of the export"
    )]
    AnnotationPastEnd {
        /// The annotation's id.
        id: String,
        /// Its end, seconds on the session clock.
        end_s: String,
        /// The session's end, seconds on its clock.
        session_end_s: String,
    },
    /// The manifest lists a media file the session's folder does not have.
    #[error(
        "session.json lists the media file {file:?}, which is not a file in the session's \
         folder (deleted, moved, or a path outside it): the MCAP's `docent.media` names it all \
         the same, but a player will not find it there, and the EAF has no WAV copy of it"
    )]
    MediaNotInSession {
        /// The `file` as the manifest gives it.
        file: String,
    },
    /// A recording's sound could not be decoded at all: no WAV copy of it was written.
    #[error(
        "no WAV copy of the recording {file:?} was written, and the EAF does not link it: \
         {problem}"
    )]
    MediaNotCopied {
        /// The `file` as the manifest gives it.
        file: String,
        /// Why.
        problem: String,
    },
    /// A recording's WAV copy stops before the recording's end.
    #[error("the WAV copy of the recording {file:?} stops early: {problem}")]
    MediaPartlyCopied {
        /// The `file` as the manifest gives it.
        file: String,
        /// What was left out, from where.
        problem: String,
    },
}

/// A name given for `--format` that is not one.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{0:?} is not an export format: use eaf, textgrid, csv, jsonl or mcap")]
pub struct UnknownFormat(pub String);
