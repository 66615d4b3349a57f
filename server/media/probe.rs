//! `docent check` asks the converters about each planned file, so a file they cannot read is
//! an error at the line that shows it (`media-undecodable`), not a surprise on the projector;
//! and says when the converter itself is missing on this computer.

use std::path::PathBuf;
use std::process::{Command, Stdio};

use crate::content::{Conversion, Diagnostic, DiagnosticCode, Severity};

use super::recipe::last_words;
use super::run::Tools;

/// Adds what the converters say about `conversions` to `diagnostics`: an error for a file
/// they cannot read; the file's `media-converted` note made a warning when the converter it
/// needs is not installed.
pub fn check_decodable(
    conversions: &[Conversion],
    tools: &Tools,
    diagnostics: &mut Vec<Diagnostic>,
) {
    for conversion in conversions {
        let at = |d: &Diagnostic| {
            d.code == DiagnosticCode::MediaConverted
                && d.file == *conversion.pos.file
                && d.line == conversion.pos.line
                && d.column == conversion.pos.column
        };
        if let Some(missing) = tools.missing_for(conversion.format) {
            if let Some(note) = diagnostics.iter_mut().find(|d| at(d)) {
                note.severity = Severity::Warning;
                note.message = format!(
                    "{} But {missing}: until then it is not shown.",
                    note.message
                );
            }
            continue;
        }
        if let Err(said) = readable(conversion, tools) {
            let message = format!(
                "`{}` cannot be converted for Chromium: ffmpeg cannot read it ({said}). The \
                 file may be damaged, cut short by a copy, or not what its name says. Open it \
                 on a computer to check, and export it again.",
                conversion.shown
            );
            diagnostics.retain(|d| !at(d));
            diagnostics.push(Diagnostic::error(
                DiagnosticCode::MediaUndecodable,
                &conversion.pos,
                message,
            ));
        }
    }
    diagnostics.sort_by(|a, b| (&a.file, a.line, a.column).cmp(&(&b.file, b.line, b.column)));
}

/// Whether the converter reads the file: `heif-info` for HEIC photos, else ffprobe, which
/// must find a picture, film or sound in it.
fn readable(conversion: &Conversion, tools: &Tools) -> Result<(), String> {
    let (tool, args): (PathBuf, Vec<&str>) = if conversion.format == "HEIC" {
        (tools.heif_info(), vec![])
    } else {
        let ffprobe = tools
            .ffprobe
            .clone()
            .unwrap_or_else(|| PathBuf::from("ffprobe"));
        let entries = vec![
            "-v",
            "error",
            "-show_entries",
            "stream=codec_type",
            "-of",
            "csv=p=0",
        ];
        (ffprobe, entries)
    };
    let output = Command::new(&tool)
        .args(args)
        .arg(&conversion.path)
        .stdout(Stdio::piped())
        .stdin(Stdio::null())
        .output()
        .map_err(|e| format!("{} could not be started: {e}", tool.display()))?;
    let said = String::from_utf8_lossy(&output.stderr);
    if !output.status.success() {
        return Err(last_words(&said));
    }
    if conversion.format != "HEIC" && output.stdout.iter().all(u8::is_ascii_whitespace) {
        return Err("it holds no picture, film or sound".to_owned());
    }
    Ok(())
}
