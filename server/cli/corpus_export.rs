//! `docent corpus export`: one session, or every session with `--all`, to the formats asked
//! for, each file written said as it is written, and what a researcher should know about it
//! (an incomplete last line, a session never ended). With `--all`, a session being recorded
//! is passed over and said so, a damaged one does not stop the others (the run then ends with
//! status 1), and a progress bar runs on the terminal.

use std::io::Write;
use std::path::{Path, PathBuf};

use indicatif::{ProgressBar, ProgressStyle};

use crate::cli::corpus::CommandError;
use crate::corpus::catalog::{Catalog, find_session};
use crate::corpus::export::{EXPORTS_DIR, ExportError, ExportFormat, SessionExport};
use crate::corpus::session_folder::SessionState;

/// What to export, and where.
pub struct ExportRequest<'a> {
    /// The corpus folder.
    pub corpus: &'a Path,
    /// The session's name or folder; `None` with `all`.
    pub session: Option<&'a str>,
    /// Every session of the corpus.
    pub all: bool,
    /// The formats, each once.
    pub formats: &'a [ExportFormat],
    /// Where the files go; by default each session's own `exports/` folder.
    pub out: Option<&'a Path>,
}

/// Runs the export, printing each file written and each warning to `out`.
pub fn export(request: &ExportRequest<'_>, out: &mut dyn Write) -> Result<(), CommandError> {
    let mut formats = request.formats.to_vec();
    formats.dedup();
    match (request.session, request.all) {
        (Some(session), false) => {
            let (_, dir) = find_session(request.corpus, session)?;
            let files = export_one(&dir, &formats, request.out, out)?;
            writeln!(out, "exported {}", count_files(files))?;
            Ok(())
        }
        (None, true) => export_all(request, &formats, out),
        _ => Err(CommandError::Usage(
            "name one session, or give --all for every session of the corpus".into(),
        )),
    }
}

fn export_all(
    request: &ExportRequest<'_>,
    formats: &[ExportFormat],
    out: &mut dyn Write,
) -> Result<(), CommandError> {
    let catalog = Catalog::read(request.corpus)?;
    // Drawn on stderr, and only on a terminal: files and warnings stay on stdout.
    let bar = ProgressBar::new(catalog.sessions.len() as u64);
    bar.set_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} sessions {msg}")
            .expect("a fixed template"),
    );
    let (mut files, mut exported_sessions, mut failed) = (0, 0, Vec::new());
    for session in &catalog.sessions {
        bar.set_message(session.name.clone());
        if session.state() == SessionState::Recording {
            bar.suspend(|| writeln!(out, "{}: being recorded, passed over", session.name))?;
        } else {
            let exported = bar.suspend(|| export_one(&session.dir, formats, request.out, out));
            match exported {
                Ok(n) => {
                    files += n;
                    exported_sessions += 1;
                }
                Err(CommandError::Export(e)) => {
                    bar.suspend(|| writeln!(out, "{}: not exported: {e}", session.name))?;
                    failed.push(session.name.clone());
                }
                Err(e) => return Err(e),
            }
        }
        bar.inc(1);
    }
    bar.finish_and_clear();
    writeln!(
        out,
        "exported {} from {exported_sessions} of {} sessions",
        count_files(files),
        catalog.sessions.len()
    )?;
    if failed.is_empty() {
        Ok(())
    } else {
        Err(CommandError::Usage(format!(
            "{} could not be exported (said above): {}",
            if failed.len() == 1 {
                "1 session"
            } else {
                "some sessions"
            },
            failed.join(", ")
        )))
    }
}

/// Exports the session in `dir` to every format; returns how many files were written.
fn export_one(
    dir: &Path,
    formats: &[ExportFormat],
    out_dir: Option<&Path>,
    out: &mut dyn Write,
) -> Result<usize, CommandError> {
    let session = SessionExport::open(dir)?;
    let target: PathBuf = out_dir.map_or_else(|| dir.join(EXPORTS_DIR), Path::to_owned);
    for warning in session.warnings() {
        writeln!(out, "{}: note: {warning}", session.name())?;
    }
    let mut written = 0;
    for &format in formats {
        let exported = session.write(format, &target)?;
        for file in &exported.files {
            writeln!(out, "wrote {}", file.display())?;
        }
        // Warnings of the session itself were said once, above.
        for warning in exported.warnings.iter().skip(session.warnings().len()) {
            writeln!(out, "{}: note: {warning}", session.name())?;
        }
        written += exported.files.len();
    }
    Ok(written)
}

fn count_files(n: usize) -> String {
    if n == 1 {
        "1 file".to_owned()
    } else {
        format!("{n} files")
    }
}

impl From<ExportError> for CommandError {
    fn from(e: ExportError) -> Self {
        CommandError::Export(e)
    }
}
