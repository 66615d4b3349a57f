//! The staff-mistake suite: `tests/fixtures/library-terminal`, a realistic info terminal written
//! from docs/AUTHORING.md as a new author would, broken in a fresh copy by one real-world
//! mistake at a time (Word and Notepad habits, copy-paste, YAML traps, commands, hand-written
//! pages, phone media). Every mistake must be reported at the place the author made it, with a
//! real place and plain words; the legal variants (byte-order mark, CRLF, spaces in file names)
//! must pass without a word. The bundle itself also serves.

use crate::common;

#[path = "staff_mistakes/acts_cases.rs"]
mod acts_cases;
#[path = "staff_mistakes/command_cases.rs"]
mod command_cases;
#[path = "staff_mistakes/edits.rs"]
mod edits;
#[path = "staff_mistakes/page_cases.rs"]
mod page_cases;

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use common::check::{assert_plain, check_all, loaded};
use common::{TestServer, bundle};
use docent::content::LoadReport;
use edits::{Edit, apply, fresh_copy};

/// Mistakes `docent check` does not yet report where and how a museum author needs it, each
/// with why. The cases keep the outcome the author needs; the lead fixes the checker and then
/// deletes the line (the suite fails while a listed case is caught, so the list stays true).
const NOT_YET_CAUGHT: &[(&str, &str)] = &[];

/// One real-world mistake: what the author did, the edits that do it to a fresh copy of the
/// fixture, and every (code, `file:line:column`) that must be reported: the mistake itself
/// first, then its real consequences.
pub struct Mistake {
    pub name: &'static str,
    pub edits: &'static [Edit],
    pub expect: &'static [(&'static str, &'static str)],
}

/// The report of the fixture after `edits`.
fn check_edited(edits: &[Edit]) -> LoadReport {
    let dir = fresh_copy();
    for edit in edits {
        apply(dir.path(), edit);
    }
    check_all(dir.path())
}

/// What is wrong with how `mistake` was reported, or `None` when it was reported right.
fn shortfall(mistake: &Mistake, report: &LoadReport) -> Option<String> {
    let reported: Vec<String> = report
        .diagnostics
        .iter()
        .map(|d| format!("{} {}:{}:{}", d.code, d.file, d.line, d.column))
        .collect();
    let missing: Vec<String> = mistake
        .expect
        .iter()
        .map(|(code, at)| format!("{code} {at}"))
        .filter(|want| !reported.contains(want))
        .collect();
    let unplaced = report
        .diagnostics
        .iter()
        .any(|d| d.line == 0 || d.column == 0);
    let plain = catch_unwind(AssertUnwindSafe(|| assert_plain(report))).is_ok();
    if missing.is_empty() && !unplaced && plain {
        return None;
    }
    let said: Vec<String> = report.diagnostics.iter().map(ToString::to_string).collect();
    Some(format!(
        "{}\n  missing: {missing:?}{}{}\n  docent check said:\n    {}",
        mistake.name,
        if unplaced {
            "\n  a diagnostic at line or column 0"
        } else {
            ""
        },
        if plain {
            ""
        } else {
            "\n  parser jargon in a message"
        },
        if said.is_empty() {
            "nothing".to_owned()
        } else {
            said.join("\n    ")
        },
    ))
}

/// Runs every case of `mistakes`: each must be reported right, except the ones listed in
/// [`NOT_YET_CAUGHT`], which must still fall short.
fn run(mistakes: &[Mistake]) {
    let mut failures = Vec::new();
    for mistake in mistakes {
        let report = check_edited(mistake.edits);
        let listed = NOT_YET_CAUGHT.iter().any(|(name, _)| *name == mistake.name);
        match (shortfall(mistake, &report), listed) {
            (Some(problem), false) => failures.push(problem),
            (None, true) => failures.push(format!(
                "{}\n  is caught now: delete it from NOT_YET_CAUGHT",
                mistake.name
            )),
            (Some(problem), true) => eprintln!("not yet caught (listed): {problem}"),
            (None, false) => {}
        }
    }
    assert!(failures.is_empty(), "\n{}", failures.join("\n\n"));
}

#[test]
fn the_library_terminal_as_written_passes_without_a_word() {
    let report = check_all(Path::new(edits::FIXTURE));
    assert!(report.diagnostics.is_empty(), "{:#?}", report.diagnostics);
}

#[test]
fn word_and_notepad_habits_are_reported_at_their_line() {
    run(acts_cases::WORD_AND_NOTEPAD);
}

#[test]
fn copy_paste_mistakes_are_reported_at_their_line() {
    run(acts_cases::COPY_PASTE);
}

#[test]
fn yaml_traps_are_reported_at_their_line() {
    run(acts_cases::YAML_TRAPS);
}

#[test]
fn command_mistakes_are_reported_at_their_line() {
    run(command_cases::COMMANDS);
}

#[test]
fn page_mistakes_are_reported_at_their_line() {
    run(page_cases::PAGES);
}

#[test]
fn media_settings_and_bundle_mistakes_are_reported_at_their_line() {
    run(page_cases::MEDIA_AND_BUNDLE);
}

#[test]
fn every_listed_not_yet_caught_case_exists_and_the_suite_is_large_enough() {
    let all: Vec<&Mistake> = [
        acts_cases::WORD_AND_NOTEPAD,
        acts_cases::COPY_PASTE,
        acts_cases::YAML_TRAPS,
        command_cases::COMMANDS,
        page_cases::PAGES,
        page_cases::MEDIA_AND_BUNDLE,
    ]
    .concat_refs();
    assert!(all.len() >= 50, "{} cases", all.len());
    for (name, _) in NOT_YET_CAUGHT {
        assert!(all.iter().any(|m| m.name == *name), "no case `{name}`");
    }
    let mut names: Vec<&str> = all.iter().map(|m| m.name).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), all.len(), "case names are unique");
}

/// Flattens tables of cases into one list of references.
trait ConcatRefs {
    fn concat_refs(&self) -> Vec<&Mistake>;
}

impl ConcatRefs for [&[Mistake]; 6] {
    fn concat_refs(&self) -> Vec<&Mistake> {
        self.iter().flat_map(|table| table.iter()).collect()
    }
}

/// Legal variants: the same bundle saved the ways Windows and phones save it.
const LEGAL_VARIANTS: &[(&str, &[Edit])] = &[
    (
        "a byte-order mark on every acts file, the settings and a page",
        &[
            Edit::AddByteOrderMark {
                file: "docent.yaml",
            },
            Edit::AddByteOrderMark {
                file: "greetings.yaml",
            },
            Edit::AddByteOrderMark { file: "info.yaml" },
            Edit::AddByteOrderMark {
                file: "slideshow.yaml",
            },
            Edit::AddByteOrderMark {
                file: "pages/index.html",
            },
        ],
    ),
    ("CRLF line ends throughout", &[Edit::CrlfEverywhere]),
    (
        "a byte-order mark and CRLF together",
        &[
            Edit::CrlfEverywhere,
            Edit::AddByteOrderMark { file: "info.yaml" },
        ],
    ),
    (
        "a page and a picture with spaces, linked with a plain space",
        &[Edit::Replace {
            file: "pages/floor-plan.html",
            find: "images/floor%20plan.png",
            with: "images/floor plan.png",
        }],
    ),
];

#[test]
fn legal_variants_pass_without_a_word_and_no_carriage_return_is_spoken() {
    for (name, edits) in LEGAL_VARIANTS {
        let report = check_edited(edits);
        assert!(
            report.diagnostics.is_empty(),
            "{name}: {:#?}",
            report.diagnostics
        );
        let bundle = loaded(report);
        for act in &bundle.acts {
            for variant in &act.variants {
                for text in &variant.alternatives {
                    assert!(!text.value.contains('\r'), "{name}: {:?}", text.value);
                }
            }
        }
    }
}

#[tokio::test]
async fn the_library_terminal_serves_its_home_page_and_the_files_with_spaces() {
    let server = TestServer::start(&bundle("tests/fixtures/library-terminal")).await;
    let http = reqwest::Client::new();
    for (path, needle) in [
        ("/pages/index.html", "Welcome to the library"),
        ("/pages/kids%20corner.html", "Children’s corner"),
    ] {
        let page = http.get(server.url(path)).send().await.expect("GET");
        assert_eq!(page.status().as_u16(), 200, "{path}");
        assert!(page.text().await.expect("text").contains(needle), "{path}");
    }
    let plan = http
        .get(server.url("/pages/images/floor%20plan.png"))
        .send()
        .await
        .expect("GET");
    assert_eq!(plan.status().as_u16(), 200);
    assert!(plan.bytes().await.expect("bytes").starts_with(b"\x89PNG"));
    server.stop().await;
}
