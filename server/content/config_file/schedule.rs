//! `schedule:` in `docent.yaml`: opening hours per weekday (`open:`), dates that differ
//! (`special_days:`), each range with its own home page and attract loop, and the page shown
//! while closed (`closed:`). The one grammar of days (`Mon-Fri`, `Sat, Sun`) and hours
//! (`09:00-12:00, 13:00-17:00`); every mistake is reported at the character concerned, and
//! ranges of one day that overlap are `schedule-overlap`.

use std::collections::BTreeMap;

use crate::DiagnosticCode;
use crate::acts_file::yaml::{Kind, Node};
use crate::diagnostic::Diagnostic;
use crate::model::{Located, Pos};
use crate::schedule::{CalendarDate, DAY_MINUTES, OpenHours, Schedule, WEEKDAYS};

use serde_json::{Value, json};

use super::Reader;
use super::attract;
use super::section::{Field, Section, Shape};
use crate::schema::section_schema;

mod days;
mod past;

pub(crate) use past::check_past_special_days;

/// The settings of `schedule:`.
pub(crate) const SECTION: Section = Section {
    name: "schedule",
    required: &[],
    fields: &[
        Field {
            key: "closed",
            description: "The page under pages/ shown outside opening hours.",
            shape: Shape::Words,
        },
        Field {
            key: "open",
            description: "Opening hours by weekday, each with its own home page and attract \
                          loop if wanted.",
            shape: Shape::Custom(open_schema),
        },
        Field {
            key: "special_days",
            description: "Dates that differ from their weekday (holidays, late nights).",
            shape: Shape::Custom(special_days_schema),
        },
    ],
};

/// What `hours` is, for the author.
const HOURS: &str = "Time ranges on the 24-hour clock, e.g. `09:00-17:00` or `10:00-12:00, \
                     13:00-18:00`.";

/// A range's own home page, in an `open` entry and a special day.
const RANGE_HOME: Field = Field {
    key: "home",
    description: "The home page in these hours, e.g. `school/index.html`.",
    shape: Shape::Words,
};

/// A range's own attract loop, in an `open` entry and a special day.
const RANGE_ATTRACT: Field = Field {
    key: "attract",
    description: attract::DESCRIPTION,
    shape: Shape::Nested(&attract::SECTION),
};

/// The settings of an entry of `open:`.
const OPEN: Section = Section {
    name: "an `open` entry",
    required: &[],
    fields: &[
        Field {
            key: "days",
            description: "Weekdays: `Mon-Fri`, `Sat, Sun`, `daily`, or a list of them.",
            shape: Shape::Custom(days_schema),
        },
        Field {
            key: "hours",
            description: HOURS,
            shape: Shape::Custom(hours_schema),
        },
        RANGE_HOME,
        RANGE_ATTRACT,
    ],
};

/// The settings of an entry of `special_days:`.
const SPECIAL_DAY: Section = Section {
    name: "a `special_days` entry",
    required: &[],
    fields: &[
        Field {
            key: "date",
            description: "The day, year-month-day, e.g. `2025-12-24`.",
            shape: Shape::Pattern(r"^\d{4}-\d\d-\d\d$"),
        },
        Field {
            key: "hours",
            description: "Its opening hours, or `closed` all day.",
            shape: Shape::Custom(special_hours_schema),
        },
        RANGE_HOME,
        RANGE_ATTRACT,
    ],
};

/// A weekday as the day grammar reads it: its first three letters in any case, then any
/// letters (`Mon`, `monday`).
const DAY: &str = r"([Mm][Oo][Nn]|[Tt][Uu][Ee]|[Ww][Ee][Dd]|[Tt][Hh][Uu]|[Ff][Rr][Ii]|[Ss][Aa][Tt]|[Ss][Uu][Nn])[A-Za-z]*";
/// A time of day on the 24-hour clock.
const TIME: &str = r"\d{1,2}:\d\d";

/// `days`: a day, a range of days, `daily`, or a list of them.
fn days_schema(description: &'static str) -> Value {
    json!({
        "description": description,
        "anyOf": [
            { "type": "string", "pattern": format!(r"^\s*([Dd]aily|{DAY}(\s*-\s*{DAY})?)(\s*,\s*{DAY}(\s*-\s*{DAY})?)*\s*$") },
            { "type": "array", "items": { "type": "string" } },
        ],
    })
}

/// `hours`: time ranges separated by commas.
fn hours_schema(description: &'static str) -> Value {
    json!({
        "type": "string",
        "pattern": format!(r"^\s*{TIME}\s*-\s*{TIME}\s*(,\s*{TIME}\s*-\s*{TIME}\s*)*$"),
        "description": description,
    })
}

/// A special day's `hours`: time ranges, or `closed`.
fn special_hours_schema(description: &'static str) -> Value {
    json!({
        "description": description,
        "anyOf": [hours_schema(HOURS), { "const": "closed" }],
    })
}

/// `open`: a list of opening hours.
fn open_schema(description: &'static str) -> Value {
    json!({
        "type": "array",
        "items": section_schema(&OPEN, "Opening hours on some weekdays."),
        "description": description,
    })
}

/// `special_days`: a list of dates.
fn special_days_schema(description: &'static str) -> Value {
    json!({
        "type": "array",
        "items": section_schema(&SPECIAL_DAY, "A date whose hours differ from its weekday's."),
        "description": description,
    })
}
const CLOSED_USAGE: &str = "`closed` names the page under pages/ the kiosk shows outside \
                            opening hours, e.g. `closed: closed.html`.";
const LIST_USAGE: &str = "`open` lists opening hours, each with `days` and `hours`, e.g. \
                          `- {days: Mon-Fri, hours: 09:00-17:00}`.";
const SPECIAL_USAGE: &str = "`special_days` lists dates that differ from their weekday, each \
                             with `date` and `hours`, e.g. `- {date: 2025-12-24, hours: \
                             09:00-13:00}` or `- {date: 2025-12-25, hours: closed}`.";
const DAYS_USAGE: &str = "`days` names weekdays by their first three letters, alone, as a \
                          range or separated by commas, e.g. `Mon-Fri`, `Sat, Sun` or `daily`.";
const HOURS_USAGE: &str = "`hours` is one or more time ranges on the 24-hour clock, separated \
                           by commas, e.g. `09:00-17:00` or `10:00-12:00, 13:00-18:00`; a \
                           range ending at midnight ends at `24:00`.";
const DATE_USAGE: &str = "`date` is a day written year-month-day, e.g. `date: 2025-12-24`.";
const CLOSED_NEEDED: &str = "A schedule needs the page shown outside opening hours, e.g. \
                             `closed: closed.html`.";

/// One range as written, before the overlap check.
struct Written {
    from: u16,
    to: u16,
    pos: Pos,
    /// The days of its entry as written (`every day`, `Mon-Fri`), for an overlap within it.
    days: String,
}

impl Reader {
    /// Reads `schedule:`; `None` (after reporting) when it is unusable.
    pub(super) fn schedule(&mut self, node: &Node) -> Option<Schedule> {
        let mut schedule = Schedule::default();
        let mut closed = None;
        let mut usable = true;
        for (field, value) in self.entries(node, &SECTION) {
            match field.key {
                "closed" => closed = self.page_setting(value, CLOSED_USAGE),
                "open" => usable &= self.open_hours(value, &mut schedule),
                _ => usable &= self.special_days(value, &mut schedule),
            }
        }
        let Some(closed) = closed else {
            if matches!(node.kind, Kind::Map(_)) && usable {
                self.bad(node, CLOSED_NEEDED);
            }
            return None;
        };
        schedule.closed_page = closed;
        usable.then_some(schedule)
    }

    /// `open:`: each entry's ranges added to its days; false after reporting a problem.
    fn open_hours(&mut self, node: &Node, schedule: &mut Schedule) -> bool {
        let Kind::Seq(entries) = &node.kind else {
            self.bad(node, LIST_USAGE);
            return false;
        };
        let mut written: [Vec<Written>; 7] = Default::default();
        let mut usable = true;
        for entry in entries {
            let mut days = None;
            let mut ranges = None;
            let mut extras = Extras::default();
            let mut days_written = String::new();
            for (field, value) in self.entries(entry, &OPEN) {
                match field.key {
                    "days" => {
                        days = self.days(value);
                        days_written = days::days_as_written(value);
                    }
                    "hours" => ranges = self.hours(value).filter(|r| !r.is_empty()),
                    _ => usable &= self.extra(field.key, value, &mut extras),
                }
            }
            self.explain_days_split_by_braces(entry);
            let (Some(days), Some(ranges)) = (days, ranges) else {
                if matches!(entry.kind, Kind::Map(_)) {
                    self.needs_both(entry, "days", LIST_USAGE);
                }
                usable = false;
                continue;
            };
            for day in days {
                for range in &ranges {
                    schedule.week[day].push(extras.hours(range));
                    written[day].push(Written {
                        pos: range.pos.clone(),
                        days: days_written.clone(),
                        ..*range
                    });
                }
            }
        }
        for (day, ranges) in written.iter_mut().enumerate() {
            usable &= self.no_overlap(ranges, WEEKDAYS[day]);
            schedule.week[day].sort_by_key(|h| h.from);
        }
        usable
    }

    /// `special_days:`: each date's ranges (none: closed all day).
    fn special_days(&mut self, node: &Node, schedule: &mut Schedule) -> bool {
        let Kind::Seq(entries) = &node.kind else {
            self.bad(node, SPECIAL_USAGE);
            return false;
        };
        let mut seen: BTreeMap<CalendarDate, u32> = BTreeMap::new();
        let mut usable = true;
        for entry in entries {
            let mut date = None;
            let mut ranges = None;
            let mut extras = Extras::default();
            for (field, value) in self.entries(entry, &SPECIAL_DAY) {
                match field.key {
                    "date" => date = self.date(value, &mut seen),
                    "hours" if value.as_text().map(str::trim) == Some("closed") => {
                        ranges = Some(Vec::new());
                    }
                    "hours" => ranges = self.hours(value).filter(|r| !r.is_empty()),
                    _ => usable &= self.extra(field.key, value, &mut extras),
                }
            }
            let (Some(date), Some(mut ranges)) = (date, ranges) else {
                if matches!(entry.kind, Kind::Map(_)) {
                    self.needs_both(entry, "date", SPECIAL_USAGE);
                }
                usable = false;
                continue;
            };
            usable &= self.no_overlap(&mut ranges, &date.to_string());
            let hours = ranges.iter().map(|r| extras.hours(r)).collect();
            schedule.special_days.insert(date, hours);
        }
        usable
    }

    /// An entry lacking `first` or `hours` (when no other problem was reported in it).
    fn needs_both(&mut self, entry: &Node, first: &str, usage: &str) {
        let Kind::Map(pairs) = &entry.kind else {
            return;
        };
        let has = |k: &str| pairs.iter().any(|(key, _)| key.as_text() == Some(k));
        if !has(first) || !has("hours") {
            let message = format!("This entry needs both `{first}` and `hours`. {usage}");
            self.diagnostics.push(Diagnostic::error(
                DiagnosticCode::ConfigBadValue,
                &entry.pos,
                message,
            ));
        }
    }

    /// `home` or `attract` of a range.
    fn extra(&mut self, key: &str, value: &Node, extras: &mut Extras) -> bool {
        if key == "home" {
            let usage = "`home` names the page under pages/ the kiosk starts on in these \
                         hours, e.g. `home: school/index.html`.";
            extras.home = self.page_setting(value, usage);
            return extras.home.is_some();
        }
        extras.attract = self.attract(value);
        extras.attract.is_some()
    }

    /// `09:00-12:00, 13:00-17:00`: each range with its place.
    fn hours(&mut self, node: &Node) -> Option<Vec<Written>> {
        let Some(text) = node.as_text() else {
            self.bad(node, HOURS_USAGE);
            return None;
        };
        let mut ranges = Vec::new();
        for (part, pos) in split_at_commas(node, text) {
            let part = part.trim();
            match time_range(part) {
                Ok((from, to)) => ranges.push(Written {
                    from,
                    to,
                    pos,
                    days: String::new(),
                }),
                Err(why) => {
                    self.bad_at(&pos, &format!("{why} {HOURS_USAGE}"), part);
                    return None;
                }
            }
        }
        Some(ranges)
    }

    /// A special day's date, each date once.
    fn date(
        &mut self,
        node: &Node,
        seen: &mut BTreeMap<CalendarDate, u32>,
    ) -> Option<CalendarDate> {
        let date = self.setting(node, DATE_USAGE, CalendarDate::parse)?;
        if let Some(line) = seen.insert(date, node.pos.line) {
            let message = format!("{date} is listed twice (first on line {line}). Keep one.");
            self.bad(node, &message);
            return None;
        }
        (self.special_dates).push(Located {
            value: date,
            pos: node.pos.clone(),
        });
        Some(date)
    }

    /// Reports `schedule-overlap` at each range that overlaps one before it on `day`.
    fn no_overlap(&mut self, ranges: &mut [Written], day: &str) -> bool {
        ranges.sort_by_key(|r| (r.from, r.pos.line, r.pos.column));
        let mut fine = true;
        // The range reaching furthest so far: a later range overlaps it, if anything.
        let mut reaching = 0;
        for index in 1..ranges.len() {
            if ranges[index - 1].to > ranges[reaching].to {
                reaching = index - 1;
            }
            let (earlier, later) = (&ranges[reaching], &ranges[index]);
            if later.from >= earlier.to {
                continue;
            }
            let at = |r: &Written| (r.pos.line, r.pos.column);
            // Reported at the range written second: the first one is usually the intended one.
            let (first, second) = if at(later) > at(earlier) {
                (earlier, later)
            } else {
                (later, earlier)
            };
            fine = false;
            let told = |d: &Diagnostic| {
                d.code == DiagnosticCode::ScheduleOverlap && (d.line, d.column) == at(second)
            };
            if self.diagnostics.iter().any(told) {
                continue; // the same range on another of its days
            }
            // Ranges of the same days overlap on each of them: name the days as written.
            let when = match first.days.as_str() {
                _ if first.days.is_empty() || first.days != second.days => format!("On {day}"),
                "every day" => "Every day".to_owned(),
                days => format!("On {days}"),
            };
            let message = format!(
                "{when}, {} overlaps {} (line {}): the kiosk cannot be in two ranges at \
                 once. End one where the next begins, e.g. `09:00-12:00` and `12:00-17:00`, \
                 or name fewer days (`Mon-Fri` and `Sat`).",
                clock_range(second),
                clock_range(first),
                first.pos.line
            );
            self.diagnostics.push(Diagnostic::error(
                DiagnosticCode::ScheduleOverlap,
                &second.pos,
                message,
            ));
        }
        fine
    }

    /// A `config-bad-value` at a place inside a value.
    fn bad_at(&mut self, pos: &Pos, message: &str, found: &str) {
        let message = format!("{message} Found: `{found}`.");
        self.diagnostics.push(Diagnostic::error(
            DiagnosticCode::ConfigBadValue,
            pos,
            message,
        ));
    }
}

/// The home page and attract loop a range was given.
#[derive(Default)]
struct Extras {
    home: Option<String>,
    attract: Option<crate::attract::AttractLoop>,
}

impl Extras {
    fn hours(&self, range: &Written) -> OpenHours {
        OpenHours {
            from: range.from,
            to: range.to,
            home: self.home.clone(),
            attract: self.attract.clone(),
        }
    }
}

/// The comma-separated parts of `text`, each with its own place when the scalar is written
/// word for word on one line (else the scalar's place).
fn split_at_commas(node: &Node, text: &str) -> Vec<(String, Pos)> {
    let verbatim = match &node.kind {
        Kind::Str { verbatim_at, .. } => *verbatim_at,
        Kind::Guessed(_) => Some(0),
        _ => None,
    };
    let mut parts = Vec::new();
    let mut offset = 0u32;
    for part in text.split(',') {
        let leading = part.len() - part.trim_start().len();
        let mut pos = node.pos.clone();
        if let Some(at) = verbatim.filter(|_| !text.contains('\n')) {
            let chars = offset + u32::try_from(part[..leading].chars().count()).unwrap_or(0);
            pos.column += at + chars;
        }
        parts.push((part.to_owned(), pos));
        offset += u32::try_from(part.chars().count()).unwrap_or(0) + 1;
    }
    parts
}

/// `09:00-17:00` into minutes from midnight, or why not (a sentence).
fn time_range(text: &str) -> Result<(u16, u16), &'static str> {
    if text.contains(days::WORD_PROCESSOR_DASHES) {
        return Err(
            "This range has a dash from a word processor (`–`), not the plain minus \
                    sign `-` (the key next to 0) that joins its start and end.",
        );
    }
    let (from, to) = text
        .split_once('-')
        .ok_or("A range needs its start and end joined by `-`.")?;
    let (from, to) = (clock_time(from.trim()), clock_time(to.trim()));
    let (Some(from), Some(to)) = (from, to) else {
        return Err("Write each time as hours and minutes, `HH:MM`, from 00:00 to 24:00.");
    };
    if from >= to {
        return Err(
            "A range must end after it starts on the same day; for hours past \
                    midnight write two ranges on the two days (`22:00-24:00` and \
                    `00:00-02:00`).",
        );
    }
    Ok((from, to))
}

/// `9:00`, `09:00` or `24:00` in minutes from midnight.
fn clock_time(text: &str) -> Option<u16> {
    let (h, m) = text.split_once(':')?;
    let digits = |t: &str| !t.is_empty() && t.bytes().all(|b| b.is_ascii_digit());
    if !digits(h) || h.len() > 2 || m.len() != 2 || !digits(m) {
        return None;
    }
    let (h, m): (u16, u16) = (h.parse().ok()?, m.parse().ok()?);
    let minutes = h * 60 + m;
    (m < 60 && minutes <= DAY_MINUTES).then_some(minutes)
}

fn clock_range(range: &Written) -> String {
    let hhmm = |m: u16| format!("{:02}:{:02}", m / 60, m % 60);
    format!("{}-{}", hhmm(range.from), hhmm(range.to))
}
