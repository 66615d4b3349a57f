//! `docent check`: the bundle's problems, each at its place, for people or as JSON, with what
//! only this computer can tell (the espeak-ng voices, whether ffmpeg reads the media to
//! convert), and the exit status `--deny-warnings` asks for.

use std::io::{IsTerminal, Write};
use std::path::Path;
use std::process::ExitCode;

use clap::ValueEnum;

use crate::adapters::{espeak_available, espeak_voices};
use crate::content::{
    Colour, Diagnostic, LoadReport, Severity, espeak_speaks, load_bundle, no_voice_diagnostics,
    render_diagnostics,
};

/// How `docent check` writes the problems.
#[derive(Clone, Copy, ValueEnum)]
pub enum CheckFormat {
    /// One line per problem, for people.
    Text,
    /// A JSON array of {severity, code, message, file, line, column}, for tools.
    Json,
}

/// Checks the bundle at `bundle` and prints its problems; the exit status to end with.
pub fn run(bundle: &Path, format: CheckFormat, deny_warnings: bool) -> anyhow::Result<ExitCode> {
    let report = checked(bundle);
    let Counts {
        errors,
        warnings,
        notes,
    } = counts(&report.diagnostics);
    let printed = print_report(bundle, format, &report.diagnostics, errors, warnings, notes);
    // A reader that stopped early (`docent check | head`) is no failure of the check.
    match printed {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {}
        other => other?,
    }
    // Notes are no mistake: a bundle copied from a Mac passes `--deny-warnings`.
    let failed = errors > 0 || (deny_warnings && warnings > 0);
    Ok(if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    })
}

/// The bundle at `bundle` loaded and checked as `docent check` does, with what only this
/// computer can tell: the one check behind both `docent check` and `/report`, so the two
/// never disagree about the files on disk. Blocking (it reads the bundle and may ask
/// espeak-ng and ffmpeg): call it off the async runtime.
pub fn checked(bundle: &Path) -> LoadReport {
    let mut report = load_bundle(bundle);
    // A bundle that speaks through espeak-ng: each language needs an installed voice. Asked of
    // espeak-ng here, not while loading (loading runs nothing); serving warns the same way.
    // That is with `speech: {adapter: espeak}`, and without any adapter written where espeak-ng
    // is installed (serve's default).
    if let Some(config) = report.bundle.as_ref().map(|b| &b.config)
        && let Some(choice) = espeak_speaks(&config.speech, espeak_available())
    {
        let missing = no_voice_diagnostics(config, &espeak_voices(), choice);
        report.diagnostics.extend(missing);
    }
    // The converters are asked about media to convert here too, not while loading.
    let tools = crate::media::Tools::find();
    crate::media::check_decodable(&report.conversions, &tools, &mut report.diagnostics);
    report
}

/// Writes the problems and the summary line to standard output.
fn print_report(
    bundle: &Path,
    format: CheckFormat,
    diagnostics: &[Diagnostic],
    errors: usize,
    warnings: usize,
    notes: usize,
) -> std::io::Result<()> {
    let mut out = std::io::stdout().lock();
    match format {
        CheckFormat::Json => writeln!(out, "{}", serde_json::to_string_pretty(diagnostics)?),
        CheckFormat::Text => {
            write!(out, "{}", render(bundle, diagnostics))?;
            // Notes are counted only when there are some: most bundles have none.
            let notes = match notes {
                0 => String::new(),
                n => format!(", {n} note(s)"),
            };
            let (name, hint) = (bundle.display(), explain_hint(diagnostics));
            writeln!(
                out,
                "{name}: {errors} error(s), {warnings} warning(s){notes}"
            )?;
            hint.map_or(Ok(()), |hint| writeln!(out, "{hint}"))
        }
    }
}

/// The diagnostics drawn with their source lines, coloured on a terminal (unless `NO_COLOR`).
pub fn render(bundle: &Path, diagnostics: &[Diagnostic]) -> String {
    let colour = if std::io::stdout().is_terminal() && std::env::var_os("NO_COLOR").is_none() {
        Colour::Styled
    } else {
        Colour::Plain
    };
    render_diagnostics(bundle, diagnostics, colour)
}

/// The line after the problems pointing to `docent explain`, with the code of the first error
/// (else warning, else note) as the example: an author copies it as it is, and wants the worst
/// explained first.
pub fn explain_hint(diagnostics: &[Diagnostic]) -> Option<String> {
    let worst = diagnostics.iter().min_by_key(|d| d.severity)?;
    Some(format!(
        "For more about a problem, type: docent explain {}",
        worst.code
    ))
}

/// How many problems of each severity a check found.
pub struct Counts {
    /// Errors: the bundle is refused.
    pub errors: usize,
    /// Warnings: `--deny-warnings` fails on them.
    pub warnings: usize,
    /// Notes: never a failure.
    pub notes: usize,
}

/// The problems of each severity in `diagnostics`.
pub fn counts(diagnostics: &[Diagnostic]) -> Counts {
    let of = |severity| {
        diagnostics
            .iter()
            .filter(|d| d.severity == severity)
            .count()
    };
    Counts {
        errors: of(Severity::Error),
        warnings: of(Severity::Warning),
        notes: of(Severity::Note),
    }
}
