//! The mistakes a new author makes following docs/GETTING-STARTED.md to the letter: its
//! `hello-museum` bundle, broken one slip at a time, and each slip told at the line (and
//! column) that causes it, with a hint a museum author can act on; not where YAML finally
//! stumbles over it. Here the acts file; files, pages and settings in `getting_started_files`.

use std::fs;
use std::path::Path;

use crate::common;

use common::check::{assert_plain, check_all, places};
use docent_content::{Diagnostic, LoadReport};

/// `acts.yaml` of the tutorial's step 2, as typed.
pub(crate) const ACTS: &str = "\
- Label: WELCOME
  Text:
    - Welcome to the museum!
    - Hello, and welcome!

- Label: OPENING_HOURS
  Text:
    - We are open every day from ten to six.
";

/// `pages/index.html` of step 3, as typed.
pub(crate) const HOME: &str = r#"<!DOCTYPE html>
<html lang="en">
<head>
  <meta charset="utf-8">
  <title>Welcome</title>
</head>
<body>
  <h1>Welcome!</h1>
  <button type="button" data-act="WELCOME">Say hello</button>
  <button type="button" data-act="OPENING_HOURS">When are you open?</button>
</body>
</html>
"#;

/// The tutorial's bundle with `files` written over it (path, contents) and `gone` removed.
pub(crate) fn hello_museum(files: &[(&str, &str)], gone: &[&str]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("temp dir");
    let root = dir.path();
    fs::create_dir_all(root.join("pages")).expect("pages");
    fs::create_dir_all(root.join("media")).expect("media");
    fs::write(root.join("acts.yaml"), ACTS).expect("acts");
    fs::write(root.join("pages/index.html"), HOME).expect("home");
    for (rel, contents) in files {
        let path = root.join(rel);
        fs::create_dir_all(path.parent().expect("parent")).expect("folders");
        fs::write(path, contents).expect("write");
    }
    for rel in gone {
        fs::remove_file(root.join(rel)).expect("remove");
    }
    dir
}

/// `ACTS` with line `number` (1-based) replaced by `with`.
fn acts_with_line(number: usize, with: &str) -> String {
    ACTS.lines()
        .enumerate()
        .map(|(i, line)| {
            if i + 1 == number {
                format!("{with}\n")
            } else {
                format!("{line}\n")
            }
        })
        .collect()
}

pub(crate) fn report_of(dir: &Path) -> LoadReport {
    let report = check_all(dir);
    assert_plain(&report);
    report
}

/// The one diagnostic of `report`, which must be `code` at `at`.
pub(crate) fn the_one<'r>(report: &'r LoadReport, code: &'static str, at: &str) -> &'r Diagnostic {
    assert_eq!(places(report), [(code, at.to_owned())]);
    &report.diagnostics[0]
}

pub(crate) fn says(diagnostic: &Diagnostic, words: &str) {
    assert!(diagnostic.message.contains(words), "{}", diagnostic.message);
}

#[test]
fn the_tutorial_bundle_as_typed_passes_without_a_word() {
    let dir = hello_museum(&[], &[]);
    assert!(report_of(dir.path()).diagnostics.is_empty());
}

#[test]
fn a_dash_glued_to_the_first_label_is_told_at_that_line_not_the_next() {
    let acts = acts_with_line(1, "-Label: WELCOME");
    let dir = hello_museum(&[("acts.yaml", &acts)], &[]);
    let report = report_of(dir.path());
    let told = the_one(&report, "yaml-syntax", "acts.yaml:1:1");
    says(told, "dash glued to `Label:`");
    says(told, "Put a space after the `-`: `- Label: WELCOME`.");
}

#[test]
fn a_dash_glued_to_a_later_label_is_told_at_that_label() {
    let acts = acts_with_line(6, "-Label: OPENING_HOURS");
    let dir = hello_museum(&[("acts.yaml", &acts)], &[]);
    let report = report_of(dir.path());
    // The page's `OPENING_HOURS` is not blamed on the page: the act is only unread.
    let told = the_one(&report, "yaml-syntax", "acts.yaml:6:1");
    says(told, "`- Label: OPENING_HOURS`");
}

#[test]
fn an_act_without_its_dash_is_told_at_its_label() {
    let acts = acts_with_line(6, "Label: OPENING_HOURS");
    let dir = hello_museum(&[("acts.yaml", &acts)], &[]);
    let report = report_of(dir.path());
    let told = the_one(&report, "yaml-syntax", "acts.yaml:6:1");
    says(told, "no `- ` in front of `Label:`");
    says(told, "`- Label: OPENING_HOURS`");
}

/// `ACTS` with a third alternative under `WELCOME`, so a text can lack its `- ` first, between
/// or last; its lines 3 to 5 are the alternatives.
fn three_alternatives(line: usize, with: &str) -> String {
    let acts = ACTS.replace(
        "    - Hello, and welcome!\n",
        "    - Hello, and welcome!\n    - Good day!\n",
    );
    acts.lines()
        .enumerate()
        .map(|(i, l)| {
            if i + 1 == line {
                format!("{with}\n")
            } else {
                format!("{l}\n")
            }
        })
        .collect()
}

#[test]
fn a_first_alternative_without_its_dash_is_told_at_its_own_line() {
    let acts = three_alternatives(3, "    Welcome to the museum!");
    let dir = hello_museum(&[("acts.yaml", &acts)], &[]);
    let report = report_of(dir.path());
    let told = the_one(&report, "joined-lines", "acts.yaml:3:5");
    assert!(told.is_error());
    says(
        told,
        "This line has no `- ` in front, but the lines below it start with `- `",
    );
    says(
        told,
        "\"Welcome to the museum! - Hello, and welcome! - Good day!\"",
    );
    says(told, "`- Welcome to the museum!`");
    assert!(!told.message.contains("lines above"), "{}", told.message);
}

#[test]
fn an_alternative_between_others_without_its_dash_is_told_at_its_own_line() {
    for (line, text) in [(4, "Hello, and welcome!"), (5, "Good day!")] {
        let acts = three_alternatives(line, &format!("    {text}"));
        let dir = hello_museum(&[("acts.yaml", &acts)], &[]);
        let report = report_of(dir.path());
        let told = the_one(&report, "yaml-syntax", &format!("acts.yaml:{line}:5"));
        says(told, "no `- ` in front, unlike the `- ` line above it");
        says(told, &format!("`- {text}`"));
    }
}

#[test]
fn a_first_text_written_after_text_colon_is_told_there() {
    let acts = three_alternatives(3, "").replacen("  Text:\n\n", "  Text: Welcome!\n", 1);
    let dir = hello_museum(&[("acts.yaml", &acts)], &[]);
    let report = report_of(dir.path());
    let told = the_one(&report, "joined-lines", "acts.yaml:2:9");
    says(told, "on the same line as `Text:`");
    says(told, "`- Welcome!`");
}

#[test]
fn a_first_alternative_with_a_glued_dash_is_one_slip_with_a_one_line_fix() {
    let acts = three_alternatives(3, "    -Welcome to the museum!");
    let dir = hello_museum(&[("acts.yaml", &acts)], &[]);
    let report = report_of(dir.path());
    let told = the_one(&report, "dash-without-space", "acts.yaml:3:5");
    says(
        told,
        "Put a space after the dash: `- Welcome to the museum!`.",
    );
}

#[test]
fn texts_under_a_label_without_their_text_line_are_told_where_text_belongs() {
    let acts = ACTS.replacen("  Text:\n", "", 1);
    let dir = hello_museum(&[("acts.yaml", &acts)], &[]);
    let report = report_of(dir.path());
    // The act is not also called empty, nor the page's `WELCOME` unknown.
    let told = the_one(&report, "joined-lines", "acts.yaml:2:5");
    assert!(told.is_error());
    says(
        told,
        "right under `Label: WELCOME`, with no `Text:` line between",
    );
    says(told, "Add a line `Text:` above it");
}

#[test]
fn a_list_that_lost_its_start_is_told_there_even_when_yaml_stumbles_lines_later() {
    // Step 7's quoted text with `: ` after a first alternative without its dash, or after a
    // forgotten `Text:` line: YAML stops at the quoted line, the slip is above it.
    let quoted = "    - \"Opening hours: ten to six, every day.\"";
    let no_dash = ACTS.replace(
        "    - We are open every day from ten to six.\n",
        &format!("    We are open every day.\n{quoted}\n"),
    );
    let dir = hello_museum(&[("acts.yaml", &no_dash)], &[]);
    let report = report_of(dir.path());
    let told = the_one(&report, "yaml-syntax", "acts.yaml:8:5");
    says(
        told,
        "This line has no `- ` in front, but the lines below it start with `- `",
    );
    says(told, "`- We are open every day.`");

    let no_text = ACTS.replace(
        "  Text:\n    - We are open every day from ten to six.\n",
        &format!("    - We are open every day.\n{quoted}\n"),
    );
    let dir = hello_museum(&[("acts.yaml", &no_text)], &[]);
    let report = report_of(dir.path());
    let told = the_one(&report, "yaml-syntax", "acts.yaml:7:5");
    says(
        told,
        "right under `Label: OPENING_HOURS`, with no `Text:` line between",
    );
}

#[test]
fn text_without_its_colon_is_told_to_get_one() {
    let acts = acts_with_line(2, "  Text");
    let dir = hello_museum(&[("acts.yaml", &acts)], &[]);
    let report = report_of(dir.path());
    let told = the_one(&report, "yaml-syntax", "acts.yaml:2:3");
    says(told, "`Text` has no colon after it");
    says(told, "Write `Text:`.");
}

#[test]
fn step_seven_fixed_with_an_editors_curly_quotes_is_told_to_straighten_them() {
    let acts = acts_with_line(8, "    - “Opening hours: ten to six, every day.”");
    let dir = hello_museum(&[("acts.yaml", &acts)], &[]);
    let report = report_of(dir.path());
    let told = the_one(&report, "bad-value", "acts.yaml:8:7");
    says(told, "its quotes are curly quotes");
    says(told, "`- \"Opening hours: ten to six, every day.\"`");
}
