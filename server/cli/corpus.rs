//! `docent corpus`: its command line (`CorpusArgs`, one variant per command), its exit codes,
//! and what `list` and `purge` print: the catalog (`catalog.rs`) and a purge (`purge.rs`) in
//! words for a researcher; `corpus_show.rs` prints one session, `corpus_export.rs` runs an export.
//! Format and exit codes: docs/CORPUS.md, "Command line".

use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use crate::cli::corpus_export::{ExportRequest, export};
use crate::cli::corpus_show::show;
use crate::cli::units::{count, minute_and_second, short_duration, size};
use crate::corpus::catalog::{Catalog, CorpusError};
use crate::corpus::export::ExportFormat;
use crate::corpus::log_lock::LogLock;
use crate::corpus::purge::{PurgeError, purge as purge_session};
use crate::corpus::session_folder::{SessionFolder, SessionState};

/// `docent corpus`'s arguments.
#[derive(Debug, clap::Args)]
pub struct CorpusArgs {
    /// The corpus folder, as given to `docent serve --corpus`.
    #[arg(long, value_name = "DIR", default_value = "corpus", global = true)]
    pub corpus: PathBuf,
    /// What to do.
    #[command(subcommand)]
    pub command: CorpusCommand,
}

/// What `docent corpus` does. A session is named by its folder (`2026-11-24T10-15-02Z`) or
/// given as that folder's path.
#[derive(Debug, clap::Subcommand)]
pub enum CorpusCommand {
    /// One line per session, oldest first: start, length, state, events, visitor group.
    List,
    /// One session: its manifest in words, its length, its events by type, its files.
    Show {
        /// The session's name or folder.
        session: String,
    },
    /// Remove a session's folder completely, saying every file removed; refused while a
    /// server records it.
    Purge {
        /// The session's name or folder.
        session: String,
    },
    /// Export a session (or every one, `--all`) for ELAN, Praat, a spreadsheet, Foxglove or
    /// a script: `--format eaf,textgrid,csv,jsonl,mcap`. By default into the session's own `exports/`.
    Export {
        /// The session's name or folder.
        #[arg(required_unless_present = "all", conflicts_with = "all")]
        session: Option<String>,
        /// Every session of the corpus (one being recorded is passed over).
        #[arg(long)]
        all: bool,
        /// The formats: eaf, textgrid, csv, jsonl, mcap (several with commas).
        #[arg(long, value_delimiter = ',', required = true)]
        format: Vec<ExportFormat>,
        /// Where the files go (created if needed); by default SESSION/exports.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
    },
}

/// Runs a `docent corpus` command, writing to stdout: exit status 0 when done, 1 (the reason
/// on stderr) when refused or failed. A reader that stops reading (`| head`) is no failure.
pub fn run(args: &CorpusArgs) -> ExitCode {
    let mut out = io::stdout().lock();
    let corpus = args.corpus.as_path();
    let result = match &args.command {
        CorpusCommand::List => list(corpus, &mut out),
        CorpusCommand::Show { session } => show(corpus, session, &mut out),
        CorpusCommand::Purge { session } => purge(corpus, session, &mut out),
        CorpusCommand::Export {
            session,
            all,
            format,
            out: out_dir,
        } => {
            let request = ExportRequest {
                corpus,
                session: session.as_deref(),
                all: *all,
                formats: format,
                out: out_dir.as_deref(),
            };
            export(&request, &mut out)
        }
    };
    match result.and_then(|()| Ok(out.flush()?)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(CommandError::Output(e)) if e.kind() == io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("docent: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Why a `docent corpus` command failed (exit status 1).
#[derive(Debug, thiserror::Error)]
pub enum CommandError {
    /// The corpus or the session could not be read or found.
    #[error(transparent)]
    Corpus(#[from] CorpusError),
    /// The purge was refused or stopped.
    #[error(transparent)]
    Purge(#[from] PurgeError),
    /// An export was refused or failed.
    #[error(transparent)]
    Export(crate::corpus::export::ExportError),
    /// The command cannot be carried out as given.
    #[error("{0}")]
    Usage(String),
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
    if rows.iter().skip(1).all(|row| row[6].is_empty()) {
        rows[0][6].clear();
    }
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
