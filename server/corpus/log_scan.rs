//! One event log read line by line, as `docent corpus` needs it: how many events of each
//! type, the first and the last (their time and session clock), and every line that is not
//! an event, by its line number. A line is read only as far as its stamps and type
//! (`docent_protocol::events::Head`): any object with a string `type` counts, so that a list
//! of a large corpus stays cheap; the first and last lines can be read whole
//! ([`LineStamp::event`]). A last line without its `\n` is the one a crash may cut
//! short (docs/CORPUS.md, "The last line after a kill"): it is set aside as incomplete, not
//! counted and not called damage; any other line that is not an event is damage.

use std::collections::BTreeMap;
use std::fmt;
use std::io::{self, BufRead};

use docent_protocol::events::{EventKind, Head, Line, LineEvent};

/// At most this many bad lines are kept one by one; the rest are only counted, so a file of
/// garbage cannot fill the memory with complaints.
const BAD_LINES_KEPT: usize = 20;

/// What one read of an event log found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LogScan {
    /// Whole event lines: each ends with `\n` and is a JSON object with a `type`.
    pub events: u64,
    /// Those events by `type`.
    pub by_type: BTreeMap<String, u64>,
    /// The first event.
    pub first: Option<LineStamp>,
    /// The last event.
    pub last: Option<LineStamp>,
    /// The first [`BAD_LINES_KEPT`] lines (other than an incomplete last one) that are not
    /// events.
    pub bad_lines: Vec<BadLine>,
    /// How many bad lines there are in all.
    pub bad_line_count: u64,
    /// The number of an incomplete last line (no `\n`), if the file ends with one.
    pub incomplete_last_line: Option<u64>,
}

/// What an event line says of its place in time.
#[derive(Clone, Debug, PartialEq)]
pub struct LineStamp {
    /// Its `type`.
    pub kind: String,
    /// Its wall-clock `time`, if it has one.
    pub time: Option<String>,
    /// Its `session_us`, if it has one (lines in a session's log do).
    pub session_us: Option<u64>,
    /// The line as written, without its `\n` (kept for the first and the last event).
    pub line: String,
}

impl LineStamp {
    /// The event, read whole through the protocol's types; `None` when its type is newer
    /// than this Docent's or its fields do not read.
    pub fn event(&self) -> Option<EventKind> {
        match Line::parse(self.line.as_bytes()).ok()?.event {
            LineEvent::Event(kind) => Some(kind),
            LineEvent::Newer(_) => None,
        }
    }
}

/// A line that is not an event, by its number (from 1).
#[derive(Clone, Debug, PartialEq)]
pub struct BadLine {
    /// Its line number, from 1.
    pub line: u64,
    /// What is wrong with it.
    pub fault: LineFault,
}

/// What is wrong with a line.
#[derive(Clone, Debug, PartialEq)]
pub enum LineFault {
    /// Nothing on it: Docent never writes an empty line.
    Empty,
    /// Not JSON: the parser stopped at this column (from 1).
    NotJson {
        /// Where the JSON parser stopped, from 1.
        column: usize,
    },
    /// JSON that stops in the middle: the line was cut short.
    CutShort {
        /// Its last column, from 1.
        column: usize,
    },
    /// JSON, but not an object with a string `type`.
    NotAnEvent,
}

impl fmt::Display for LineFault {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LineFault::Empty => write!(f, "an empty line"),
            LineFault::NotJson { column } => write!(f, "not JSON at column {column}"),
            LineFault::CutShort { column } => {
                write!(f, "a JSON line cut short at column {column}")
            }
            LineFault::NotAnEvent => write!(f, "JSON, but not an event (no `type`)"),
        }
    }
}

impl LogScan {
    /// Reads every line of `log`.
    pub fn read(mut log: impl BufRead) -> io::Result<LogScan> {
        let mut scan = LogScan::default();
        let mut bytes = Vec::new();
        // The last event's line, kept in one buffer rather than copied for every line.
        let mut last = Vec::new();
        let mut number = 0;
        loop {
            bytes.clear();
            if log.read_until(b'\n', &mut bytes)? == 0 {
                return Ok(scan.with_last_line(&last));
            }
            number += 1;
            let Some(line) = bytes.strip_suffix(b"\n") else {
                scan.incomplete_last_line = Some(number);
                return Ok(scan.with_last_line(&last));
            };
            match parse(line) {
                Ok(stamp) => {
                    scan.add(stamp, line);
                    last.clear();
                    last.extend_from_slice(line);
                }
                Err(fault) => scan.add_bad(number, fault),
            }
        }
    }

    fn add(&mut self, stamp: LineStamp, line: &[u8]) {
        self.events += 1;
        *self.by_type.entry(stamp.kind.clone()).or_default() += 1;
        if self.first.is_none() {
            let line = String::from_utf8_lossy(line).into_owned();
            self.first = Some(LineStamp {
                line,
                ..stamp.clone()
            });
        }
        self.last = Some(stamp);
    }

    /// The scan with its last event's line.
    fn with_last_line(mut self, line: &[u8]) -> LogScan {
        if let Some(last) = &mut self.last {
            last.line = String::from_utf8_lossy(line).into_owned();
        }
        self
    }

    fn add_bad(&mut self, line: u64, fault: LineFault) {
        self.bad_line_count += 1;
        if self.bad_lines.len() < BAD_LINES_KEPT {
            self.bad_lines.push(BadLine { line, fault });
        }
    }
}

fn parse(line: &[u8]) -> Result<LineStamp, LineFault> {
    if line.is_empty() {
        return Err(LineFault::Empty);
    }
    // serde_json checks the whole line's syntax, reading only the head's fields.
    let parsed = Head::parse(line).map_err(|e| match e.classify() {
        serde_json::error::Category::Data => LineFault::NotAnEvent,
        serde_json::error::Category::Eof => LineFault::CutShort {
            column: e.column().max(1),
        },
        _ => LineFault::NotJson {
            column: e.column().max(1),
        },
    })?;
    let kind = parsed.kind.ok_or(LineFault::NotAnEvent)?;
    Ok(LineStamp {
        kind,
        time: parsed.time,
        session_us: parsed.session_us,
        // Kept for the first and last events only (`LogScan::read`).
        line: String::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scan(text: &str) -> LogScan {
        LogScan::read(text.as_bytes()).unwrap()
    }

    #[test]
    fn events_are_counted_by_type_with_the_first_and_the_last() {
        let log = scan(concat!(
            r#"{"type":"session.started","time":"2026-11-24T10:15:02.629Z","session_us":0}"#,
            "\n",
            r#"{"type":"act.triggered","session_us":500}"#,
            "\n",
            r#"{"type":"act.triggered","session_us":900}"#,
            "\n",
            r#"{"type":"session.ended","session_us":1776}"#,
            "\n",
        ));
        assert_eq!(log.events, 4);
        assert_eq!(log.by_type["act.triggered"], 2);
        let first = log.first.unwrap();
        assert_eq!(first.time.as_deref(), Some("2026-11-24T10:15:02.629Z"));
        let last = log.last.unwrap();
        assert_eq!(
            (last.kind.as_str(), last.session_us),
            ("session.ended", Some(1776))
        );
        assert!(log.bad_lines.is_empty());
        assert_eq!(log.incomplete_last_line, None);
        assert_eq!(
            (first.line.as_str(), last.line.as_str()),
            (
                r#"{"type":"session.started","time":"2026-11-24T10:15:02.629Z","session_us":0}"#,
                r#"{"type":"session.ended","session_us":1776}"#
            )
        );
    }

    #[test]
    fn a_last_line_cut_short_is_set_aside_not_called_damage() {
        let log = scan("{\"type\":\"a\"}\n{\"type\":\"b\"}\n{\"ty");
        assert_eq!((log.events, log.incomplete_last_line), (2, Some(3)));
        assert_eq!(log.bad_line_count, 0);
    }

    #[test]
    fn a_bad_line_in_the_middle_is_damage_at_its_line_and_column() {
        let log = scan(concat!(
            "{\"type\":\"a\"}\n",
            "{\"type\":\"b\" oops}\n",
            "\n",
            "[1,2]\n",
            "{\"seq\":5}\n",
            "{\"type\":\"c\",\n",
            "{\"type\":\"d\"}\n",
        ));
        assert_eq!(log.events, 2);
        assert_eq!(log.bad_line_count, 5);
        let faults: Vec<(u64, String)> = (log.bad_lines.iter())
            .map(|b| (b.line, b.fault.to_string()))
            .collect();
        assert_eq!(
            faults,
            [
                (2, "not JSON at column 13".to_owned()),
                (3, "an empty line".to_owned()),
                (4, "JSON, but not an event (no `type`)".to_owned()),
                (5, "JSON, but not an event (no `type`)".to_owned()),
                (6, "a JSON line cut short at column 12".to_owned()),
            ]
        );
    }

    #[test]
    fn a_flood_of_bad_lines_is_counted_but_kept_only_in_part() {
        let log = scan(&"x\n".repeat(1000));
        assert_eq!(log.bad_line_count, 1000);
        assert_eq!(log.bad_lines.len(), BAD_LINES_KEPT);
    }
}
