//! Tests of reading a YAML file as a whole: the node budget, size and encoding limits, guessed
//! scalars, tabs, and recovery past broken items.

use super::*;

fn file() -> Arc<str> {
    Arc::from("acts.yaml")
}

fn parse_acts(text: &str) -> YamlFile {
    parse(
        &file(),
        text.as_bytes(),
        crate::DiagnosticCode::YamlSyntax,
        Recovery::SkipBrokenItems,
    )
}

fn codes(parsed: &YamlFile) -> Vec<(&'static str, u32, u32)> {
    parsed
        .diagnostics
        .iter()
        .map(|d| (d.code.as_str(), d.line, d.column))
        .collect()
}

#[test]
fn budget_admits_100_000_acts_in_one_file() {
    // Five nodes an act: twice serde-saphyr's default node budget.
    let text: String = (0..100_000)
        .map(|i| format!("- Label: A{i}\n  Text: hi\n"))
        .collect();
    let parsed = parse_acts(&text);
    assert!(parsed.diagnostics.is_empty(), "{:?}", parsed.diagnostics);
    let Some(Node {
        kind: Kind::Seq(items),
        ..
    }) = parsed.root
    else {
        panic!("expected a list")
    };
    assert_eq!(items.len(), 100_000);
    assert_eq!(items[99_999].pos.line, 199_999);
    let default_budget = serde_saphyr::from_str::<Spanned<raw::Raw>>(&text);
    assert!(
        default_budget.is_err(),
        "the default budget is too small for real bundles"
    );
}

#[test]
fn refuses_files_over_the_size_limit() {
    let parsed = parse_acts(&" ".repeat(MAX_FILE_BYTES + 1));
    assert_eq!(codes(&parsed), [("file-too-large", 1, 1)]);
    assert!(parsed.root.is_none());
}

#[test]
fn locates_bytes_that_are_not_utf8() {
    let parsed = parse(
        &file(),
        b"- Label: A\n  Text: caf\xe9\n",
        crate::DiagnosticCode::YamlSyntax,
        Recovery::SkipBrokenItems,
    );
    assert_eq!(codes(&parsed), [("file-encoding", 2, 12)]);
}

#[test]
fn guessed_scalars_keep_the_text_as_written() {
    let parsed = parse_acts("- [yes, 3.5, 0x1F, 010, .inf, ~, 'quoted', \"d: q\", plain]\n");
    let Some(Node {
        kind: Kind::Seq(items),
        ..
    }) = parsed.root
    else {
        panic!("expected a list")
    };
    let Kind::Seq(values) = &items[0].kind else {
        panic!("expected a nested list")
    };
    let shown: Vec<String> = values
        .iter()
        .map(|n| match &n.kind {
            Kind::Guessed(t) => format!("guessed {t}"),
            Kind::Str { value, verbatim_at } => format!("text {value} at {verbatim_at:?}"),
            Kind::Null => "null".to_owned(),
            _ => "other".to_owned(),
        })
        .collect();
    assert_eq!(
        shown,
        [
            "guessed yes",
            "guessed 3.5",
            "guessed 0x1F",
            "guessed 010",
            "guessed .inf",
            "null",
            "text quoted at Some(1)",
            "text d: q at Some(1)",
            "text plain at Some(0)",
        ]
    );
}

#[test]
fn a_tab_in_indentation_is_reported_at_the_tab_and_the_rest_still_parses() {
    let parsed = parse_acts("- Label: A\n  Text:\n  \t- x\n- Label: B\n");
    assert_eq!(codes(&parsed), [("yaml-tab", 3, 3)]);
    assert_eq!(parsed.skipped_lines, [(1, 4)]);
    let Some(Node {
        kind: Kind::Seq(items),
        ..
    }) = parsed.root
    else {
        panic!("expected a list")
    };
    assert_eq!(items.len(), 1);
}

#[test]
fn a_tab_yaml_accepts_is_only_a_warning() {
    let parsed = parse_acts("- Label: A\n  Text: |\n    line\n    \tindented text\n");
    assert_eq!(parsed.diagnostics.len(), 1);
    assert_eq!(parsed.diagnostics[0].severity, crate::Severity::Warning);
}

#[test]
fn every_broken_item_is_reported_and_skipped() {
    let text = "- Label: A\n  Text: \"open\n- Label: B\n  Text: fine\n\
                - Label: C\n  Text: [a, b\n- Label: D\n";
    let parsed = parse_acts(text);
    assert_eq!(
        codes(&parsed),
        [("yaml-syntax", 2, 9), ("yaml-syntax", 6, 9)]
    );
    assert_eq!(parsed.skipped_lines, [(1, 3), (5, 7)]);
    let Some(Node {
        kind: Kind::Seq(items),
        ..
    }) = parsed.root
    else {
        panic!("expected a list")
    };
    assert_eq!(items.len(), 2);
    assert_eq!(items[1].pos.line, 7);
}

#[test]
fn settings_are_not_partially_read() {
    let parsed = parse(
        &file(),
        b"home: [x\nspeech: {}\n",
        crate::DiagnosticCode::ConfigSyntax,
        Recovery::None,
    );
    assert!(parsed.root.is_none());
    assert_eq!(parsed.diagnostics.len(), 1);
    assert_eq!(parsed.diagnostics[0].code, "config-syntax");
}
