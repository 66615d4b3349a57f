//! `docent explain`: a code's entry from the reference in the terminal, a mistyped code
//! answered with the nearest one, and `docent check` ending with the command that explains its
//! most serious problem.

use crate::common;

use common::TempBundle;
use common::process::run_docent;

use super::cli::BROKEN;

#[test]
fn check_ends_with_the_command_that_explains_its_first_problem() {
    let b = TempBundle::new(BROKEN);
    let (code, text, _) = run_docent(&["check", b.path().to_str().unwrap()]);
    assert_eq!(code, 1, "{text}");
    assert!(
        text.trim_end()
            .ends_with("For more about a problem, type: docent explain unknown-verb"),
        "{text}"
    );
    // The worst problem is named, not the first: the ignored `.DS_Store` is a note listed
    // before the unknown verb's error.
    let b = TempBundle::new("- Label: A\n  Text: [Hello]\n  Cmds: [SAYY Hi]\n");
    let ignored = b.path().join(".DS_Store");
    std::fs::write(&ignored, b"\0\0\0\x01Bud1").expect("a Finder file");
    let (_, text, _) = run_docent(&["check", b.path().to_str().unwrap()]);
    assert!(text.contains("note[ignored-files]"), "{text}");
    assert!(
        text.trim_end().ends_with("docent explain unknown-verb"),
        "the error, not the note before it: {text}"
    );
    // A bundle with nothing to report has no such line.
    let b = TempBundle::new("- Label: A\n  Text: [Hello]\n");
    let (code, text, _) = run_docent(&["check", b.path().to_str().unwrap()]);
    assert_eq!(code, 0, "{text}");
    assert!(!text.contains("docent explain"), "{text}");
}

#[test]
fn explain_prints_a_codes_entry_with_its_broken_example_and_fix() {
    let (code, text, _) = run_docent(&["explain", "unknown-verb"]);
    assert_eq!(code, 0, "{text}");
    assert!(text.starts_with("unknown-verb (error)\n"), "{text}");
    assert!(
        text.contains("Verbs are in capitals"),
        "the summary: {text}"
    );
    assert!(
        text.contains("How to fix it: Correct the verb"),
        "the fix: {text}"
    );
    assert!(
        text.matches("```").count() >= 4,
        "an example and its fix: {text}"
    );
    assert!(text.contains("docs/DIAGNOSTICS.md#unknown-verb"), "{text}");
}

#[test]
fn explain_refuses_a_code_docent_lacks_and_names_the_nearest() {
    let (code, out, err) = run_docent(&["explain", "unknown-vreb"]);
    assert_eq!((code, out.as_str()), (1, ""));
    assert!(err.contains("Did you mean `unknown-verb`?"), "{err}");
    // Alone, it lists every code.
    let (code, out, _) = run_docent(&["explain"]);
    assert_eq!(code, 0);
    let listed = docent::content::DiagnosticCode::ALL
        .iter()
        .filter(|c| out.contains(&format!("  {:<32} ", c.as_str())))
        .count();
    assert_eq!(listed, docent::content::DiagnosticCode::ALL.len(), "{out}");
}
