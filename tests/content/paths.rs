//! What `docent check` reports about files, pages and settings, and the path gate it shares
//! with the HTTP file routes: no path leaves the bundle, file names match exactly.

use crate::common;

use std::fs;

use common::check::{bundle, check, places, yaml};
use docent_content::{BundleArea, PathError, Severity, resolve_in_bundle};

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
            ("media-unrecognised", "acts.yaml:9:15".to_owned()),
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
    assert!(
        messages[6].contains("`media/film.mpg` is named as an MPEG-1/2 video"),
        "{}",
        messages[6]
    );
    assert!(report.conversions.is_empty(), "never handed to ffmpeg");
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
        "<a data-act='OK' href=#x>b</a>",
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
fn a_missing_home_page_is_a_warning_unless_it_was_chosen() {
    let acts = ("acts.yaml", "- Label: A\n  Text: Hi\n");
    let dir = bundle(&[acts]);
    fs::remove_file(dir.path().join("pages/index.html")).expect("remove home");
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("no-home-page", "pages/index.html:1:1".to_owned())]
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
