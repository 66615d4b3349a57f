//! Tests of reading one command: verb and argument split, problems placed inside the text,
//! empty and unknown commands, highlight areas.

use super::*;

fn command(text: &str, column: u32, verbatim_at: Option<u32>) -> WrittenCommand {
    WrittenCommand {
        text: text.to_owned(),
        pos: Pos::new("acts.yaml", 3, column),
        verbatim_at,
    }
}

fn check(cmd: &WrittenCommand) -> (Option<CommandSpec>, Vec<(&'static str, u32)>) {
    let root = std::env::temp_dir();
    let config = SiteConfig::default();
    let checker = CommandChecker::new(&root, &config);
    let mut out = Vec::new();
    let spec = checker.check(cmd, &mut out).map(|c| c.value);
    (
        spec,
        out.iter().map(|d| (d.code.as_str(), d.column)).collect(),
    )
}

#[test]
fn splits_the_verb_from_a_trimmed_argument() {
    let (spec, problems) = check(&command("SAY   Hello there  ", 7, Some(0)));
    assert_eq!(
        spec,
        Some(CommandSpec {
            verb: Verb::Say,
            arg: Some("Hello there".to_owned()),
            args: Args::Say {
                text: "Hello there".to_owned(),
                language: None,
            }
        })
    );
    assert!(problems.is_empty());
    let (spec, _) = check(&command("DRIVE_STOP", 7, Some(0)));
    assert_eq!(
        spec,
        Some(CommandSpec {
            verb: Verb::DriveStop,
            arg: None,
            args: Args::None {}
        })
    );
}

#[test]
fn argument_problems_point_into_the_text_when_it_is_verbatim() {
    assert_eq!(
        check(&command("WAIT soon", 7, Some(0))).1,
        [("bad-argument", 12)]
    );
    assert_eq!(
        check(&command("WAIT soon", 7, Some(1))).1,
        [("bad-argument", 13)]
    );
    assert_eq!(
        check(&command("WAIT soon", 7, None)).1,
        [("bad-argument", 7)]
    );
    assert_eq!(
        check(&command("SET_WAYPOINT 1 é", 7, Some(0))).1,
        [("bad-argument", 22)]
    );
}

#[test]
fn empty_and_lower_case_commands_are_refused() {
    assert_eq!(
        check(&command("  ", 7, Some(0))),
        (None, vec![("bad-value", 7)])
    );
    assert_eq!(
        check(&command("wait", 7, Some(0))),
        (None, vec![("unknown-verb", 7)])
    );
}

#[test]
fn highlight_problems_point_at_the_bad_number() {
    let (spec, problems) = check(&command("HIGHLIGHT 0.1 0.2 0.35 0.25 ellipse", 7, Some(1)));
    assert_eq!(spec.map(|s| s.verb), Some(Verb::Highlight));
    assert!(problems.is_empty(), "{problems:?}");
    let (spec, problems) = check(&command("HIGHLIGHT", 7, Some(1)));
    assert_eq!(spec.and_then(|s| s.arg), None, "no argument clears");
    assert!(problems.is_empty(), "{problems:?}");
    // Column 7 is the quote; the argument starts at column 18.
    assert_eq!(
        check(&command("HIGHLIGHT 0.1 0.2 1.35 0.25", 7, Some(1))),
        (None, vec![("bad-argument", 26)])
    );
    assert_eq!(
        check(&command("HIGHLIGHT 0 0 1 1; 0.5 0.5 0.25 0.75", 7, Some(1))).1,
        [("bad-argument", 40)]
    );
    assert_eq!(
        check(&command("HIGHLIGHT 0.1 0.2 0.3", 7, None)).1,
        [("bad-argument", 7)]
    );
}
