//! A bundle's opening hours (`schedule:` in `docent.yaml`): per weekday and for special
//! dates, the time ranges the kiosk is open, each with its own home page and attract loop,
//! and the page shown while closed. Read once by `config_file/schedule.rs`; evaluated only
//! here: for `GET /api/state` ([`SiteConfig::showing_at`]) and, for the kiosk, as a
//! [`Timetable`] from the kiosk's own wall-clock time (`static/schedule.js` applies the
//! changes it is given when its clock reaches them; it holds no copy of the rule).
//!
//! Times are wall-clock times where the kiosk is: the kiosk uses its own clock and time zone,
//! the server its own (`WallClock::now`), so both machines should be set to the site's zone.

use std::collections::BTreeMap;
use std::fmt;

use serde::{Serialize, Serializer};

use crate::attract::AttractLoop;
use crate::config::SiteConfig;

/// Minutes in a day: the end of a range that closes at midnight (`24:00`).
pub const DAY_MINUTES: u16 = 24 * 60;

/// The weekday names as written in `docent.yaml`, Monday first (the index used throughout).
pub const WEEKDAYS: [&str; 7] = ["Mon", "Tue", "Wed", "Thu", "Fri", "Sat", "Sun"];

/// When the kiosk is open and what it shows then.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Schedule {
    /// The page under `pages/` shown outside opening hours.
    pub closed_page: String,
    /// Each weekday's open ranges, Monday first, sorted and never overlapping.
    pub week: [Vec<OpenHours>; 7],
    /// Dates whose ranges replace their weekday's (empty: closed all day).
    pub special_days: BTreeMap<CalendarDate, Vec<OpenHours>>,
}

/// One open time range of a day.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct OpenHours {
    /// First minute open, from midnight.
    pub from: u16,
    /// First minute closed again (`DAY_MINUTES` for midnight).
    pub to: u16,
    /// The home page in this range; `None`: the bundle's `home`.
    pub home: Option<String>,
    /// The attract loop in this range; `None`: `kiosk: attract`, if any.
    pub attract: Option<AttractLoop>,
}

/// A day of the calendar, as written `YYYY-MM-DD`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct CalendarDate {
    /// The year, e.g. 2025.
    pub year: u16,
    /// 1 to 12.
    pub month: u8,
    /// 1 to the month's length.
    pub day: u8,
}

impl CalendarDate {
    /// The date written `YYYY-MM-DD`, if it is a real day.
    pub fn parse(text: &str) -> Option<Self> {
        let mut parts = text.split('-');
        let (y, m, d) = (parts.next()?, parts.next()?, parts.next()?);
        if parts.next().is_some() || y.len() != 4 || m.len() != 2 || d.len() != 2 {
            return None;
        }
        let number = |t: &str| {
            t.bytes()
                .all(|b| b.is_ascii_digit())
                .then(|| t.parse().ok())?
        };
        let date = CalendarDate {
            year: number(y)?,
            month: u8::try_from(number(m)?).ok()?,
            day: u8::try_from(number(d)?).ok()?,
        };
        (date.day >= 1 && date.day <= date.month_days()).then_some(date)
    }

    fn month_days(self) -> u8 {
        let y = self.year;
        let leap = y.is_multiple_of(4) && (!y.is_multiple_of(100) || y.is_multiple_of(400));
        match self.month {
            1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
            4 | 6 | 9 | 11 => 30,
            2 if leap => 29,
            2 => 28,
            _ => 0,
        }
    }
}

impl fmt::Display for CalendarDate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:04}-{:02}-{:02}", self.year, self.month, self.day)
    }
}

impl Serialize for CalendarDate {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// A moment as the wall clock where the kiosk stands shows it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WallClock {
    /// Today.
    pub date: CalendarDate,
    /// Today's weekday, 0 for Monday.
    pub weekday: u8,
    /// Minutes since midnight.
    pub minute: u16,
}

impl WallClock {
    /// Now, in this machine's time zone (the `TZ` variable, else the system's).
    pub fn now() -> Self {
        let now = jiff::ZonedDateTime::now();
        let date = CalendarDate {
            year: u16::try_from(now.year()).unwrap_or(0),
            month: u8::try_from(now.month()).unwrap_or(1),
            day: u8::try_from(now.day()).unwrap_or(1),
        };
        let minute = i32::from(now.hour()) * 60 + i32::from(now.minute());
        WallClock {
            date,
            weekday: u8::try_from(now.weekday().to_monday_zero_offset()).unwrap_or(0),
            minute: u16::try_from(minute).unwrap_or(0),
        }
    }
}

impl WallClock {
    /// `minute` of `date`, its weekday worked out from the calendar.
    pub fn at(date: CalendarDate, minute: u16) -> Option<Self> {
        let day = jiff::civil::Date::new(
            i16::try_from(date.year).ok()?,
            i8::try_from(date.month).ok()?,
            i8::try_from(date.day).ok()?,
        )
        .ok()?;
        let weekday = u8::try_from(day.weekday().to_monday_zero_offset()).ok()?;
        (minute < DAY_MINUTES).then_some(WallClock {
            date,
            weekday,
            minute,
        })
    }

    /// The time written `YYYY-MM-DDTHH:MM`, if it is a real one.
    pub fn parse(text: &str) -> Option<Self> {
        let (date, time) = text.split_once('T')?;
        let (hh, mm) = time.split_once(':')?;
        let number = |t: &str| {
            (t.len() == 2 && t.bytes().all(|b| b.is_ascii_digit()))
                .then(|| t.parse::<u16>().ok())?
        };
        let (hh, mm) = (number(hh)?, number(mm)?);
        (hh < 24 && mm < 60).then_some(())?;
        WallClock::at(CalendarDate::parse(date)?, hh * 60 + mm)
    }

    /// Midnight of the next day.
    fn next_midnight(&self) -> Self {
        let d = self.date;
        let date = if d.day < d.month_days() {
            CalendarDate {
                day: d.day + 1,
                ..d
            }
        } else if d.month < 12 {
            CalendarDate {
                month: d.month + 1,
                day: 1,
                ..d
            }
        } else {
            CalendarDate {
                year: d.year.saturating_add(1),
                month: 1,
                day: 1,
            }
        };
        WallClock {
            date,
            weekday: (self.weekday + 1) % 7,
            minute: 0,
        }
    }
}

impl fmt::Display for WallClock {
    /// `YYYY-MM-DDTHH:MM`: ordered as text the way it is in time.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (hh, mm) = (self.minute / 60, self.minute % 60);
        write!(f, "{}T{hh:02}:{mm:02}", self.date)
    }
}

impl Serialize for WallClock {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl Schedule {
    /// The open ranges of `clock`'s day: its special day's if it has one, else its weekday's.
    pub fn hours_on(&self, clock: &WallClock) -> &[OpenHours] {
        match self.special_days.get(&clock.date) {
            Some(hours) => hours,
            None => &self.week[usize::from(clock.weekday % 7)],
        }
    }

    /// The range open at `clock`, if any (a range's end minute is already closed).
    pub fn open_at(&self, clock: &WallClock) -> Option<&OpenHours> {
        (self.hours_on(clock).iter()).find(|h| h.from <= clock.minute && clock.minute < h.to)
    }
}

/// What the touchscreen should show at a moment, by the schedule.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(tag = "state", rename_all = "lowercase")]
pub enum Showing<'a> {
    /// Open: this home page, and this attract loop when idle.
    Open {
        /// The home page.
        home: &'a str,
        /// The attract loop, if any.
        attract: Option<&'a AttractLoop>,
    },
    /// Closed: this page.
    Closed {
        /// The closed page.
        page: &'a str,
    },
}

/// What the touchscreen shows from a moment on: `GET /api/schedule`'s answer.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Timetable<'a> {
    /// What it shows at the moment asked about.
    pub showing: Showing<'a>,
    /// Each later change, in time order.
    pub changes: Vec<Change<'a>>,
    /// The end of the evaluated time: ask again before it.
    pub until: WallClock,
}

/// One change of what the touchscreen shows.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Change<'a> {
    /// When, on the kiosk's wall clock.
    pub at: WallClock,
    /// What it shows from then on.
    pub showing: Showing<'a>,
}

impl SiteConfig {
    /// What the touchscreen should show at `clock`: always open without a schedule.
    pub fn showing_at(&self, clock: &WallClock) -> Showing<'_> {
        let default_attract = self.kiosk.attract.as_ref();
        let Some(schedule) = &self.schedule else {
            return Showing::Open {
                home: &self.home,
                attract: default_attract,
            };
        };
        match schedule.open_at(clock) {
            Some(hours) => Showing::Open {
                home: hours.home.as_deref().unwrap_or(&self.home),
                attract: hours.attract.as_ref().or(default_attract),
            },
            None => Showing::Closed {
                page: &schedule.closed_page,
            },
        }
    }

    /// What the touchscreen shows from `from` on, evaluated for `days` whole days after
    /// `from`'s: the kiosk applies each change when its own clock reaches it, so it keeps to
    /// the hours while the server is away.
    pub fn timetable(&self, from: &WallClock, days: u16) -> Timetable<'_> {
        let showing = self.showing_at(from);
        let mut changes: Vec<Change<'_>> = Vec::new();
        let mut day = WallClock { minute: 0, ..*from };
        for _ in 0..=days {
            let mut minutes: Vec<u16> = (self.schedule.iter())
                .flat_map(|s| s.hours_on(&day).iter().flat_map(|h| [h.from, h.to]))
                .chain([0])
                .filter(|&m| m < DAY_MINUTES && (day.date != from.date || m > from.minute))
                .collect();
            minutes.sort_unstable();
            minutes.dedup();
            for minute in minutes {
                let at = WallClock { minute, ..day };
                let now = self.showing_at(&at);
                let last = changes.last().map_or(&showing, |c| &c.showing);
                if now != *last {
                    changes.push(Change { at, showing: now });
                }
            }
            day = day.next_midnight();
        }
        Timetable {
            showing,
            changes,
            until: day,
        }
    }

    /// The acts the kiosk itself may trigger: the idle act and every attract loop's act.
    pub fn kiosk_own_acts(&self) -> impl Iterator<Item = &str> {
        let schedule = self.schedule.iter().flat_map(|s| {
            (s.week.iter().flatten())
                .chain(s.special_days.values().flatten())
                .filter_map(|h| h.attract.as_ref())
        });
        (self.kiosk.idle_act.iter().map(String::as_str))
            .chain((self.kiosk.attract.iter().chain(schedule)).filter_map(|a| a.act.as_deref()))
    }
}

#[cfg(test)]
mod tests;
