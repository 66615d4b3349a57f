//! `docent translations`: its command line, what it prints and its exit codes.
//!
//! Exit status (docs/AUTHORING.md, "Working with a translator"): 0 when done with nothing to
//! report; 1 when refused or failed, with nothing written (a bundle with errors, a language
//! not in `languages:`, a table that cannot be read, a cell that refuses the table (a shifted
//! row or column, a stale or repeated key, an error value, a formula, an unfinished or copied
//! target), a result that would not load for a reason outside the written texts); 2 for a command line clap cannot read; 3 when an import
//! wrote what it could (or had nothing to write) but reported rows or texts that need a look,
//! a translation left out for an error in its texts among them.

use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use crate::content::{Bundle, Language, load_bundle};

use crate::content::translations::csv::{read_csv, write_csv};
use crate::content::translations::import::{language_name, plan, target_language};
use crate::content::translations::save::{replace_file, save};
use crate::content::translations::table::rows;
use crate::content::translations::xliff::{read_xliff, unwritable, write_xliff};
use crate::content::translations::{Format, ReadError};

/// `docent translations`'s arguments.
/// `--format`: the formats a table is written in, as the command line names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum FormatArg {
    /// Comma-separated values (RFC 4180, UTF-8 with a byte order mark), for spreadsheets.
    Csv,
    /// XLIFF 1.2, for CAT tools.
    Xliff,
}

impl From<FormatArg> for Format {
    fn from(arg: FormatArg) -> Format {
        match arg {
            FormatArg::Csv => Format::Csv,
            FormatArg::Xliff => Format::Xliff,
        }
    }
}

#[derive(Debug, clap::Args)]
pub struct TranslationsArgs {
    /// What to do.
    #[command(subcommand)]
    pub command: TranslationsCommand,
}

/// What `docent translations` does.
#[derive(Debug, clap::Subcommand)]
pub enum TranslationsCommand {
    /// Write a table of every text with its translation into one language (CSV for a
    /// spreadsheet, XLIFF 1.2 for a CAT tool), keyed LABEL/Variant/N.
    Export {
        /// The bundle folder.
        bundle: PathBuf,
        /// The language to translate into (one of docent.yaml's `languages:` but the first).
        #[arg(long)]
        language: String,
        /// csv or xliff; by default the output file's extension says, else csv.
        #[arg(long, value_enum)]
        format: Option<FormatArg>,
        /// The file to write (replaced atomically); by default the table goes to stdout.
        #[arg(long, value_name = "FILE")]
        output: Option<PathBuf>,
    },
    /// Write a filled table's translations into the acts files as `Variant@xx:` lists.
    Import {
        /// The bundle folder.
        bundle: PathBuf,
        /// The table (CSV or XLIFF, told by its extension or its first bytes).
        file: PathBuf,
        /// The translations' language; by default the table's own (its column heading or
        /// target-language).
        #[arg(long)]
        language: Option<String>,
    },
}

/// Exit status 3: done, with problems reported.
const REPORTED: u8 = 3;

/// Runs a `docent translations` command.
pub fn run(args: &TranslationsArgs) -> ExitCode {
    let mut out = io::stdout().lock();
    let result = match &args.command {
        TranslationsCommand::Export {
            bundle,
            language,
            format,
            output,
        } => export(
            bundle,
            language,
            format.map(Format::from),
            output.as_deref(),
            &mut out,
        ),
        TranslationsCommand::Import {
            bundle,
            file,
            language,
        } => import(bundle, file, language.as_deref(), &mut out),
    };
    let flushed = result.and_then(|code| out.flush().map(|()| code).map_err(Refusal::from));
    match flushed {
        Ok(code) => code,
        Err(Refusal::Output(e)) if e.kind() == io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("docent: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Why a command did nothing (exit status 1).
#[derive(Debug, thiserror::Error)]
enum Refusal {
    #[error("{0}")]
    Said(String),
    #[error("could not write the output: {0}")]
    Output(#[from] io::Error),
}

/// The bundle, loaded without errors, or a refusal listing them.
fn loaded(path: &Path) -> Result<Bundle, Refusal> {
    let report = load_bundle(path);
    report.bundle.ok_or_else(|| {
        let errors: Vec<String> = (report.diagnostics.iter())
            .filter(|d| d.is_error())
            .map(|d| format!("  {d}"))
            .collect();
        Refusal::Said(format!(
            "{} has errors, so its texts cannot be exported or imported (`docent check {}` \
             shows them with their lines):\n{}",
            path.display(),
            path.display(),
            errors.join("\n")
        ))
    })
}

fn export(
    bundle_path: &Path,
    language: &str,
    format: Option<Format>,
    output: Option<&Path>,
    out: &mut dyn Write,
) -> Result<ExitCode, Refusal> {
    let bundle = loaded(bundle_path)?;
    let languages = &bundle.config.languages;
    let target = target_language(language, languages).map_err(Refusal::Said)?;
    let format = match (format, output) {
        (Some(format), _) => format,
        (None, None) => Format::Csv,
        (None, Some(path)) => Format::of_path(path).ok_or_else(|| {
            Refusal::Said(format!(
                "{} does not end in .csv, .xlf or .xliff: say the format with --format csv or \
                 --format xliff",
                path.display()
            ))
        })?,
    };
    let rows = rows(&bundle, &target);
    let mut bytes = Vec::new();
    match format {
        Format::Csv => write_csv(&rows, languages.default_language(), &target, &mut bytes)?,
        Format::Xliff => {
            if let Some((key, c)) = unwritable(&rows) {
                return Err(Refusal::Said(format!(
                    "{key} holds the control character U+{:04X}, which XLIFF cannot carry: \
                     remove it from the text, or export CSV",
                    u32::from(c)
                )));
            }
            let name = bundle
                .root
                .file_name()
                .map(|n| n.to_string_lossy().into_owned());
            let original = name.unwrap_or_else(|| "bundle".to_owned());
            write_xliff(
                &rows,
                languages.default_language(),
                &target,
                &original,
                &mut bytes,
            )?;
        }
    }
    let translated = rows.iter().filter(|r| r.translation.is_some()).count();
    let summary = format!(
        "{} texts for {} ({}): {translated} translated, {} to translate",
        rows.len(),
        language_name(&target),
        target,
        rows.len() - translated
    );
    match output {
        Some(path) => {
            replace_file(path, &bytes).map_err(|e| {
                Refusal::Said(format!("{} could not be written: {e}", path.display()))
            })?;
            writeln!(out, "Wrote {}: {summary}.", path.display())?;
        }
        None => {
            out.write_all(&bytes)?;
            eprintln!("docent: {summary}.");
        }
    }
    Ok(ExitCode::SUCCESS)
}

fn import(
    bundle_path: &Path,
    file: &Path,
    language: Option<&str>,
    out: &mut dyn Write,
) -> Result<ExitCode, Refusal> {
    let bundle = loaded(bundle_path)?;
    let languages = &bundle.config.languages;
    let wanted: Option<Language> = match language {
        Some(written) => Some(target_language(written, languages).map_err(Refusal::Said)?),
        None => None,
    };
    let bytes = std::fs::read(file)
        .map_err(|e| Refusal::Said(format!("{} cannot be read: {e}", file.display())))?;
    let default = languages.default_language();
    let table = match Format::of_table(file, &bytes) {
        Format::Csv => read_csv(&bytes, default, wanted.as_ref()),
        Format::Xliff => read_xliff(&bytes, default, wanted.as_ref()),
    }
    .map_err(|e: ReadError| {
        Refusal::Said(format!("{}: {e}; nothing was imported", file.display()))
    })?;
    let target = match wanted {
        Some(wanted) => wanted,
        None => target_language(&table.language, languages).map_err(|e| {
            Refusal::Said(format!("{}: the table's translations: {e}", file.display()))
        })?,
    };
    let plan = plan(&bundle, &target, &table);
    if !plan.refusals.is_empty() {
        let cells: Vec<String> = (plan.refusals.iter())
            .map(|r| format!("  {}:{r}", file.display()))
            .collect();
        return Err(Refusal::Said(format!(
            "{}: the table is not imported, and nothing was written: {} cell(s) would put \
             a text under the wrong act or write one that is no translation. Correct them in \
             the table and import it again:\n{}",
            file.display(),
            cells.len(),
            cells.join("\n")
        )));
    }
    let saved = if plan.changes.is_empty() {
        Default::default()
    } else {
        save(&bundle, &target, &plan.changes).map_err(|e| Refusal::Said(e.to_string()))?
    };
    let added = saved.written.iter().filter(|c| !c.replaces).count();
    let replaced = saved.written.len() - added;
    let name = language_name(&target);
    writeln!(
        out,
        "{name} ({target}) from {}: {added} translation(s) added, {replaced} replaced, {} \
         unchanged.",
        file.display(),
        plan.unchanged
    )?;
    if !saved.files.is_empty() {
        writeln!(out, "Written: {}.", saved.files.join(", "))?;
    }
    let problems = (plan.problems.iter())
        .chain(&saved.left_out)
        .chain(&saved.new_warnings);
    let reported = plan.problems.len() + saved.left_out.len() + saved.new_warnings.len();
    if reported > 0 {
        writeln!(out, "{reported} problem(s):")?;
        for problem in problems {
            writeln!(out, "  {problem}")?;
        }
        return Ok(ExitCode::from(REPORTED));
    }
    Ok(ExitCode::SUCCESS)
}
