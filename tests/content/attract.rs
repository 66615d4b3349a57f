//! The kiosk's attract loop (`kiosk: attract:`) and opening hours (`schedule:`) in
//! `docent.yaml`: one broken bundle per check, each problem at its exact file, line and
//! column, and a good one loaded into its parsed form.

use crate::common;

use std::time::Duration;

use common::check::{assert_plain, bundle, check, loaded, places, yaml};
use docent_content::{Colour, render_diagnostics};

const ACTS: (&str, &str) = ("acts.yaml", "- Label: INVITE\n  Text: Come closer!\n");

/// (code, place) of the bundle with `docent.yaml` of `lines` and the extra `files`.
fn problems(lines: &[&str], files: &[(&str, &str)]) -> Vec<(&'static str, String)> {
    let config = yaml(lines);
    let mut all = vec![ACTS, ("docent.yaml", config.as_str())];
    all.extend_from_slice(files);
    let dir = bundle(&all);
    let report = check(dir.path());
    assert_plain(&report);
    places(&report)
}

fn one(code: &'static str, place: &str) -> Vec<(&'static str, String)> {
    vec![(code, place.to_owned())]
}

#[test]
fn a_good_attract_loop_and_schedule_load() {
    let config = yaml(&[
        "kiosk:",
        "  attract: {after: 90s, pages: [attract/a.html, attract/b.html], every: 8s}",
        "schedule:",
        "  closed: closed.html",
        "  open:",
        "    - {days: Mon-Fri, hours: 09:00-17:00}",
        "    - {days: Sat, hours: 10:00-14:00, attract: {after: 1m, act: INVITE}}",
    ]);
    let dir = bundle(&[
        ACTS,
        ("docent.yaml", &config),
        ("pages/attract/a.html", "<title>a</title>"),
        ("pages/attract/b.html", "<title>b</title>"),
        ("pages/closed.html", "<title>closed</title>"),
    ]);
    let bundle = loaded(check(dir.path()));
    let attract = bundle.config.kiosk.attract.as_ref().expect("attract");
    assert_eq!(attract.after, Duration::from_secs(90));
    assert_eq!(attract.pages, ["attract/a.html", "attract/b.html"]);
    assert_eq!(attract.every, Some(Duration::from_secs(8)));
    let schedule = bundle.config.schedule.as_ref().expect("schedule");
    assert_eq!(schedule.week[0].len(), 1);
    assert_eq!(schedule.week[5][0].from, 600);
    assert!(schedule.week[6].is_empty(), "closed on Sundays");
    // The attract act is the kiosk's own: triggered by nothing else, it is not unused.
    assert!(bundle.config.kiosk_own_acts().any(|a| a == "INVITE"));
}

#[test]
fn a_missing_attract_page_is_reported_at_its_name() {
    let lines = ["kiosk:", "  attract: {pages: [attract/a.html, nope.html]}"];
    let found = problems(&lines, &[("pages/attract/a.html", "a")]);
    assert_eq!(found, one("missing-file", "docent.yaml:2:37"));
}

#[test]
fn an_attract_page_outside_pages_is_refused() {
    let lines = ["kiosk:", "  attract:", "    pages: ../docent.yaml"];
    assert_eq!(
        problems(&lines, &[]),
        one("path-outside-bundle", "docent.yaml:3:12")
    );
}

#[test]
fn a_miscased_attract_page_is_reported() {
    let lines = ["kiosk:", "  attract:", "    pages: [Attract.html]"];
    let found = problems(&lines, &[("pages/attract.html", "a")]);
    assert_eq!(found, one("miscased-file", "docent.yaml:3:13"));
}

#[test]
fn an_unknown_attract_act_is_reported_with_a_suggestion() {
    let lines = ["kiosk:", "  attract: {after: 2m, act: INVTE}"];
    let config = yaml(&lines);
    let dir = bundle(&[ACTS, ("docent.yaml", &config)]);
    let report = check(dir.path());
    assert_eq!(places(&report), one("unknown-act", "docent.yaml:2:29"));
    assert!(
        report.diagnostics[0]
            .message
            .contains("Did you mean `INVITE`?")
    );
}

#[test]
fn an_attract_loop_needs_pages_or_an_act() {
    let lines = ["kiosk:", "  attract:", "    after: 2m"];
    assert_eq!(
        problems(&lines, &[]),
        one("config-bad-value", "docent.yaml:3:5")
    );
}

#[test]
fn attract_times_need_their_unit() {
    let lines = [
        "kiosk:",
        "  attract: {after: 120, act: INVITE, every: 0.5s}",
    ];
    assert_eq!(
        problems(&lines, &[]),
        [
            ("config-bad-value", "docent.yaml:2:20".to_owned()),
            ("config-bad-value", "docent.yaml:2:45".to_owned()),
        ]
    );
}

#[test]
fn the_closed_page_must_exist() {
    let lines = [
        "schedule:",
        "  closed: closed.html",
        "  open: [{days: daily, hours: 09:00-17:00}]",
    ];
    assert_eq!(
        problems(&lines, &[]),
        one("missing-file", "docent.yaml:2:11")
    );
}

#[test]
fn a_schedule_needs_its_closed_page() {
    let lines = ["schedule:", "  open: [{days: daily, hours: 09:00-17:00}]"];
    assert_eq!(
        problems(&lines, &[]),
        one("config-bad-value", "docent.yaml:2:3")
    );
}

#[test]
fn a_range_home_page_must_exist() {
    let lines = [
        "schedule:",
        "  closed: index.html",
        "  open:",
        "    - days: Mon",
        "      hours: 09:00-17:00",
        "      home: school.html",
    ];
    assert_eq!(
        problems(&lines, &[]),
        one("missing-file", "docent.yaml:6:13")
    );
}

#[test]
fn overlapping_ranges_are_reported_once_at_the_second() {
    let lines = [
        "schedule:",
        "  closed: index.html",
        "  open:",
        "    - days: Mon-Fri",
        "      hours: 09:00-17:00",
        "    - days: Fri-Sat",
        "      hours: 10:00-12:00, 16:30-18:00",
    ];
    let config = yaml(&lines);
    let dir = bundle(&[ACTS, ("docent.yaml", &config)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("schedule-overlap", "docent.yaml:7:14".to_owned()),
            ("schedule-overlap", "docent.yaml:7:27".to_owned()),
        ]
    );
    let message = &report.diagnostics[0].message;
    assert!(
        message.contains("On Fri, 10:00-12:00 overlaps 09:00-17:00 (line 5)"),
        "{message}"
    );
    assert!(
        message.contains("`09:00-12:00` and `12:00-17:00`"),
        "{message}"
    );
}

#[test]
fn overlapping_ranges_of_a_special_day_are_reported() {
    let lines = [
        "schedule:",
        "  closed: index.html",
        "  special_days:",
        // A date to come, whenever the test runs: past dates are `past-special-day`.
        "    - {date: 2999-12-24, hours: '09:00-13:00, 12:00-14:00'}",
    ];
    assert_eq!(
        problems(&lines, &[]),
        one("schedule-overlap", "docent.yaml:4:47")
    );
}

#[test]
fn malformed_hours_are_reported_at_the_range_with_an_example() {
    for (hours, column, says) in [
        ("9-17", 14, "`HH:MM`"),
        ("09:00", 14, "joined by `-`"),
        ("17:00-09:00", 14, "two ranges"),
        ("09:00-17:00, 18:00-25:00", 27, "`HH:MM`"),
        ("09:60-17:00", 14, "`HH:MM`"),
    ] {
        let line = format!("      hours: {hours}");
        let config = yaml(&[
            "schedule:",
            "  closed: index.html",
            "  open:",
            "    - days: Mon",
            &line,
        ]);
        let dir = bundle(&[ACTS, ("docent.yaml", &config)]);
        let report = check(dir.path());
        assert_eq!(
            places(&report),
            one("config-bad-value", &format!("docent.yaml:5:{column}")),
            "{hours}"
        );
        let message = &report.diagnostics[0].message;
        assert!(message.contains(says), "{hours}: {message}");
        assert!(message.contains("e.g. `09:00-17:00`"), "{hours}: {message}");
    }
}

#[test]
fn malformed_days_are_reported_with_a_suggestion() {
    let lines = [
        "schedule:",
        "  closed: index.html",
        "  open:",
        "    - days: Mon, Tuesday, Frday",
        "      hours: 09:00-17:00",
    ];
    let config = yaml(&lines);
    let dir = bundle(&[ACTS, ("docent.yaml", &config)]);
    let report = check(dir.path());
    assert_eq!(places(&report), one("config-bad-value", "docent.yaml:4:27"));
    let message = &report.diagnostics[0].message;
    assert!(message.contains("Did you mean `Fri`?"), "{message}");
    assert!(message.contains("`Mon-Fri`"), "{message}");
}

#[test]
fn days_split_by_the_comma_of_braces_are_explained_with_the_quotes_that_fix_them() {
    let lines = [
        "schedule:",
        "  closed: index.html",
        "  open:",
        "    - { days: Sat, Sun, hours: 10:00-18:00 }",
    ];
    let config = yaml(&lines);
    let dir = bundle(&[ACTS, ("docent.yaml", &config)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        one("config-unknown-key", "docent.yaml:4:20")
    );
    let message = &report.diagnostics[0].message;
    assert!(message.contains("`Sun` is a day"), "{message}");
    assert!(message.contains("`days: \"Sat, Sun\"`"), "{message}");
}

#[test]
fn bad_and_repeated_dates_are_reported() {
    let lines = [
        "schedule:",
        "  closed: index.html",
        "  special_days:",
        "    - {date: 2999-02-29, hours: closed}",
        "    - {date: 2999-12-25, hours: closed}",
        "    - {date: 2999-12-25, hours: 10:00-12:00}",
    ];
    assert_eq!(
        problems(&lines, &[]),
        [
            ("config-bad-value", "docent.yaml:4:14".to_owned()),
            ("config-bad-value", "docent.yaml:6:14".to_owned()),
        ]
    );
}

#[test]
fn last_years_special_days_are_warned_at_their_date() {
    // 2001 is before any day this test runs on; the check with a fixed today is
    // `config_file::schedule::past`'s unit test.
    let lines = [
        "schedule:",
        "  closed: index.html",
        "  special_days:",
        "    - {date: 2001-12-25, hours: closed}",
        "    - {date: 2999-12-25, hours: closed}",
    ];
    assert_eq!(
        problems(&lines, &[]),
        one("past-special-day", "docent.yaml:4:14")
    );
}

#[test]
fn days_written_as_people_write_them_get_the_whole_range_as_the_fix() {
    for (days, says) in [
        (
            "Mon to Fri",
            "Write a range of days with a hyphen: `Mon-Fri`.",
        ),
        (
            "Mo-Fr",
            "Days are written by their first three English letters: `Mon-Fri`.",
        ),
        ("weekdays", "Write `Mon-Fri` for `weekdays`"),
        ("weekends", "Write `Sat, Sun` for `weekends`"),
        ("everyday", "Write `daily` for `everyday`"),
        ("Mon–Fri", "`–` is a dash from a word processor"),
    ] {
        let line = format!("    - days: {days}");
        let config = yaml(&[
            "schedule:",
            "  closed: index.html",
            "  open:",
            &line,
            "      hours: 09:00-17:00",
        ]);
        let dir = bundle(&[ACTS, ("docent.yaml", &config)]);
        let report = check(dir.path());
        assert_eq!(
            places(&report),
            one("config-bad-value", "docent.yaml:4:13"),
            "{days}"
        );
        let message = &report.diagnostics[0].message;
        assert!(message.starts_with(says), "{days}: {message}");
        assert!(!message.contains("Did you mean"), "{days}: {message}");
        if days == "Mon–Fri" {
            assert!(message.contains("write `Mon-Fri`"), "{message}");
        }
    }
}

#[test]
fn a_usage_with_an_example_is_rendered_as_one_whole_sentence() {
    let lines = [
        "schedule:",
        "  closed: index.html",
        "  open:",
        "    - days: Mon to Fri",
        "      hours: 09:00-17:00",
        "  special_days:",
        "    - {date: 24.12.2025, hours: closed}",
    ];
    let config = yaml(&lines);
    let dir = bundle(&[ACTS, ("docent.yaml", &config)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("config-bad-value", "docent.yaml:4:13".to_owned()),
            ("config-bad-value", "docent.yaml:7:14".to_owned()),
        ]
    );
    let text = render_diagnostics(dir.path(), &report.diagnostics, Colour::Plain);
    for whole in [
        "help: `days` names weekdays by their first three letters, alone, as a range or \
         separated by commas, e.g. `Mon-Fri`, `Sat, Sun` or `daily`.",
        "error[config-bad-value]: `date` is a day written year-month-day, e.g. `date: \
         2025-12-24`.",
    ] {
        assert!(text.contains(whole), "{whole}\n{text}");
    }
}

#[test]
fn ranges_of_one_daily_entry_that_overlap_are_said_to_overlap_every_day() {
    let lines = [
        "schedule:",
        "  closed: index.html",
        "  open:",
        "    - {days: daily, hours: '10:00-18:00, 12:00-14:00'}",
    ];
    let config = yaml(&lines);
    let dir = bundle(&[ACTS, ("docent.yaml", &config)]);
    let report = check(dir.path());
    assert_eq!(places(&report), one("schedule-overlap", "docent.yaml:4:42"));
    let message = &report.diagnostics[0].message;
    assert!(
        message.starts_with("Every day, 12:00-14:00 overlaps 10:00-18:00 (line 4)"),
        "{message}"
    );
}
