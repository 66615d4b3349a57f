//! Helpers for the `docent check` tests: temporary bundles and ways to look at diagnostics.

#![allow(dead_code)] // Each test binary uses a different part of the helpers.

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

use docent_content::{Bundle, Diagnostic, LoadReport, load_bundle};

/// Lines joined into a file, one element a line: line numbers in assertions are indexes + 1.
pub fn yaml(lines: &[&str]) -> String {
    lines.iter().map(|l| format!("{l}\n")).collect()
}

/// A bundle in a temporary folder: `pages/index.html`, an empty `media/`, and `files`.
pub fn bundle(files: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("temp dir");
    fs::create_dir_all(dir.path().join("pages")).expect("pages");
    fs::create_dir_all(dir.path().join("media")).expect("media");
    fs::write(
        dir.path().join("pages/index.html"),
        "<!doctype html><title>home</title>",
    )
    .expect("home");
    for (rel, contents) in files {
        let path = dir.path().join(rel);
        fs::create_dir_all(path.parent().expect("parent")).expect("folders");
        fs::write(path, contents).expect("write file");
    }
    dir
}

/// The report of the bundle at `dir` without `unused-act` warnings: the small bundles of these
/// tests trigger their acts from nothing. [`check_all`] keeps them (for the tests of that code).
pub fn check(dir: &Path) -> LoadReport {
    let mut report = load_bundle(dir);
    report
        .diagnostics
        .retain(|d| d.code != docent_content::DiagnosticCode::UnusedAct);
    report
}

/// The whole report of the bundle at `dir`.
pub fn check_all(dir: &Path) -> LoadReport {
    load_bundle(dir)
}

/// (code, file:line:column) of every diagnostic. Every place is a real one: never line or
/// column 0.
pub fn places(report: &LoadReport) -> Vec<(&'static str, String)> {
    report
        .diagnostics
        .iter()
        .map(|d| {
            assert!(
                d.line > 0 && d.column > 0,
                "a diagnostic without a place: {d}"
            );
            (
                d.code.as_str(),
                format!("{}:{}:{}", d.file, d.line, d.column),
            )
        })
        .collect()
}

pub fn only<'r>(report: &'r LoadReport, code: &str) -> Vec<&'r Diagnostic> {
    report
        .diagnostics
        .iter()
        .filter(|d| d.code == code)
        .collect()
}

/// Messages are for museum staff: no Rust or parser vocabulary.
pub fn assert_plain(report: &LoadReport) {
    for d in &report.diagnostics {
        for jargon in [
            "Option<",
            "String",
            "scalar",
            "serde",
            "struct",
            "invalid type",
            "u32",
            "f64",
            "simple key",
            "trailing content",
            "block sequence",
            "mapping",
            "YAML cannot read the file from here (",
        ] {
            assert!(!d.message.contains(jargon), "{d} uses `{jargon}`");
        }
    }
}

/// The bundle of a report that must have no errors (the errors are the failure message).
pub fn loaded(report: LoadReport) -> Bundle {
    let errors: Vec<String> = report
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| d.to_string())
        .collect();
    assert!(
        errors.is_empty(),
        "unexpected errors:\n{}",
        errors.join("\n")
    );
    report.bundle.expect("a bundle when there are no errors")
}

/// Visitor groups and their contexts, as the console's settings hold them.
pub fn groups(pairs: &[(&str, &str)]) -> BTreeMap<String, String> {
    pairs
        .iter()
        .map(|(g, c)| ((*g).to_owned(), (*c).to_owned()))
        .collect()
}
