//! What `docent check` reports about acts files as YAML: syntax, keys, act shapes, labels,
//! contexts and guessed values, every diagnostic at its exact file, line and column, with
//! plain-language messages (every code's row and entry in `docs/DIAGNOSTICS.md`:
//! `diagnostics_reference.rs`). Commands: `content_commands.rs`; the bundle as a whole and files too
//! large or deep: `content_bundle.rs`; paths, pages and settings: `content_paths.rs`.

use crate::common;

use common::check::{assert_plain, bundle, check, only, places, yaml};
use docent_content::Severity;

#[test]
fn yaml_errors_are_reworded_located_and_do_not_hide_other_acts_or_files() {
    let acts = yaml(&[
        "- Label: A",
        "  Text: Note: broken",
        "- Label: B",
        "  Text: \"unclosed",
        "- Label: C",
        "  Text: fine",
        "  Cmds: say hi",
    ]);
    let dir = bundle(&[
        ("a.yaml", &acts),
        ("b.yaml", "- Label: D\n  Cmds: [DRIVE_STOP now]\n"),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("yaml-syntax", "a.yaml:2:13".to_owned()),
            ("yaml-syntax", "a.yaml:4:9".to_owned()),
            ("unknown-verb", "a.yaml:7:9".to_owned()),
            ("bad-argument", "b.yaml:2:21".to_owned()),
        ]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("put the whole text in quotes")
    );
    assert!(report.diagnostics[1].message.contains("never closed"));
    assert!(report.bundle.is_none());
    assert_plain(&report);
}

#[test]
fn a_tab_in_indentation_is_reported_at_the_tab() {
    let dir = bundle(&[(
        "acts.yaml",
        "- Label: A\n  Text:\n  \t- hello\n- Label: B\n  Text: hi\n",
    )]);
    let report = check(dir.path());
    assert_eq!(places(&report), [("yaml-tab", "acts.yaml:3:3".to_owned())]);
    assert_eq!(report.diagnostics[0].severity, Severity::Error);
}

#[test]
fn key_problems_are_reported_at_the_key_with_suggestions() {
    let acts = yaml(&[
        "- Label: A",
        "  Lable: x",
        "  label: y",
        "  Commands: [SAY hi]",
        "  textGroup: hey",
        "  Text: one",
        "  Text: two",
    ]);
    let dir = bundle(&[("acts.yaml", &acts)]);
    let report = check(dir.path());
    let found: Vec<(&str, u32, u32)> = report
        .diagnostics
        .iter()
        .map(|d| (d.code.as_str(), d.line, d.column))
        .collect();
    assert_eq!(
        found,
        [
            ("unknown-key", 2, 3),
            ("unknown-key", 3, 3),
            ("unknown-key", 4, 3),
            ("unknown-key", 5, 3),
            ("duplicate-key", 7, 3),
        ]
    );
    let messages: Vec<&str> = report
        .diagnostics
        .iter()
        .map(|d| d.message.as_str())
        .collect();
    assert!(messages[0].contains("Did you mean `Label`?"));
    assert!(messages[1].contains("Did you mean `Label`?"));
    assert!(messages[2].contains("Did you mean `Cmds`?"));
    assert!(messages[3].contains("Did you mean `TextGroup`?"));
    assert!(messages[4].contains("line 6"));
}

#[test]
fn act_shape_problems_are_each_reported() {
    let acts = yaml(&[
        "- Text: no label",
        "- Label: \"\"",
        "- Label: EMPTY_TEXT",
        "  Text:",
        "    - ~",
        "    -",
        "    - \"  \"",
        "- Label: NOTHING",
        "- just a string",
        "- Label: COLON",
        "  Text:",
        "    - Note: this is splendid",
        "- Label: NO_TEXT",
        "  Text: []",
        "  TextGroup:",
        "  Cmds: [WAIT]",
    ]);
    let dir = bundle(&[("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("missing-label", "acts.yaml:1:3".to_owned()),
            ("empty-label", "acts.yaml:2:10".to_owned()),
            ("empty-text", "acts.yaml:5:7".to_owned()),
            ("empty-text", "acts.yaml:6:6".to_owned()),
            ("empty-text", "acts.yaml:7:7".to_owned()),
            ("empty-act", "acts.yaml:8:3".to_owned()),
            ("not-a-list", "acts.yaml:9:3".to_owned()),
            ("bad-value", "acts.yaml:12:7".to_owned()),
            ("empty-text", "acts.yaml:14:9".to_owned()),
            ("empty-text", "acts.yaml:15:12".to_owned()),
        ]
    );
    assert_eq!(only(&report, "empty-act")[0].severity, Severity::Warning);
    assert!(
        only(&report, "bad-value")[0]
            .message
            .contains("\"Note: this is splendid\"")
    );
    assert_plain(&report);
}

#[test]
fn a_file_that_is_not_a_list_is_explained() {
    let dir = bundle(&[("acts.yaml", "Label: WELCOME\nText: Hello\n")]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("not-a-list", "acts.yaml:1:1".to_owned())]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("Start each act with a dash")
    );
}

#[test]
fn duplicate_labels_are_reported_at_both_places_naming_each_other() {
    let dir = bundle(&[
        ("a.yaml", "- Label: OK\n  Text: OK!\n"),
        (
            "b.yaml",
            "# more\n- Label: HI\n  Text: Hi\n- Label: OK\n  Text: Fine\n",
        ),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("duplicate-label", "a.yaml:1:10".to_owned()),
            ("duplicate-label", "b.yaml:4:10".to_owned())
        ]
    );
    assert!(
        report.diagnostics[0].message.contains("b.yaml:4"),
        "{}",
        report.diagnostics[0]
    );
    assert!(
        report.diagnostics[1].message.contains("a.yaml:1"),
        "{}",
        report.diagnostics[1]
    );
}

#[test]
fn declared_contexts_are_enforced() {
    let acts = yaml(&[
        "- Label: A",
        "  Text: Hi",
        "  TextGrup: Hi all",
        "  TextChild: Hi kid",
        "  TextFormally: Good day",
    ]);
    let dir = bundle(&[
        ("docent.yaml", "contexts: [TextGroup, TextChild]\n"),
        ("acts.yaml", &acts),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("unknown-context", "acts.yaml:3:3".to_owned()),
            ("unknown-context", "acts.yaml:5:3".to_owned())
        ]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("Did you mean `TextGroup`?")
    );
}

#[test]
fn unquoted_values_are_kept_as_written_with_a_warning() {
    let dir = bundle(&[(
        "acts.yaml",
        "- Label: A\n  Text:\n    - yes\n    - 3.5\n    - \"no\"\n",
    )]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("unquoted-scalar", "acts.yaml:3:7".to_owned()),
            ("unquoted-scalar", "acts.yaml:4:7".to_owned())
        ]
    );
    let bundle = report.bundle.expect("warnings do not stop loading");
    let texts: Vec<&str> = bundle.acts[0].variants[0]
        .alternatives
        .iter()
        .map(|a| a.value.as_str())
        .collect();
    assert_eq!(texts, ["yes", "3.5", "no"]);
}

#[test]
fn an_act_with_variants_but_no_default_text_is_warned_about() {
    let b = common::check::bundle(&[("acts.yaml", "- Label: KIDS\n  TextChild: [Hi kids]\n")]);
    let report = docent_content::load_bundle(b.path());
    assert!(report.bundle.is_some(), "a warning, not an error");
    let d = only(&report, "no-default-text");
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!((d[0].line, d[0].column), (2, 3));
}
