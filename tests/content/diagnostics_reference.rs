//! `docs/DIAGNOSTICS.md`, the reference of every problem, is generated from the checker's own
//! table (`server/content/diagnostic.rs`) and each code's page (`server/content/diagnostics/
//! CODE.md`): these tests fail while the file is out of date, showing what differs, and
//! `DOCENT_BLESS=1` rewrites it (docs/DIAGNOSTICS.md says how).

use std::fs;

use docent_content::DiagnosticCode;
use docent_content::explain::{page_problems, reference_markdown};

use crate::common;

#[test]
fn the_reference_of_every_problem_is_the_one_generated_from_the_table() {
    let path = common::repo().join("docs/DIAGNOSTICS.md");
    let generated = reference_markdown();
    if std::env::var_os("DOCENT_BLESS").is_some() {
        fs::write(&path, &generated).expect("writing docs/DIAGNOSTICS.md");
        return;
    }
    let written = fs::read_to_string(&path).unwrap_or_default();
    if written != generated {
        panic!(
            "docs/DIAGNOSTICS.md is out of date; run\n  DOCENT_BLESS=1 cargo test --locked \
             -p docent-content --test content diagnostics_reference\nFirst difference:\n{}",
            first_difference(&written, &generated)
        );
    }
}

#[test]
fn every_code_has_a_page_with_its_kind_severity_fix_and_a_broken_example() {
    let problems = page_problems();
    assert!(problems.is_empty(), "{problems:#?}");
}

#[test]
fn every_page_in_the_folder_is_a_code_docent_has() {
    let dir = common::repo().join("server/content/diagnostics");
    let codes: Vec<&str> = DiagnosticCode::ALL.iter().map(|c| c.as_str()).collect();
    let mut stale = Vec::new();
    let mut pages = 0;
    for entry in fs::read_dir(&dir).expect("server/content/diagnostics") {
        let name = entry.expect("an entry").file_name();
        let name = name.to_string_lossy();
        pages += 1;
        match name.strip_suffix(".md") {
            Some(code) if codes.contains(&code) => {}
            _ => stale.push(name.into_owned()),
        }
    }
    assert!(stale.is_empty(), "pages of no code Docent has: {stale:?}");
    assert_eq!(pages, codes.len(), "one page for each code");
}

#[test]
fn every_code_is_in_the_reference_at_its_own_heading() {
    let reference = reference_markdown();
    let missing: Vec<&str> = DiagnosticCode::ALL
        .iter()
        .map(|c| c.as_str())
        .filter(|code| {
            !reference.contains(&format!("\n#### `{code}`\n"))
                || !reference.contains(&format!("| `{code}` |"))
        })
        .collect();
    assert!(
        missing.is_empty(),
        "neither a row nor an entry: {missing:?}"
    );
}

/// The first line that differs, with its number, both ways.
fn first_difference(written: &str, generated: &str) -> String {
    let mut written_lines = written.lines();
    let mut generated_lines = generated.lines();
    for number in 1.. {
        match (written_lines.next(), generated_lines.next()) {
            (Some(w), Some(g)) if w == g => continue,
            (None, None) => break,
            (w, g) => {
                return format!(
                    "line {number}\n  in the file:  {}\n  generated:    {}",
                    w.unwrap_or("(end of file)"),
                    g.unwrap_or("(end of file)")
                );
            }
        }
    }
    "only the line endings".to_string()
}
