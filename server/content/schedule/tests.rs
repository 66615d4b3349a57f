//! The schedule evaluated at fixed wall-clock times: day boundaries, closing time, special
//! days, and each range's home page and attract loop.

use std::time::Duration;

use super::*;
use crate::config_file::test_support::parse;

const SITE: &str = "\
home: index.html
kiosk:
  attract: {after: 3m, pages: [attract/a.html]}
schedule:
  closed: closed.html
  open:
    - days: Mon-Fri
      hours: 09:00-12:00
      home: school.html
      attract: {after: 1m, act: INVITE}
    - days: Mon-Fri
      hours: 12:00-17:00
    - days: Sat, Sun
      hours: 10:00-24:00
  special_days:
    - date: 2025-12-24
      hours: 09:00-13:00
    - date: 2025-12-25
      hours: closed
";

fn site() -> SiteConfig {
    let file = parse(SITE);
    assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
    file.config
}

/// `date` (a day of 2025) at `hh:mm`; `weekday` 0 for Monday.
fn at(month: u8, day: u8, weekday: u8, hh: u16, mm: u16) -> WallClock {
    WallClock {
        date: CalendarDate {
            year: 2025,
            month,
            day,
        },
        weekday,
        minute: hh * 60 + mm,
    }
}

fn home_at(config: &SiteConfig, clock: &WallClock) -> Option<String> {
    match config.showing_at(clock) {
        Showing::Open { home, .. } => Some(home.to_owned()),
        Showing::Closed { page } => {
            assert_eq!(page, "closed.html");
            None
        }
    }
}

#[test]
fn opening_and_closing_minutes_are_open_and_closed() {
    let config = site();
    // Monday 2025-12-01.
    assert_eq!(
        home_at(&config, &at(12, 1, 0, 8, 59)),
        None,
        "before opening"
    );
    assert_eq!(
        home_at(&config, &at(12, 1, 0, 9, 0)).as_deref(),
        Some("school.html")
    );
    assert_eq!(
        home_at(&config, &at(12, 1, 0, 11, 59)).as_deref(),
        Some("school.html")
    );
    assert_eq!(
        home_at(&config, &at(12, 1, 0, 12, 0)).as_deref(),
        Some("index.html")
    );
    assert_eq!(
        home_at(&config, &at(12, 1, 0, 16, 59)).as_deref(),
        Some("index.html")
    );
    assert_eq!(
        home_at(&config, &at(12, 1, 0, 17, 0)),
        None,
        "closing time is closed"
    );
}

#[test]
fn a_range_to_midnight_covers_the_last_minute_and_the_next_day_starts_closed() {
    let config = site();
    // Saturday 2025-12-06 23:59 is open; Sunday 00:00 is before Sunday's 10:00.
    assert!(home_at(&config, &at(12, 6, 5, 23, 59)).is_some());
    assert_eq!(home_at(&config, &at(12, 7, 6, 0, 0)), None);
    assert!(home_at(&config, &at(12, 7, 6, 10, 0)).is_some());
}

#[test]
fn special_days_replace_their_weekday() {
    let config = site();
    // Wednesday 2025-12-24: 09:00-13:00 instead of Mon-Fri's two ranges.
    assert_eq!(
        home_at(&config, &at(12, 24, 2, 12, 59)).as_deref(),
        Some("index.html")
    );
    assert_eq!(home_at(&config, &at(12, 24, 2, 13, 0)), None);
    assert_eq!(
        home_at(&config, &at(12, 24, 2, 10, 0)).as_deref(),
        Some("index.html")
    );
    // Thursday 2025-12-25: closed all day; Friday the 26th as any Friday.
    assert_eq!(home_at(&config, &at(12, 25, 3, 10, 0)), None);
    assert_eq!(
        home_at(&config, &at(12, 26, 4, 10, 0)).as_deref(),
        Some("school.html")
    );
}

#[test]
fn each_range_has_its_attract_loop_or_the_kiosks() {
    let config = site();
    let attract = |clock| match config.showing_at(&clock) {
        Showing::Open { attract, .. } => attract.cloned(),
        Showing::Closed { .. } => None,
    };
    let school = attract(at(12, 1, 0, 10, 0)).expect("the range's own loop");
    assert_eq!(school.act.as_deref(), Some("INVITE"));
    assert_eq!(school.after, Duration::from_secs(60));
    let default = attract(at(12, 1, 0, 13, 0)).expect("the kiosk's loop");
    assert_eq!(default.pages, ["attract/a.html"]);
    let mut acts: Vec<&str> = config.kiosk_own_acts().collect();
    acts.dedup(); // one per weekday the range is on
    assert_eq!(acts, ["INVITE"]);
}

#[test]
fn without_a_schedule_the_kiosk_is_always_open() {
    let config = parse("home: start.html\n").config;
    assert_eq!(
        config.showing_at(&at(12, 25, 3, 3, 0)),
        Showing::Open {
            home: "start.html",
            attract: None
        }
    );
}

#[test]
fn the_kiosk_gets_weekdays_monday_first_and_dates_as_text() {
    let config = site();
    let json = serde_json::to_value(config.schedule.as_ref().expect("a schedule")).expect("json");
    assert_eq!(json["closed_page"], "closed.html");
    assert_eq!(json["week"][0][0]["from"], 540);
    assert_eq!(json["week"][0][0]["home"], "school.html");
    assert_eq!(json["week"][6][0]["to"], 1440);
    assert_eq!(json["special_days"]["2025-12-25"], serde_json::json!([]));
    let showing = serde_json::to_value(config.showing_at(&at(12, 25, 3, 10, 0))).expect("json");
    assert_eq!(
        showing,
        serde_json::json!({"state": "closed", "page": "closed.html"})
    );
}

#[test]
fn calendar_dates_are_real_days() {
    assert!(CalendarDate::parse("2024-02-29").is_some());
    for bad in [
        "2025-02-29",
        "2025-13-01",
        "2025-1-01",
        "25-01-01",
        "2025-01-00",
        "2025-01-01-",
    ] {
        assert_eq!(CalendarDate::parse(bad), None, "{bad}");
    }
    let date = CalendarDate::parse("2025-03-09").expect("a day");
    assert_eq!(date.to_string(), "2025-03-09");
}

#[test]
fn a_timetable_changes_exactly_where_the_schedule_does_minute_by_minute() {
    let config = site();
    // Monday 2025-12-22 08:59, over Christmas Eve (09:00-13:00) and a closed Christmas Day.
    let from = WallClock::parse("2025-12-22T08:59").expect("a time");
    let table = config.timetable(&from, 8);
    assert_eq!(table.until.to_string(), "2025-12-31T00:00");
    let mut clock = from;
    let mut held = &table.showing;
    let mut changes = table.changes.iter().peekable();
    while clock != table.until {
        if let Some(change) = changes.next_if(|c| c.at == clock) {
            held = &change.showing;
        }
        assert_eq!(*held, config.showing_at(&clock), "at {clock}");
        clock = match clock.minute + 1 {
            DAY_MINUTES => clock.next_midnight(),
            minute => WallClock { minute, ..clock },
        };
    }
    assert!(changes.next().is_none(), "a change after the window");
    let first: Vec<String> = (table.changes.iter().take(4))
        .map(|c| format!("{} {:?}", c.at, home_at(&config, &c.at)))
        .collect();
    assert_eq!(
        first,
        [
            "2025-12-22T09:00 Some(\"school.html\")",
            "2025-12-22T12:00 Some(\"index.html\")",
            "2025-12-22T17:00 None",
            "2025-12-23T09:00 Some(\"school.html\")",
        ]
    );
}

#[test]
fn without_a_schedule_a_timetable_never_changes() {
    let config = parse("home: start.html\n").config;
    let from = WallClock::parse("2025-12-31T23:59").expect("a time");
    let table = config.timetable(&from, 2);
    assert!(table.changes.is_empty());
    assert_eq!(table.until.to_string(), "2026-01-03T00:00");
}

#[test]
fn wall_times_are_read_and_written_as_the_kiosk_sends_them() {
    let monday = WallClock::parse("2025-12-01T08:59").expect("a time");
    assert_eq!(monday, at(12, 1, 0, 8, 59));
    assert_eq!(monday.to_string(), "2025-12-01T08:59");
    let sunday = WallClock::parse("2024-02-29T23:05").expect("a leap day");
    assert_eq!((sunday.weekday, sunday.minute), (3, 23 * 60 + 5));
    for bad in [
        "2025-12-01 08:59",
        "2025-12-01T24:00",
        "2025-12-01T08:60",
        "2025-02-29T08:00",
        "2025-12-01T8:59",
        "2025-12-01T08:59:00",
        "",
    ] {
        assert_eq!(WallClock::parse(bad), None, "{bad}");
    }
}
