//! Loading bundles into the model: the paper's Fig. 4 sample unchanged, every position kept,
//! acts files merged in name order, site settings applied, and the shipped dialogs clean.

use crate::common;

use std::fs;
use std::path::PathBuf;

use common::check::loaded;
use docent_content::config::{AccessSettings, AdapterKind, ArgRule};
use docent_content::{Args, Bundle, CommandSpec, MediaKind, Pos, Severity, Verb, load_bundle};

fn repo(rel: &str) -> PathBuf {
    common::repo().join(rel)
}

/// Lines joined into a file, one element a line: line numbers in assertions are indexes + 1.
fn yaml(lines: &[&str]) -> String {
    lines.iter().map(|l| format!("{l}\n")).collect()
}

/// A bundle in a temporary folder with `pages/index.html` and `files`.
fn bundle(files: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("temp dir");
    fs::create_dir_all(dir.path().join("media")).expect("media");
    fs::create_dir_all(dir.path().join("pages")).expect("pages");
    fs::write(dir.path().join("pages/index.html"), "<title>home</title>").expect("home");
    for (rel, contents) in files {
        fs::write(dir.path().join(rel), contents).expect("write file");
    }
    dir
}

fn at(line: u32, column: u32) -> Pos {
    Pos::new("acts.yaml", line, column)
}

/// (text, line, column) of each alternative of a variant.
fn alternatives(bundle: &Bundle, label: &str, variant: &str) -> Vec<(String, u32, u32)> {
    let act = bundle.act(label).expect("act");
    let variant = act.variant(variant).expect("variant");
    variant
        .alternatives
        .iter()
        .map(|a| (a.value.clone(), a.pos.line, a.pos.column))
        .collect()
}

#[test]
fn the_papers_fig4_sample_loads_unchanged() {
    let report = load_bundle(&repo("tests/fixtures/fig4-verbatim"));
    let warnings: Vec<(&str, String)> = report
        .diagnostics
        .iter()
        .map(|d| {
            (
                d.code.as_str(),
                format!("{}:{}:{}", d.file, d.line, d.column),
            )
        })
        .collect();
    assert_eq!(
        warnings,
        [
            // No docent.yaml names the figure's Welcome page as the home page. WELCOME and OK
            // (no page offers them) are the operator's, and each context used once is meant.
            ("no-home-page", "pages/index.html:1:1".to_owned())
        ]
    );
    assert!(
        report
            .diagnostics
            .iter()
            .all(|d| d.severity == Severity::Warning)
    );
    let bundle = loaded(report);
    assert_eq!(
        bundle.labels().collect::<Vec<_>>(),
        ["WELCOME", "OK", "WHERE_FROM", "RUN_VIDEO_EXHIBIT"]
    );
    assert_eq!(bundle.index["WHERE_FROM"], 2);
    assert_eq!(bundle.contexts, ["Text", "TextFormally", "TextGroup"]);
    assert_eq!(bundle.page_acts, ["RUN_VIDEO_EXHIBIT", "WHERE_FROM"]);
    assert_eq!(
        bundle.root,
        repo("tests/fixtures/fig4-verbatim")
            .canonicalize()
            .expect("root")
    );
}

/// The paper's Fig. 4 as printed (its `video.mpg`, a real MPEG-1 file, and its "May I mask"),
/// with its Welcome page and a docent.yaml naming that page home, and no `Group` or
/// `contexts:`: nothing about its design is a problem, and the MPEG-1 video is converted when
/// served, which the check notes.
#[test]
fn the_papers_fig4_as_printed_loads_with_a_note_that_its_mpeg_video_is_converted() {
    let report = load_bundle(&common::repo().join("tests/content/fixtures/fig4-paper"));
    let problems: Vec<(&str, Severity, String)> = report
        .diagnostics
        .iter()
        .map(|d| {
            (
                d.code.as_str(),
                d.severity,
                format!("{}:{}:{}", d.file, d.line, d.column),
            )
        })
        .collect();
    assert_eq!(
        problems,
        [(
            "media-converted",
            Severity::Note,
            "acts.yaml:25:15".to_owned()
        )]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("`media/Exhibit/video.mpg` is an MPEG-1/2 video"),
        "{}",
        report.diagnostics[0].message
    );
    let bundle = report.bundle.expect("Fig. 4 runs as printed");
    assert_eq!(bundle.conversions.len(), 1);
}

#[test]
fn every_fig4_act_keeps_the_place_of_each_part() {
    let bundle = loaded(load_bundle(&repo("tests/fixtures/fig4-verbatim")));
    let labels: Vec<(&str, Pos)> = bundle
        .acts
        .iter()
        .map(|a| (a.label.as_str(), a.pos.clone()))
        .collect();
    assert_eq!(
        labels,
        [
            ("WELCOME", at(1, 10)),
            ("OK", at(7, 10)),
            ("WHERE_FROM", at(13, 10)),
            ("RUN_VIDEO_EXHIBIT", at(21, 10))
        ]
    );

    assert_eq!(
        alternatives(&bundle, "WELCOME", "Text"),
        [("Hello!".to_owned(), 3, 7)]
    );
    assert_eq!(
        alternatives(&bundle, "OK", "Text"),
        [
            ("OK!".to_owned(), 9, 7),
            ("Great!".to_owned(), 10, 7),
            ("Splendid!".to_owned(), 11, 7)
        ]
    );
    let where_from = bundle.act("WHERE_FROM").expect("act");
    let variants: Vec<(&str, Pos)> = where_from
        .variants
        .iter()
        .map(|v| (v.name.as_str(), v.pos.clone()))
        .collect();
    assert_eq!(
        variants,
        [
            ("Text", at(14, 3)),
            ("TextGroup", at(16, 3)),
            ("TextFormally", at(18, 3))
        ]
    );
    assert_eq!(
        alternatives(&bundle, "WHERE_FROM", "TextGroup"),
        [("Where are you from?".to_owned(), 17, 7)]
    );
    assert_eq!(
        alternatives(&bundle, "WHERE_FROM", "TextFormally"),
        [("May I ask from where you are?".to_owned(), 19, 7)]
    );
    assert!(bundle.act("OK").expect("act").commands.is_empty());
    assert!(where_from.commands.is_empty());

    let commands = |label: &str| -> Vec<(CommandSpec, Pos)> {
        bundle
            .act(label)
            .expect("act")
            .commands
            .iter()
            .map(|c| (c.value.clone(), c.pos.clone()))
            .collect()
    };
    let spec = |verb, arg: &str, args| CommandSpec {
        verb,
        arg: Some(arg.to_owned()),
        args,
    };
    let page = "Welcome/Welcome.html";
    assert_eq!(
        commands("WELCOME"),
        [(
            spec(Verb::DisplayPage, page, Args::Page { page: page.into() }),
            at(5, 7)
        )]
    );
    let file = "Exhibit/video.mp4";
    let video = Args::Project {
        file: file.into(),
        kind: MediaKind::Video,
    };
    assert_eq!(
        commands("RUN_VIDEO_EXHIBIT"),
        [(spec(Verb::Project, file, video), at(25, 7))]
    );
}

#[test]
fn every_shipped_dialog_bundle_loads_without_errors() {
    let mut checked = 0;
    for entry in fs::read_dir(repo("dialogs"))
        .expect("dialogs folder")
        .flatten()
    {
        if entry.path().is_dir() {
            let bundle = loaded(load_bundle(&entry.path()));
            assert!(
                !bundle.acts.is_empty(),
                "{} has acts",
                entry.path().display()
            );
            // Tokens come from the environment; a shipped bundle would give them to everyone.
            assert_eq!(
                bundle.config.access,
                AccessSettings::default(),
                "{} holds no tokens",
                entry.path().display()
            );
            checked += 1;
        }
    }
    assert!(checked > 0);
}

#[test]
fn acts_files_are_merged_in_file_name_order() {
    let dir = bundle(&[
        ("b.yaml", "- Label: B1\n  Text: b\n"),
        ("a.yml", "- Label: A1\n  Text: a\n- Label: A2\n  Text: a\n"),
        ("c.YAML", "- Label: C1\n  Text: c\n"),
        (".draft.yaml", "not: [valid\n"),
        ("docent.yaml", "home: index.html\n"),
        ("notes.txt", "- Label: NOT_READ\n"),
    ]);
    let bundle = loaded(load_bundle(dir.path()));
    assert_eq!(
        bundle.labels().collect::<Vec<_>>(),
        ["A1", "A2", "B1", "C1"]
    );
    assert_eq!(
        bundle.act("B1").expect("act").pos,
        Pos::new("b.yaml", 1, 10)
    );
    for (label, index) in [("A1", 0), ("A2", 1), ("B1", 2), ("C1", 3)] {
        assert_eq!(bundle.index[label], index);
    }
}

#[test]
fn a_single_string_is_accepted_where_a_list_is_expected() {
    let dir = bundle(&[(
        "acts.yaml",
        "- Label: HI\n  Text: Hello there\n  TextChild: Hi kid\n  Cmds: WAIT 2s\n",
    )]);
    let bundle = loaded(load_bundle(dir.path()));
    assert_eq!(
        alternatives(&bundle, "HI", "Text"),
        [("Hello there".to_owned(), 2, 9)]
    );
    assert_eq!(
        alternatives(&bundle, "HI", "TextChild"),
        [("Hi kid".to_owned(), 3, 14)]
    );
    let act = bundle.act("HI").expect("act");
    assert_eq!(
        act.commands[0].value,
        CommandSpec {
            verb: Verb::Wait,
            arg: Some("2s".to_owned()),
            args: Args::Wait {
                pause: Some(std::time::Duration::from_secs(2))
            }
        }
    );
    assert_eq!(act.commands[0].pos, at(4, 9));
}

#[test]
fn site_settings_shape_the_bundle() {
    let config = yaml(&[
        "contexts: [TextGroup, TextChild]",
        "verbs:",
        "  LIGHTS:",
        "    adapter: log",
        "    argument: required",
    ]);
    let acts = yaml(&[
        "- Label: ON",
        "  Text: Let there be light",
        "  TextChild: Look!",
        "  Cmds:",
        "    - LIGHTS on",
        "    - WAIT",
    ]);
    let dir = bundle(&[("docent.yaml", &config), ("acts.yaml", &acts)]);
    let bundle = loaded(load_bundle(dir.path()));
    assert_eq!(bundle.contexts, ["Text", "TextGroup", "TextChild"]);
    let lights = &bundle.config.verbs["LIGHTS"];
    assert_eq!(
        (lights.adapter, lights.argument),
        (AdapterKind::Log, ArgRule::Required)
    );
    let commands: Vec<&CommandSpec> = bundle
        .act("ON")
        .expect("act")
        .commands
        .iter()
        .map(|c| &c.value)
        .collect();
    assert_eq!(
        commands,
        [
            &CommandSpec {
                verb: Verb::Site("LIGHTS".into()),
                arg: Some("on".to_owned()),
                args: Args::Site {
                    arg: Some("on".to_owned())
                }
            },
            &CommandSpec {
                verb: Verb::Wait,
                arg: None,
                args: Args::Wait { pause: None }
            },
        ]
    );
}

#[test]
fn diagnostics_are_sorted_by_file_line_and_column() {
    let dir = bundle(&[
        ("b.yaml", "- Label: X\n  Cmds: [say a, say b]\n"),
        ("a.yaml", "- Label: X\n  Lable: Y\n- Text: z\n"),
    ]);
    let report = load_bundle(dir.path());
    let order: Vec<(String, u32, u32)> = report
        .diagnostics
        .iter()
        .map(|d| (d.file.clone(), d.line, d.column))
        .collect();
    let mut sorted = order.clone();
    sorted.sort();
    assert_eq!(order, sorted);
    // Seven problems (X of b.yaml, offered by no page, is the operator's: no act has a Group).
    assert_eq!(order.len(), 7, "{:#?}", report.diagnostics);
    assert!(report.bundle.is_none());
}

#[test]
fn ten_thousand_rich_acts_load_in_one_go() {
    let acts: String = (0..10_000)
        .map(|i| {
            format!(
                "- Label: ACT_{i}\n  Text:\n    - Hello number {i}.\n    - Another alternative.\n  \
                 TextGroup:\n    - Hello all.\n  Cmds:\n    - SAY extra\n    - WAIT 2s\n"
            )
        })
        .collect();
    let dir = bundle(&[("acts.yaml", &acts)]);
    let started = std::time::Instant::now();
    let bundle = loaded(load_bundle(dir.path()));
    eprintln!(
        "10,000 acts loaded in {:?} (debug builds are much slower than release)",
        started.elapsed()
    );
    assert_eq!(bundle.acts.len(), 10_000);
    assert_eq!(bundle.act("ACT_9999").expect("act").pos, at(89_992, 10));
}
