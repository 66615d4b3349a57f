//! What `docent check` reports: every diagnostic code at its exact file, line and column,
//! with plain-language messages, and the path gate shared with the HTTP file routes.

mod common;

use std::fs;
use std::path::Path;

use docent::content::{
    BundleArea, Diagnostic, LoadReport, PathError, Severity, load_bundle, resolve_in_bundle,
};

/// Lines joined into a file, one element a line: line numbers in assertions are indexes + 1.
fn yaml(lines: &[&str]) -> String {
    lines.iter().map(|l| format!("{l}\n")).collect()
}

/// A bundle in a temporary folder: `pages/index.html`, an empty `media/`, and `files`.
fn bundle(files: &[(&str, &str)]) -> tempfile::TempDir {
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

fn check(dir: &Path) -> LoadReport {
    load_bundle(dir)
}

/// (code, file:line:column) of every diagnostic.
fn places(report: &LoadReport) -> Vec<(&'static str, String)> {
    report
        .diagnostics
        .iter()
        .map(|d| (d.code, format!("{}:{}:{}", d.file, d.line, d.column)))
        .collect()
}

fn only<'r>(report: &'r LoadReport, code: &str) -> Vec<&'r Diagnostic> {
    report
        .diagnostics
        .iter()
        .filter(|d| d.code == code)
        .collect()
}

/// Messages are for museum staff: no Rust or parser vocabulary.
fn assert_plain(report: &LoadReport) {
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
        ] {
            assert!(!d.message.contains(jargon), "{d} uses `{jargon}`");
        }
    }
}

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
        .map(|d| (d.code, d.line, d.column))
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
fn verbs_and_arguments_are_checked() {
    let acts = yaml(&[
        "- Label: A",
        "  Cmds:",
        "    - say Hello",
        "    - SAY",
        "    - DRIVE_START fast",
        "    - SET_WAYPOINT 1",
        "    - SET_WAYPOINT 1 2 3 4",
        "    - SET_WAYPOINT x 2",
        "    - WAIT abc",
        "    - WAIT 1.5s",
        "    - WAIT",
        "    - \"SET_WAYPOINT 1 two\"",
        "    - PROJECT",
        "    - HONK",
    ]);
    let dir = bundle(&[("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("unknown-verb", "acts.yaml:3:7".to_owned()),
            ("bad-argument", "acts.yaml:4:7".to_owned()),
            ("bad-argument", "acts.yaml:5:19".to_owned()),
            ("bad-argument", "acts.yaml:6:20".to_owned()),
            ("bad-argument", "acts.yaml:7:20".to_owned()),
            ("bad-argument", "acts.yaml:8:20".to_owned()),
            ("bad-argument", "acts.yaml:9:12".to_owned()),
            ("bad-argument", "acts.yaml:12:23".to_owned()),
            ("bad-argument", "acts.yaml:13:7".to_owned()),
            ("unknown-verb", "acts.yaml:14:7".to_owned()),
        ]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("Did you mean `SAY`?")
    );
    assert!(
        report.diagnostics[9]
            .message
            .contains("Known commands: SAY, PROJECT")
    );
    assert_plain(&report);
}

#[test]
fn highlight_areas_are_checked_number_by_number() {
    let acts = yaml(&[
        "- Label: A",
        "  Cmds:",
        "    - HIGHLIGHT 0.10 0.20 0.35 0.25",
        "    - HIGHLIGHT 0.1 0.1 0.2 0.2; 0.5 0.5 0.3 0.3 ellipse",
        "    - HIGHLIGHT",
        "    - HIGHLIGHT 0.10 0.20 1.35 0.25",
        "    - HIGHLIGHT 0.8 0.2 0.3 0.25",
        "    - HIGHLIGHT 0.1 0.2 0.3",
        "    - HIGHLIGHT 0 0 1 1; 0.5 half 0.1 0.1",
        "    - \"HIGHLIGHT 0.1 0.2 0.3 0.4 circle\"",
        "    - HIGHLIGHT 0.1 0.2 0.3 0.4;",
    ]);
    let dir = bundle(&[("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("bad-argument", "acts.yaml:6:27".to_owned()),
            ("bad-argument", "acts.yaml:7:25".to_owned()),
            ("bad-argument", "acts.yaml:8:17".to_owned()),
            ("bad-argument", "acts.yaml:9:30".to_owned()),
            ("bad-argument", "acts.yaml:10:34".to_owned()),
            ("bad-argument", "acts.yaml:11:32".to_owned()),
        ]
    );
    let messages: Vec<&str> = report
        .diagnostics
        .iter()
        .map(|d| d.message.as_str())
        .collect();
    assert!(
        messages[0].contains("The width `1.35` must be a fraction"),
        "{}",
        messages[0]
    );
    assert!(
        messages[1].contains("past the right edge"),
        "{}",
        messages[1]
    );
    assert!(messages[2].contains("Found 3 value(s)"), "{}", messages[2]);
    assert!(
        messages[3].contains("`half` is not a number"),
        "{}",
        messages[3]
    );
    assert!(
        messages[4].contains("`circle` is not a shape"),
        "{}",
        messages[4]
    );
    assert!(messages[5].contains("no area between"), "{}", messages[5]);
    assert_plain(&report);
}

#[test]
fn site_verbs_follow_their_argument_rule_and_waypoints_their_bounds() {
    let config = yaml(&[
        "drive:",
        "  bounds: { min_x: 0, min_y: 0, max_x: 20, max_y: 12 }",
        "verbs:",
        "  LIGHTS:",
        "    argument: required",
        "  BELL:",
        "    argument: none",
        "  FOG:",
    ]);
    let acts = yaml(&[
        "- Label: A",
        "  Cmds:",
        "    - LIGHTS",
        "    - LIGHTS on",
        "    - BELL now",
        "    - BELL",
        "    - FOG",
        "    - FOG thick",
        "    - SET_WAYPOINT 25 3",
        "    - SET_WAYPOINT 20 12 90",
        "    - lights on",
    ]);
    let dir = bundle(&[("docent.yaml", &config), ("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("bad-argument", "acts.yaml:3:7".to_owned()),
            ("bad-argument", "acts.yaml:5:12".to_owned()),
            ("waypoint-out-of-bounds", "acts.yaml:9:20".to_owned()),
            ("unknown-verb", "acts.yaml:11:7".to_owned()),
        ]
    );
    assert!(
        report.diagnostics[3]
            .message
            .contains("Did you mean `LIGHTS`?")
    );
}

#[test]
fn file_arguments_are_checked_through_the_bundle_gate() {
    let acts = yaml(&[
        "- Label: A",
        "  Cmds:",
        "    - DISPLAY_PAGE ../secret.html",
        "    - DISPLAY_PAGE /etc/passwd",
        "    - DISPLAY_PAGE welcome/WELCOME.html",
        "    - DISPLAY_PAGE Welcome/Welcom.html",
        "    - DISPLAY_PAGE Welcome",
        "    - PROJECT clip.avi",
        "    - PROJECT film.mpg",
        "    - PROJECT %2e%2e/secret.webm",
        "    - DISPLAY_PAGE Welcome/Welcome.html",
    ]);
    let dir = bundle(&[
        ("acts.yaml", &acts),
        ("pages/Welcome/Welcome.html", "<p>hi</p>"),
        ("media/film.mpg", "x"),
        ("secret.webm", "x"),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("path-outside-bundle", "acts.yaml:3:20".to_owned()),
            ("path-outside-bundle", "acts.yaml:4:20".to_owned()),
            ("miscased-file", "acts.yaml:5:20".to_owned()),
            ("missing-file", "acts.yaml:6:20".to_owned()),
            ("missing-file", "acts.yaml:7:20".to_owned()),
            ("missing-file", "acts.yaml:8:15".to_owned()),
            ("media-format", "acts.yaml:8:15".to_owned()),
            ("media-format", "acts.yaml:9:15".to_owned()),
            ("missing-file", "acts.yaml:10:15".to_owned()),
        ]
    );
    let messages: Vec<&str> = report
        .diagnostics
        .iter()
        .map(|d| d.message.as_str())
        .collect();
    assert!(
        messages[2].contains("`Welcome/Welcome.html`"),
        "{}",
        messages[2]
    );
    assert!(
        messages[3].contains("Did you mean `Welcome/Welcome.html`?"),
        "{}",
        messages[3]
    );
    assert!(messages[4].contains("is a folder"), "{}", messages[4]);
    assert!(messages[7].contains("WebM"), "{}", messages[7]);
    assert_eq!(only(&report, "media-format")[0].severity, Severity::Warning);
}

#[cfg(unix)]
#[test]
fn a_symlink_leading_out_of_the_bundle_is_refused() {
    let outside = tempfile::tempdir().expect("outside dir");
    fs::write(outside.path().join("secret.html"), "secret").expect("secret");
    let acts = yaml(&[
        "- Label: A",
        "  Cmds:",
        "    - DISPLAY_PAGE escape.html",
        "    - DISPLAY_PAGE inside.html",
        "    - DISPLAY_PAGE out/secret.html",
    ]);
    let dir = bundle(&[("acts.yaml", &acts)]);
    let pages = dir.path().join("pages");
    std::os::unix::fs::symlink(
        outside.path().join("secret.html"),
        pages.join("escape.html"),
    )
    .expect("file link");
    std::os::unix::fs::symlink(pages.join("index.html"), pages.join("inside.html"))
        .expect("inside link");
    std::os::unix::fs::symlink(outside.path(), pages.join("out")).expect("folder link");
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("path-outside-bundle", "acts.yaml:3:20".to_owned()),
            ("path-outside-bundle", "acts.yaml:5:20".to_owned())
        ]
    );
    let root = dir.path().canonicalize().expect("root");
    assert_eq!(
        resolve_in_bundle(&root, BundleArea::Pages, "escape.html"),
        Err(PathError::Outside)
    );
    assert_eq!(
        resolve_in_bundle(&root, BundleArea::Pages, "out/secret.html"),
        Err(PathError::Outside)
    );
    assert_eq!(
        resolve_in_bundle(&root, BundleArea::Pages, "inside.html"),
        Ok(root.join("pages/index.html"))
    );
}

#[test]
fn the_path_gate_refuses_everything_but_exact_files_inside_the_area() {
    let dir = bundle(&[
        ("pages/Welcome/Welcome.html", "hi"),
        ("media/Exhibit/video.webm", "v"),
        ("top.html", "t"),
    ]);
    let root = dir.path().canonicalize().expect("root");
    let gate = |area, rel: &str| resolve_in_bundle(&root, area, rel);
    assert_eq!(
        gate(BundleArea::Pages, "Welcome/Welcome.html"),
        Ok(root.join("pages/Welcome/Welcome.html"))
    );
    assert_eq!(
        gate(BundleArea::Media, "Exhibit/video.webm"),
        Ok(root.join("media/Exhibit/video.webm"))
    );
    for rel in [
        "",
        "../top.html",
        "Welcome/../../top.html",
        "/etc/passwd",
        "./index.html",
        "C:/x.html",
        "a\\b",
        "x\0",
        "Welcome//Welcome.html",
    ] {
        assert_eq!(
            gate(BundleArea::Pages, rel),
            Err(PathError::Outside),
            "{rel:?}"
        );
    }
    // The HTTP layer decodes first; a name still encoded is just a name that does not exist.
    assert_eq!(
        gate(BundleArea::Pages, "%2e%2e/top.html"),
        Err(PathError::NotFound)
    );
    assert_eq!(
        gate(BundleArea::Pages, "Welcome/welcome.html"),
        Err(PathError::Miscased {
            actual: "Welcome/Welcome.html".into()
        })
    );
    assert_eq!(
        gate(BundleArea::Pages, "WELCOME/Welcome.html"),
        Err(PathError::Miscased {
            actual: "Welcome/Welcome.html".into()
        })
    );
    assert_eq!(gate(BundleArea::Pages, "Welcome"), Err(PathError::NotAFile));
    assert_eq!(
        gate(BundleArea::Media, "Welcome/Welcome.html"),
        Err(PathError::NotFound)
    );
}

#[test]
fn page_labels_are_checked_at_the_attribute_value() {
    let page = yaml(&[
        "<!doctype html>",
        "<button data-act=\"WELCOM\">a</button>",
        "<a data-act='OK' href=x>b</a>",
        "<div data-act=GONE></div>",
        "<!-- <b data-act=\"OLD\"> -->",
    ]);
    let dir = bundle(&[
        (
            "acts.yaml",
            "- Label: WELCOME\n  Text: Hello\n- Label: OK\n  Text: OK!\n",
        ),
        ("pages/index.html", &page),
        (
            "pages/old/legacy.htm",
            "<p>\n  <span data-act=\"OKAY\">x</span>",
        ),
        ("pages/notes.txt", "data-act=\"NOT_HTML\""),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("unknown-act", "pages/index.html:2:19".to_owned()),
            ("unknown-act", "pages/index.html:4:15".to_owned()),
            ("unknown-act", "pages/old/legacy.htm:2:19".to_owned()),
        ]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("Did you mean `WELCOME`?")
    );
    assert!(!report.diagnostics[1].message.contains("Did you mean"));
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
fn a_missing_home_page_is_a_warning_unless_it_was_chosen() {
    let acts = ("acts.yaml", "- Label: A\n  Text: Hi\n");
    let dir = bundle(&[acts]);
    fs::remove_file(dir.path().join("pages/index.html")).expect("remove home");
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("no-home-page", "pages/index.html:0:0".to_owned())]
    );
    assert_eq!(report.diagnostics[0].severity, Severity::Warning);
    assert!(report.bundle.is_some());

    let dir = bundle(&[acts, ("docent.yaml", "home: start.html\n")]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("no-home-page", "docent.yaml:1:7".to_owned())]
    );
    assert_eq!(report.diagnostics[0].severity, Severity::Error);
    assert!(report.bundle.is_none());

    let dir = bundle(&[acts, ("docent.yaml", "home: ../outside.html\n")]);
    assert_eq!(
        places(&check(dir.path())),
        [("path-outside-bundle", "docent.yaml:1:7".to_owned())]
    );
    let dir = bundle(&[acts, ("docent.yaml", "home: INDEX.html\n")]);
    assert_eq!(
        places(&check(dir.path())),
        [("miscased-file", "docent.yaml:1:7".to_owned())]
    );
}

#[test]
fn settings_problems_are_located() {
    let config = yaml(&["hoem: index.html", "speech:", "  rate: fast"]);
    let dir = bundle(&[
        ("docent.yaml", &config),
        ("acts.yaml", "- Label: A\n  Text: Hi\n"),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("config-unknown-key", "docent.yaml:1:1".to_owned()),
            ("config-bad-value", "docent.yaml:3:9".to_owned())
        ]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("Did you mean `home`?")
    );

    let dir = bundle(&[
        ("docent.yaml", "speech: [espeak\n"),
        ("acts.yaml", "- Label: A\n  Cmds: [say hi]\n"),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("unknown-verb", "acts.yaml:2:10".to_owned()),
            ("config-syntax", "docent.yaml:1:9".to_owned())
        ]
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
fn bundle_level_problems_are_reported() {
    let empty = tempfile::tempdir().expect("temp dir");
    assert_eq!(
        places(&check(empty.path())),
        [
            ("no-acts", ".:0:0".to_owned()),
            ("no-home-page", "pages/index.html:0:0".to_owned())
        ]
    );
    assert_eq!(
        places(&check(&empty.path().join("nope"))),
        [("not-a-bundle", ".:0:0".to_owned())]
    );
    let dir = bundle(&[
        ("acts.yaml", "# nothing yet\n"),
        ("more.yaml", "- Label: A\n  Text: Hi\n"),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("empty-file", "acts.yaml:0:0".to_owned())]
    );
    assert!(report.bundle.is_some());
}

#[test]
fn an_oversized_acts_file_is_refused_without_reading_it_whole() {
    let dir = bundle(&[("small.yaml", "- Label: A\n  Text: Hi\n")]);
    let big = fs::File::create(dir.path().join("huge.yaml")).expect("create");
    big.set_len(64 * 1024 * 1024).expect("sparse file");
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("file-too-large", "huge.yaml:0:0".to_owned())]
    );
}

#[test]
fn an_act_with_variants_but_no_default_text_is_warned_about() {
    let b = common::TempBundle::new("- Label: KIDS\n  TextChild: [Hi kids]\n");
    let report = docent::content::load_bundle(b.path());
    assert!(report.bundle.is_some(), "a warning, not an error");
    let d = &report.diagnostics;
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!(
        (d[0].code, d[0].line, d[0].column),
        ("no-default-text", 2, 3)
    );
}
