//! The `kiosk:`, `projector:` and `corpus:` sections of `docent.yaml`: how the touchscreen and
//! projector shells behave (idle return home, idle act, what follows a video, the soft edge of
//! highlights) and how visitors' touches cut the corpus into sessions. Whether the idle act
//! exists is checked later, with the acts (`load.rs`); `attract:` is read by `attract.rs`.

use crate::Consent;
use crate::acts_file::yaml::{Kind, Node};
use crate::config::{AfterVideo, RecordLimits, RecordTracks, SessionStart, SiteConfig};
use crate::duration::parse_duration;
use crate::model::Located;
use crate::names::robot_event_name_problem;
use crate::size::parse_size;
use crate::suggest::did_you_mean;

use serde_json::{Value, json};

use super::Reader;
use super::attract;
use super::section::{Field, Limit, Section, Shape};
use super::shell_strings;

/// The settings of `kiosk:`.
pub(crate) const KIOSK: Section = Section {
    name: "kiosk",
    required: &[],
    fields: &[
        Field {
            key: "idle",
            description: "How long the touchscreen waits without a touch before it goes back \
                          to the home page, e.g. `2m` or `90s`; `0s` turns this off.",
            shape: Shape::Duration,
        },
        Field {
            key: "idle_act",
            description: "The label of the act to trigger when the touchscreen goes idle, \
                          e.g. `INVITE`.",
            shape: Shape::Pattern(r"^\S+$"),
        },
        Field {
            key: "leave_page_stops_speech",
            description: "Whether leaving a page stops the speech that page started (true \
                          unless set).",
            shape: Shape::Bool,
        },
        Field {
            key: "attract",
            description: attract::DESCRIPTION,
            shape: Shape::Nested(&attract::SECTION),
        },
        Field {
            key: "strings",
            description: shell_strings::DESCRIPTION,
            shape: Shape::Custom(shell_strings::schema),
        },
    ],
};
const IDLE_USAGE: &str = "`idle` is how long the touchscreen waits without a touch before it \
                          returns to the home page: a length of time with its unit, e.g. \
                          `idle: 2m` or `idle: 90s`; `idle: 0s` turns it off.";
/// The settings of `corpus:`.
pub(crate) const CORPUS: Section = Section {
    name: "corpus",
    required: &[],
    fields: &[
        Field {
            key: "session_start",
            description: "What starts a visitor session: `touch` (a visitor's first touch when \
                          none runs, or an operator's or dialog manager's mark; the default) \
                          or `marked` (only a mark).",
            shape: Shape::Choice(&["touch", "marked"]),
        },
        Field {
            key: "session_idle",
            description: "How long a session that a touch started goes on without a touch \
                          before it ends, e.g. `2m` (the default) or `90s`; `0s`: until it is \
                          marked ended.",
            shape: Shape::Duration,
        },
        Field {
            key: "session_start_events",
            description: "The robot events (sent by an adapter process on the robot, e.g. a \
                          people tracker's `person.near`) that start a visitor session when \
                          none runs and `session_start` is `touch`; such a session ends after \
                          `session_idle` like one a touch started. None by default.",
            shape: Shape::Custom(event_names_schema),
        },
        Field {
            key: "consent",
            description: "The consent each visitor session starts with: `recorded` (the \
                          default: the site records with notice, and an operator marks \
                          `declined` or `withdrawn` when visitors object) or `declined` \
                          (nothing is recorded until an operator marks `recorded`).",
            shape: Shape::Choice(&["recorded", "declined"]),
        },
        Field {
            key: "record",
            description: "What the kiosk device records during a session whose consent is \
                          `recorded`: `[audio]` (the default, its microphone), `[audio, \
                          video]` (and its camera), `[video]`, or `[]` or `none` for nothing.",
            shape: Shape::Custom(record_schema),
        },
        Field {
            key: "record_limits",
            description: "How much of the disk recordings may take; a chunk beyond a limit is \
                          refused, the recording stops and operators are told.",
            shape: Shape::Nested(&RECORD_LIMITS),
        },
    ],
};

/// The settings of `corpus: record_limits:`, each an amount of storage.
const RECORD_LIMITS: Section = Section {
    name: "record_limits",
    required: &[],
    fields: &[
        Field {
            key: "per_session",
            description: "All recordings of one visitor session together (default 4 GB).",
            shape: Shape::Custom(amount_schema),
        },
        Field {
            key: "per_kiosk",
            description: "One kiosk's recordings in one visitor session (default 2 GB).",
            shape: Shape::Custom(amount_schema),
        },
        Field {
            key: "keep_free",
            description: "Left free on the corpus's disk, so the event log can always be \
                          written (default 1 GB).",
            shape: Shape::Custom(amount_schema),
        },
    ],
};

/// The settings of `projector:`.
pub(crate) const PROJECTOR: Section = Section {
    name: "projector",
    required: &[],
    fields: &[
        Field {
            key: "after_video",
            description: "What the projector shows when a video ends: `black` (the default) or \
                          `hold` (its last picture).",
            shape: Shape::Choice(&["black", "hold"]),
        },
        Field {
            key: "highlight_edge",
            description: "How soft the edge of a HIGHLIGHT area is, as a fraction of the \
                          projected width: 0 (sharp) to 0.5, e.g. `0.02`.",
            shape: Shape::Number {
                min: Limit::Inclusive(0.0),
                max: Limit::Inclusive(0.5),
            },
        },
    ],
};
const RECORD_LIMITS_USAGE: &str = "is an amount of storage with its unit, e.g. `4 GB`, \
                                   `500 MB` or `1.5 GiB` (a bare number is refused).";
const START_EVENTS_USAGE: &str = "`session_start_events` lists the robot events (sent by an \
                                  adapter process, see docs/PROTOCOL.md) that start a visitor \
                                  session when none runs, e.g. `[person.near]`: names of \
                                  lower-case letters, digits, '.', '_' and '-'.";
const RECORD_USAGE: &str = "`record` lists what the kiosk device records during a visitor \
                            session whose consent is `recorded`: `[audio]` (the default), \
                            `[audio, video]`, `[video]`, or `[]` or `none` for nothing.";
const SESSION_IDLE_USAGE: &str = "`session_idle` is how long a visitor session that a touch \
                                  started goes on without a touch before it ends: a length of \
                                  time with its unit, e.g. `session_idle: 2m`; `0s` keeps it \
                                  going until it is marked ended.";
const HIGHLIGHT_EDGE_USAGE: &str = "`highlight_edge` is how soft the edge of a HIGHLIGHT area \
                                    is, as a fraction of the projected width: a number from 0 \
                                    (a sharp edge) to 0.5, e.g. `highlight_edge: 0.02`.";
const IDLE_ACT_USAGE: &str = "`idle_act` is the label of the act to trigger when the \
                              touchscreen goes idle, e.g. `idle_act: INVITE`.";

impl Reader {
    /// Reads `kiosk:` into `config.kiosk`; returns the idle act with its place.
    pub(super) fn kiosk(
        &mut self,
        node: &Node,
        config: &mut SiteConfig,
    ) -> Option<Located<String>> {
        let mut idle_act = None;
        for (field, value) in self.entries(node, &KIOSK) {
            let key = field.key;
            if key == "leave_page_stops_speech" {
                let what = "`leave_page_stops_speech`";
                if let Some(stops) = self.pick(value, what, &field.shape, &[true, false]) {
                    config.kiosk.leave_page_stops_speech = stops;
                }
                continue;
            }
            if key == "attract" {
                config.kiosk.attract = self.attract(value);
                continue;
            }
            if key == "strings" {
                config.kiosk.strings = self.shell_strings(value);
                continue;
            }
            if key == "idle" {
                if let Some(idle) = self.setting(value, IDLE_USAGE, parse_duration) {
                    config.kiosk.idle = idle;
                }
                continue;
            }
            let label = |t: &str| (!t.chars().any(char::is_whitespace)).then(|| t.to_owned());
            if let Some(act) = self.setting(value, IDLE_ACT_USAGE, label) {
                config.kiosk.idle_act = Some(act.clone());
                idle_act = Some(Located {
                    value: act,
                    pos: value.pos.clone(),
                });
            }
        }
        idle_act
    }

    /// Reads `corpus:` into `config.corpus`.
    pub(super) fn corpus(&mut self, node: &Node, config: &mut SiteConfig) {
        for (field, value) in self.entries(node, &CORPUS) {
            let key = field.key;
            if key == "session_idle" {
                if let Some(idle) = self.setting(value, SESSION_IDLE_USAGE, parse_duration) {
                    config.corpus.session_idle = idle;
                }
                continue;
            }
            if key == "session_start_events" {
                if let Some(names) = self.robot_event_names(value) {
                    config.session_start_events = names;
                }
                continue;
            }
            if key == "record" {
                if let Some(record) = self.record(value) {
                    config.corpus.record = record;
                }
                continue;
            }
            if key == "record_limits" {
                self.record_limits(value, &mut config.corpus.record_limits);
                continue;
            }
            if key == "consent" {
                let options = [Consent::Recorded, Consent::Declined];
                if let Some(consent) = self.pick(value, "`consent`", &field.shape, &options) {
                    config.corpus.consent = consent;
                }
                continue;
            }
            let options = [SessionStart::Touch, SessionStart::Marked];
            if let Some(start) = self.pick(value, "`session_start`", &field.shape, &options) {
                config.corpus.session_start = start;
            }
        }
    }

    /// Reads `corpus: record_limits:`: each limit an amount of storage.
    fn record_limits(&mut self, node: &Node, limits: &mut RecordLimits) {
        for (field, value) in self.entries(node, &RECORD_LIMITS) {
            let key = field.key;
            let usage = format!("`record_limits: {key}` {RECORD_LIMITS_USAGE}");
            let Some(bytes) = self.setting(value, &usage, parse_size) else {
                continue;
            };
            match key {
                "per_session" => limits.per_session = bytes,
                "per_kiosk" => limits.per_kiosk = bytes,
                _ => limits.keep_free = bytes,
            }
        }
    }

    /// Reads `corpus: session_start_events:`: a list of robot event names, each once.
    fn robot_event_names(&mut self, node: &Node) -> Option<Vec<String>> {
        let Kind::Seq(items) = &node.kind else {
            self.bad(node, START_EVENTS_USAGE);
            return None;
        };
        let mut names: Vec<String> = Vec::new();
        for item in items {
            let name = item.as_text().map(str::trim).unwrap_or_default();
            if let Some(problem) = robot_event_name_problem(name) {
                self.bad(item, &format!("{START_EVENTS_USAGE} Here: {problem}."));
                return None;
            }
            if names.iter().any(|n| n == name) {
                self.bad(item, "This event is listed twice. Keep one.");
                return None;
            }
            names.push(name.to_owned());
        }
        Some(names)
    }

    /// Reads `corpus: record:`: a list of `audio` and `video`, `[]` or `none`.
    fn record(&mut self, node: &Node) -> Option<RecordTracks> {
        let items: Vec<&Node> = match &node.kind {
            Kind::Seq(items) => items.iter().collect(),
            _ if node.as_text().map(str::trim) == Some("none") => return Some(RecordTracks::OFF),
            _ => {
                self.bad(node, RECORD_USAGE);
                return None;
            }
        };
        let mut tracks = RecordTracks::OFF;
        for item in items {
            let word = item.as_text().map(str::trim).unwrap_or_default();
            let track = match word {
                "audio" => &mut tracks.audio,
                "video" => &mut tracks.video,
                _ => {
                    let hint = did_you_mean(word, ["audio", "video"]);
                    self.bad(item, &format!("{RECORD_USAGE}{hint}"));
                    return None;
                }
            };
            if *track {
                self.bad(item, "This track is listed twice. Keep one.");
                return None;
            }
            *track = true;
        }
        Some(tracks)
    }

    /// Reads `projector:` into `config.projector`.
    pub(super) fn projector(&mut self, node: &Node, config: &mut SiteConfig) {
        for (field, value) in self.entries(node, &PROJECTOR) {
            if field.key == "highlight_edge" {
                let edge = |t: &str| t.parse::<f64>().ok().filter(|e| (0.0..=0.5).contains(e));
                if let Some(edge) = self.setting(value, HIGHLIGHT_EDGE_USAGE, edge) {
                    config.projector.highlight_edge = edge;
                }
                continue;
            }
            let options = [AfterVideo::Black, AfterVideo::Hold];
            let what = "projector's `after_video`";
            if let Some(after) = self.pick(value, what, &field.shape, &options) {
                config.projector.after_video = after;
            }
        }
    }
}

/// A list of robot event names, each once.
fn event_names_schema(description: &'static str) -> Value {
    json!({
        "description": description,
        "type": "array",
        "uniqueItems": true,
        "items": { "type": "string", "pattern": "^[a-z][a-z0-9._-]{0,63}$" },
    })
}

/// `none` or a list of `audio` and `video`.
fn record_schema(description: &'static str) -> Value {
    json!({
        "description": description,
        "anyOf": [
            { "const": "none" },
            {
                "type": "array",
                "uniqueItems": true,
                "items": { "enum": ["audio", "video"] },
            },
        ],
    })
}

/// An amount of storage with its unit, as `size.rs` parses it: the schema's pattern.
pub(super) const AMOUNT_PATTERN: &str = r"^\s*(\d+(\.\d*)?|\.\d+)\s*([bB]|[kKmMgGtT][iI]?[bB])\s*$";

/// An amount of storage with its unit, as `size.rs` parses it.
fn amount_schema(description: &'static str) -> Value {
    json!({
        "type": "string",
        "pattern": AMOUNT_PATTERN,
        "description": format!(
            "{description} An amount with its unit: `4 GB`, `500 MB`, `1.5 GiB`."
        ),
        "examples": ["4 GB", "500 MB"],
    })
}

#[cfg(test)]
mod tests {
    use crate::config_file::test_support::parse;

    use std::time::Duration;

    use crate::config::{AfterVideo, RecordLimits, RecordTracks};

    #[test]
    fn kiosk_and_projector_settings_are_read() {
        let file =
            parse("kiosk:\n  idle: 90s\n  idle_act: INVITE\nprojector:\n  after_video: hold\n");
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        assert_eq!(file.config.kiosk.idle, Duration::from_secs(90));
        assert_eq!(file.config.kiosk.idle_act.as_deref(), Some("INVITE"));
        let act = file.idle_act.expect("idle act located");
        assert_eq!(
            (act.value.as_str(), act.pos.line, act.pos.column),
            ("INVITE", 3, 13)
        );
        assert_eq!(file.config.projector.after_video, AfterVideo::Hold);
        assert_eq!(file.config.projector.highlight_edge, 0.02);
    }

    #[test]
    fn the_highlight_edge_is_a_fraction_up_to_a_half() {
        let edge = |text: &str| parse(text).config.projector.highlight_edge;
        assert_eq!(edge("projector: { highlight_edge: 0.05 }\n"), 0.05);
        assert_eq!(edge("projector: { highlight_edge: 0 }\n"), 0.0);
        assert_eq!(edge("projector: { highlight_edge: 0.5 }\n"), 0.5);
        for bad in ["0.6", "-0.01", "soft", "2%", ".nan"] {
            let file = parse(&format!("projector:\n  highlight_edge: {bad}\n"));
            let located: Vec<_> = file
                .diagnostics
                .iter()
                .map(|d| (d.code.as_str(), d.line, d.column))
                .collect();
            assert_eq!(located, [("config-bad-value", 2, 19)], "{bad}");
            assert!(
                file.diagnostics[0]
                    .message
                    .contains("from 0 (a sharp edge) to 0.5"),
                "{bad}: {}",
                file.diagnostics[0].message
            );
            assert_eq!(file.config.projector.highlight_edge, 0.02, "default kept");
        }
    }

    #[test]
    fn record_limits_are_amounts_with_units_and_a_bad_one_keeps_its_default() {
        let limits = |text: &str| parse(text).config.corpus.record_limits;
        assert_eq!(limits("corpus: {}\n"), RecordLimits::default());
        let set = limits(
            "corpus:\n  record_limits: {per_session: 2 GB, per_kiosk: 500 MB, keep_free: 1.5 GiB}\n",
        );
        assert_eq!(
            set,
            RecordLimits {
                per_session: 2_000_000_000,
                per_kiosk: 500_000_000,
                keep_free: 1_610_612_736,
            }
        );
        let file = parse("corpus:\n  record_limits: {per_session: 2000}\n");
        assert_eq!(file.config.corpus.record_limits, RecordLimits::default());
        let problem = &file.diagnostics[0];
        assert_eq!(
            (problem.code.as_str(), problem.line),
            ("config-bad-value", 2),
            "{problem:?}"
        );
        assert!(problem.message.contains("`4 GB`"), "{}", problem.message);
        let typo = parse("corpus:\n  record_limits: {per_sesion: 2 GB}\n");
        assert!(
            typo.diagnostics[0].message.contains("per_session"),
            "{:?}",
            typo.diagnostics
        );
    }

    #[test]
    fn corpus_record_lists_the_tracks_and_a_bad_one_is_located() {
        let record = |text: &str| parse(text).config.corpus.record;
        let audio = RecordTracks {
            audio: true,
            video: false,
        };
        assert_eq!(record("corpus: {}\n"), audio, "audio by default");
        assert_eq!(record("corpus: { record: [audio] }\n"), audio);
        let both = record("corpus:\n  record: [audio, video]\n");
        assert!(both.audio && both.video);
        assert_eq!(record("corpus: { record: [] }\n"), RecordTracks::OFF);
        assert_eq!(record("corpus: { record: none }\n"), RecordTracks::OFF);
        for (text, column) in [
            ("corpus:\n  record: [audio, vidoe]\n", 19),
            ("corpus:\n  record: audio\n", 11),
            ("corpus:\n  record: [audio, audio]\n", 19),
        ] {
            let file = parse(text);
            let located: Vec<_> = (file.diagnostics.iter())
                .map(|d| (d.code.as_str(), d.line, d.column))
                .collect();
            assert_eq!(located, [("config-bad-value", 2, column)], "{text}");
            assert_eq!(file.config.corpus.record, audio, "default kept: {text}");
        }
        let typo = parse("corpus:\n  record: [vidoe]\n");
        assert!(
            typo.diagnostics[0]
                .message
                .contains("Did you mean `video`?")
        );
    }

    #[test]
    fn corpus_session_start_events_are_robot_event_names_each_once() {
        let events = |text: &str| parse(text).config.session_start_events;
        assert!(events("corpus: {}\n").is_empty(), "none by default");
        assert_eq!(
            events("corpus:\n  session_start_events: [person.near, bumper]\n"),
            ["person.near", "bumper"]
        );
        for (text, column, says) in [
            (
                "corpus:\n  session_start_events: [Person Near]\n",
                26,
                "lower-case",
            ),
            (
                "corpus:\n  session_start_events: person.near\n",
                25,
                "lists the robot events",
            ),
            (
                "corpus:\n  session_start_events: [a, a]\n",
                29,
                "listed twice",
            ),
        ] {
            let file = parse(text);
            let located: Vec<_> = (file.diagnostics.iter())
                .map(|d| (d.code.as_str(), d.line, d.column))
                .collect();
            assert_eq!(located, [("config-bad-value", 2, column)], "{text}");
            assert!(file.diagnostics[0].message.contains(says), "{text}");
            assert!(file.config.session_start_events.is_empty(), "default kept");
        }
    }

    #[test]
    fn defaults_are_two_minutes_no_act_and_black() {
        let file = parse("kiosk:\nprojector:\n");
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        assert_eq!(file.config.kiosk.idle, Duration::from_secs(120));
        assert_eq!(file.config.kiosk.idle_act, None);
        assert_eq!(file.config.projector.after_video, AfterVideo::Black);
        assert_eq!(
            parse("kiosk: { idle: 0s }\n").config.kiosk.idle,
            Duration::ZERO
        );
    }

    #[test]
    fn bad_values_are_located_and_defaults_kept() {
        let file = parse(
            "kiosk:\n  idle: 120\n  idle_act: two words\n  idel: 1m\nprojector:\n  after_video: blak\n",
        );
        let located: Vec<_> = file
            .diagnostics
            .iter()
            .map(|d| (d.code.as_str(), d.line, d.column))
            .collect();
        assert_eq!(
            located,
            [
                ("config-unknown-key", 4, 3),
                ("config-bad-value", 2, 9),
                ("config-bad-value", 3, 13),
                ("config-bad-value", 6, 16),
            ]
        );
        assert!(file.diagnostics[0].message.contains("Did you mean `idle`?"));
        assert!(
            file.diagnostics[3]
                .message
                .contains("Did you mean `black`?")
        );
        assert_eq!(file.config.kiosk.idle, Duration::from_secs(120));
        assert_eq!(file.config.projector.after_video, AfterVideo::Black);
        assert!(file.idle_act.is_none());
    }
}
