//! What `docent check` reports about the bundle as a whole (no acts, no home page, not a
//! bundle, an empty file) and about files it will not read: too large, or nested too deep.

use crate::common;

use std::fs;

use common::check::{assert_plain, bundle, check, places};

#[test]
fn bundle_level_problems_are_reported() {
    let empty = tempfile::tempdir().expect("temp dir");
    assert_eq!(
        places(&check(empty.path())),
        [
            ("no-acts", "acts.yaml:1:1".to_owned()),
            ("no-home-page", "pages/index.html:1:1".to_owned())
        ]
    );
    assert_eq!(
        places(&check(&empty.path().join("nope"))),
        [(
            "not-a-bundle",
            format!("{}:1:1", empty.path().join("nope").display())
        )]
    );
    let dir = bundle(&[
        ("acts.yaml", "# nothing yet\n"),
        ("more.yaml", "- Label: A\n  Text: Hi\n"),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("empty-file", "acts.yaml:1:1".to_owned())]
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
        [("file-too-large", "huge.yaml:1:1".to_owned())]
    );
}

#[test]
fn deeply_nested_yaml_is_refused_with_a_message_not_a_crash() {
    // Pasted or generated YAML can nest far deeper than acts ever do; the readers recurse,
    // so the check must give them the stack room to refuse it (this test runs on a small
    // debug thread stack, as `docent check` runs on the main thread).
    for depth in [70, 2_000] {
        let nested = format!("{}x{}", "[".repeat(depth), "]".repeat(depth));
        let acts = format!("- Label: A\n  Text: hi\n- Label: B\n  Text: {nested}\n");
        let dir = bundle(&[("acts.yaml", &acts)]);
        let report = check(dir.path());
        let (code, place) = places(&report).into_iter().next().expect("a problem");
        assert_eq!(code, "yaml-syntax", "{depth}: {:?}", report.diagnostics);
        assert!(place.starts_with("acts.yaml:4:"), "{depth}: {place}");
        let message = &report.diagnostics[0].message;
        assert!(message.contains("nested"), "{depth}: {message}");
        assert!(report.bundle.is_none());
        assert_plain(&report);
        // The settings file is read the same way.
        let settings = format!("contexts: {nested}\n");
        let dir = bundle(&[
            ("acts.yaml", "- Label: A\n  Text: hi\n"),
            ("docent.yaml", &settings),
        ]);
        let report = check(dir.path());
        let (code, place) = places(&report).into_iter().next().expect("a problem");
        assert_eq!(code, "config-syntax", "{depth}: {:?}", report.diagnostics);
        assert!(place.starts_with("docent.yaml:1:"), "{depth}: {place}");
        assert_plain(&report);
    }
}
