//! What `docent check` reports about touchscreen pages: one broken page per check, with the
//! exact code, file, line and column; and the legal variants that must pass.

use crate::common;

use common::check::{bundle, check, loaded, only, places, yaml};
use docent_content::Severity;

const ACTS: &str = "- Label: WELCOME\n  Text: Hello\n- Label: MAP\n  Text: The map\n\
                    - Label: SLIDE\n  Text: Next\n- Label: SECRET\n  Text: Psst\n";

const PNG: &[u8] = b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR";
const WEBM: &[u8] = b"\x1a\x45\xdf\xa3\x9f\x42\x86\x81\x01\x42\x82\x84webm";

/// Writes binary files (pictures, videos) into a bundle.
fn write_bytes(dir: &tempfile::TempDir, files: &[(&str, &[u8])]) {
    for (rel, bytes) in files {
        let path = dir.path().join(rel);
        std::fs::create_dir_all(path.parent().expect("parent")).expect("folders");
        std::fs::write(path, bytes).expect("write file");
    }
}

fn page_report(page: &str) -> docent_content::LoadReport {
    let dir = bundle(&[("acts.yaml", ACTS), ("pages/start.html", page)]);
    check(dir.path())
}

#[test]
fn an_unclosed_comment_hiding_buttons_is_reported_at_its_start() {
    let page = yaml(&[
        "<!doctype html><meta charset=utf-8>",
        "<p>Welcome</p>  <!-- old button",
        "<button data-act=\"WELCOME\">Hi</button>",
        "<button data-act=\"MAP\">Map</button>",
    ]);
    let report = page_report(&page);
    assert_eq!(
        places(&report),
        [("page-hidden-content", "pages/start.html:2:17".to_owned())]
    );
    let message = &report.diagnostics[0].message;
    assert!(message.contains("lines 2 to 5"), "{message}");
    assert!(message.contains("2 `data-act` buttons"), "{message}");
}

#[test]
fn unclosed_script_style_title_and_template_are_reported_at_the_opening_tag() {
    for (tag, close) in [
        ("script", "let a = 1;"),
        ("style", "p { color: red }"),
        ("title", "Home"),
        ("textarea", "x"),
        ("template", "<p>x</p>"),
    ] {
        let page = format!(
            "<meta charset=utf-8>\n  <{tag}>{close}\n<button data-act=\"WELCOME\">Hi</button>\n"
        );
        let report = page_report(&page);
        assert_eq!(
            places(&report),
            [("page-hidden-content", "pages/start.html:2:3".to_owned())],
            "{tag}"
        );
        assert!(report.diagnostics[0].message.contains(&format!("</{tag}>")));
    }
}

#[test]
fn broken_data_act_quoting_is_reported_at_the_value() {
    let page = yaml(&[
        "<meta charset=utf-8>",
        "<button data-act=MAP\">Map</button>",
        "<button data-act=“SLIDE”>Next</button>",
        "<button data-act=\"WELCOME>Hi</button>",
        "<button data-act=\"SECRET\">ok</button>",
    ]);
    let report = page_report(&page);
    assert_eq!(
        places(&report),
        [
            ("act-quoting", "pages/start.html:2:18".to_owned()),
            ("act-quoting", "pages/start.html:3:18".to_owned()),
            ("act-quoting", "pages/start.html:4:19".to_owned()),
        ]
    );
    assert!(report.diagnostics[0].message.contains("data-act=\"MAP\""));
    assert!(report.diagnostics[1].message.contains("curly quotes"));
    assert!(
        report.diagnostics[2]
            .message
            .contains("data-act=\"WELCOME\"")
    );
}

#[test]
fn an_unknown_data_act_label_gets_a_suggestion() {
    let report = page_report("<meta charset=utf-8>\n<b data-act=\"WELLCOME\">x</b>\n");
    assert_eq!(
        places(&report),
        [("unknown-act", "pages/start.html:2:14".to_owned())]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("Did you mean `WELCOME`?")
    );
}

#[test]
fn links_to_missing_or_miscased_files_are_reported_at_the_link() {
    let page = yaml(&[
        "<meta charset=utf-8><link rel=stylesheet href=\"style.css\">",
        "<img src=\"images/Map.png\" alt=\"\">",
        "<img srcset=\"images/map.png 1x, images/map@2x.png 2x\" alt=\"\">",
        "<video poster=\"poster.png\" src=\"../media/clip.webm\"></video>",
        "<div style=\"background: url('images/bg.png')\"></div>",
        "<style>body { background: url(images/paper.png) }</style>",
        "<a href=\"../../secret.html\">x</a> <img src=\"C:\\Users\\ana\\map.png\">",
    ]);
    let dir = bundle(&[
        ("acts.yaml", ACTS),
        ("pages/start.html", &page),
        (
            "pages/style.css",
            "h1 {\n  background: url(\"images/missing.png\");\n}\n",
        ),
    ]);
    write_bytes(
        &dir,
        &[("pages/images/map.png", PNG), ("media/clip.webm", WEBM)],
    );
    let report = check(dir.path());
    let broken: Vec<String> = only(&report, "broken-link")
        .iter()
        .map(|d| format!("{}:{}:{}", d.file, d.line, d.column))
        .collect();
    assert_eq!(
        broken,
        [
            "pages/start.html:2:11",
            "pages/start.html:3:33",
            "pages/start.html:4:16",
            "pages/start.html:5:30",
            "pages/start.html:6:31",
            "pages/start.html:7:10",
            "pages/start.html:7:45",
            "pages/style.css:2:20",
        ]
    );
    let messages: Vec<&str> = only(&report, "broken-link")
        .iter()
        .map(|d| d.message.as_str())
        .collect();
    assert!(messages[0].contains("`images/map.png`"), "{}", messages[0]);
    assert!(messages[1].contains("Did you mean"), "{}", messages[1]);
    assert!(messages[5].contains("`/secret.html`"), "{}", messages[5]);
    assert!(messages[6].contains("own computer"), "{}", messages[6]);
}

#[test]
fn a_link_to_the_internet_is_a_dead_button_in_the_kiosk() {
    let report = page_report("<meta charset=utf-8>\n<a href=\"https://example.org\">More</a>\n");
    assert_eq!(
        places(&report),
        [("external-link", "pages/start.html:2:10".to_owned())]
    );
    assert_eq!(report.diagnostics[0].severity, Severity::Warning);
}

#[test]
fn legal_variants_pass() {
    // A byte-order mark, Windows line ends, spaces as %20, srcset descriptors, query strings
    // and fragments, absolute /pages/ and /media/ forms, and links that are not files.
    let page = [
        "\u{feff}<!doctype html>\r",
        "<meta charset=\"UTF-8\">\r",
        "<title>Öffnungszeiten</title><!-- a closed comment -->\r",
        "<img src=\"images/Opening%20Hours.png?v=2#top\" srcset=\"images/Opening%20Hours.png 1x, \
         /pages/images/Opening%20Hours.png 2x\" alt=\"\">\r",
        "<video src=\"/media/clip.webm\" poster=\"../media/still.png\"></video>\r",
        "<a href=\"#top\">top</a> <a href=\"mailto:a@b.org\">mail</a> <a href=\"tel:123\">t</a>\r",
        "<img src=\"data:image/png;base64,iVBOR\"> <a href=\"javascript:void(0)\">x</a>\r",
        "<a href=\"other.html\">other</a> <button data-act='WELCOME' data-act-after=\" 1.5s\">Hi</button>\r",
        "<script>document.querySelector('[data-act=\"X\"]'); docent.trigger(\"WELCOME\");</script>\r",
    ]
    .join("\n");
    let dir = bundle(&[
        ("acts.yaml", ACTS),
        ("pages/start.html", &page),
        ("pages/other.html", "<meta charset=utf-8><p>hi</p>"),
    ]);
    write_bytes(
        &dir,
        &[
            ("pages/images/Opening Hours.png", PNG),
            ("media/clip.webm", WEBM),
            ("media/still.png", PNG),
        ],
    );
    let report = check(dir.path());
    assert!(report.diagnostics.is_empty(), "{:?}", report.diagnostics);
    assert_eq!(loaded(report).page_acts, ["WELCOME"]);
}

#[test]
fn a_windows_1252_page_is_reported_at_its_first_letter_that_is_not_utf8() {
    let dir = bundle(&[("acts.yaml", ACTS)]);
    std::fs::write(
        dir.path().join("pages/start.html"),
        b"<meta charset=utf-8>\r\n<h1>  \xd6ffnungszeiten</h1>\r\n",
    )
    .expect("page");
    std::fs::write(dir.path().join("pages/utf16.html"), b"\xff\xfe<\0p\0>\0").expect("page");
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("page-encoding", "pages/start.html:2:7".to_owned()),
            ("page-encoding", "pages/utf16.html:1:1".to_owned()),
        ]
    );
    assert!(report.diagnostics[0].message.contains("probably `Ö`"));
    assert!(
        report.diagnostics[0]
            .message
            .contains("with the encoding UTF-8")
    );
    assert!(report.diagnostics[1].message.contains("UTF-16"));
}

#[test]
fn a_page_declaring_another_charset_or_none_is_reported() {
    let page = yaml(&[
        "<meta charset=\"windows-1252\">",
        "<meta http-equiv=\"Content-Type\" content=\"text/html; charset=iso-8859-1\">",
    ]);
    let report = page_report(&page);
    assert_eq!(
        places(&report),
        [
            ("page-charset", "pages/start.html:1:16".to_owned()),
            ("page-charset", "pages/start.html:2:61".to_owned()),
        ]
    );
    let report = page_report("<h1>Café</h1>\n");
    assert_eq!(
        places(&report),
        [("page-charset", "pages/start.html:1:1".to_owned())]
    );
    assert_eq!(report.diagnostics[0].severity, Severity::Warning);
}

#[test]
fn delays_the_page_script_cannot_read_are_reported() {
    let page = yaml(&[
        "<meta charset=utf-8>",
        "<div data-act=\"SLIDE\" data-act-after=\"20 sec\"></div>",
        "<div data-act-after=\"20s\"></div>",
        "<div data-act=\"SLIDE\" data-act-after=\"2,5s\"></div>",
        "<div data-act=\"SLIDE\" data-act-after=\"500ms\"></div>",
    ]);
    let report = page_report(&page);
    assert_eq!(
        places(&report),
        [
            ("bad-act-delay", "pages/start.html:2:39".to_owned()),
            ("act-after-without-act", "pages/start.html:3:22".to_owned()),
            ("bad-act-delay", "pages/start.html:4:39".to_owned()),
        ]
    );
}

#[test]
fn triggered_labels_must_exist_and_be_offered_by_a_page() {
    let page = yaml(&[
        "<meta charset=utf-8><button data-act=\"SLIDE\">next</button>",
        "<script>",
        "  // docent.trigger('IGNORED') in a comment",
        "  docent.trigger(\"SLIDE\"); docent.trigger('SLIDEE');",
        "</script>",
    ]);
    let dir = bundle(&[
        ("acts.yaml", ACTS),
        ("docent.yaml", "kiosk:\n  idle_act: WELCOME\n"),
        ("pages/start.html", &page),
        (
            "pages/js/show.js",
            "setTimeout(() => {\n  docent.trigger(`SECRET`);\n  docent.trigger('WELCOME');\n}, 10);\n",
        ),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("trigger-not-offered", "pages/js/show.js:2:19".to_owned()),
            ("unknown-act", "pages/start.html:4:44".to_owned()),
        ]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("data-act=\"SECRET\"")
    );
    assert!(
        report.diagnostics[1]
            .message
            .contains("Did you mean `SLIDE`?")
    );
}
