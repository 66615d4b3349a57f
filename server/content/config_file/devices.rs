//! The device sections of `docent.yaml`: `speech:` (adapter, voice, rate, longest text) and
//! `drive:` (adapter, speed, pose rate, bounds). Separate from the top level because each
//! value here has its own range and wording for the author.

use crate::acts_file::yaml::{Kind, Node};
use crate::config::{AdapterKind, Bounds, Language, SiteConfig};
use crate::model::Located;

use serde_json::{Value, json};

use super::Reader;
use super::languages::LANGUAGE_PATTERN;
use super::section::{Field, Limit, Section, Shape};

/// An espeak-ng voice name, as [`is_voice_name`] accepts it.
const VOICE_PATTERN: &str = "^[A-Za-z0-9+_/][A-Za-z0-9+_/-]*$";

/// The settings of `speech:`.
pub(crate) const SPEECH: Section = Section {
    name: "speech",
    required: &[],
    fields: &[
        Field {
            key: "adapter",
            description: "Who speaks: `espeak` (this computer's speech synthesiser), `browser` \
                          (the touchscreen's browser), `ws` (a program connected over the \
                          websocket) or `log` (nobody: speech is only written to the log).",
            shape: Shape::Choice(&["espeak", "log", "ws", "browser"]),
        },
        Field {
            key: "voice",
            description: "The voice: a language such as `en`, `en-us` or `de`.",
            shape: Shape::Pattern(VOICE_PATTERN),
        },
        Field {
            key: "voices",
            description: "The espeak-ng voice of each language, e.g. `{en: en-gb, de: de}`. A \
                          language without one speaks with the voice named like it (the \
                          default language with `voice`, when that is written).",
            shape: Shape::Custom(voices_schema),
        },
        Field {
            key: "rate",
            description: "Speaking speed in words per minute, from 40 to 600, e.g. `160`.",
            shape: Shape::Integer { min: 40, max: 600 },
        },
        Field {
            key: "max_seconds",
            description: "The longest one text may take to say, in seconds (30 unless set). \
                          `docent check` warns above it, and refuses texts over four times as \
                          long.",
            shape: Shape::Integer { min: 1, max: 3600 },
        },
    ],
};

/// The settings of `drive:`.
pub(crate) const DRIVE: Section = Section {
    name: "drive",
    required: &[],
    fields: &[
        Field {
            key: "adapter",
            description: "Who drives: `sim` (a simulated robot, for trying things out), `ws` \
                          (the real robot's program, connected over the websocket) or \
                          `rosbridge` (a ROS 2 robot through a rosbridge server, see \
                          `rosbridge:`).",
            shape: Shape::Choice(&["sim", "ws", "rosbridge"]),
        },
        Field {
            key: "speed",
            description: "The simulated driving speed in metres per second, e.g. `0.5`.",
            shape: Shape::Number {
                min: Limit::Exclusive(0.0),
                max: Limit::Open,
            },
        },
        Field {
            key: "pose_rate",
            description: "How many position updates per second the simulated robot sends (at \
                          most 50), e.g. `5`.",
            shape: Shape::Number {
                min: Limit::Exclusive(0.0),
                max: Limit::Inclusive(50.0),
            },
        },
        Field {
            key: "bounds",
            description: "The area the robot drives in, in metres: `{ min_x: 0, min_y: 0, \
                          max_x: 20, max_y: 12 }`.",
            shape: Shape::Nested(&BOUNDS),
        },
    ],
};

/// Any number.
const METRES: Shape = Shape::Number {
    min: Limit::Open,
    max: Limit::Open,
};

/// The settings of `drive: bounds:`, all four needed.
const BOUNDS: Section = Section {
    name: "bounds",
    required: &["min_x", "min_y", "max_x", "max_y"],
    fields: &[
        Field {
            key: "min_x",
            description: "`min_x`: in metres; each min below its max.",
            shape: METRES,
        },
        Field {
            key: "min_y",
            description: "`min_y`: in metres; each min below its max.",
            shape: METRES,
        },
        Field {
            key: "max_x",
            description: "`max_x`: in metres; each min below its max.",
            shape: METRES,
        },
        Field {
            key: "max_y",
            description: "`max_y`: in metres; each min below its max.",
            shape: METRES,
        },
    ],
};

/// Language → espeak-ng voice.
fn voices_schema(description: &'static str) -> Value {
    json!({
        "type": "object",
        "propertyNames": { "pattern": LANGUAGE_PATTERN },
        "additionalProperties": { "type": "string", "pattern": VOICE_PATTERN },
        "description": description,
    })
}

const VOICE_USAGE: &str = "`voice` is an espeak-ng voice name such as `en`, `en-us` or `de`.";
const MAX_SECONDS_USAGE: &str = "`max_seconds` is the longest a single text may take to say, \
                                 in seconds: a whole number from 1 to 3600, e.g. \
                                 `max_seconds: 45`.";
const RATE_USAGE: &str = "`rate` is the speaking speed in words per minute: a whole number \
                          from 40 to 600, e.g. `rate: 160`.";
const SPEED_USAGE: &str = "`speed` is the simulated driving speed in metres per second: a \
                           number above 0, e.g. `speed: 0.5`.";
const POSE_RATE_USAGE: &str = "`pose_rate` is how many position updates per second the \
                               simulated drive sends: above 0 and at most 50, e.g. `pose_rate: 5`.";
const BOUNDS_USAGE: &str = "`bounds` needs four numbers in metres, each min below its max, \
                            e.g. `bounds: { min_x: 0, min_y: 0, max_x: 20, max_y: 12 }`.";

/// An espeak-ng voice is passed as a process argument: a plain name, never an option.
fn is_voice_name(name: &str) -> bool {
    !name.is_empty()
        && !name.starts_with('-')
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "-+_/".contains(c))
}

fn positive(text: &str) -> Option<f64> {
    text.parse::<f64>()
        .ok()
        .filter(|n| n.is_finite() && *n > 0.0)
}

impl Reader {
    /// `speech:`; returns its `voices:`, settled once `languages:` is known.
    pub(super) fn speech(
        &mut self,
        node: &Node,
        config: &mut SiteConfig,
    ) -> Vec<(Located<Language>, String)> {
        let speech = &mut config.speech;
        let mut voices = Vec::new();
        for (field, value) in self.entries(node, &SPEECH) {
            match field.key {
                "adapter" => {
                    let kinds = [
                        AdapterKind::Espeak,
                        AdapterKind::Log,
                        AdapterKind::Ws,
                        AdapterKind::Browser,
                    ];
                    speech.adapter = self
                        .pick(value, "speech adapter", &field.shape, &kinds)
                        .or(speech.adapter);
                }
                "voice" => {
                    let parse = |t: &str| is_voice_name(t).then(|| t.to_owned());
                    if let Some(voice) = self.setting(value, VOICE_USAGE, parse) {
                        speech.voice = voice;
                    }
                }
                "voices" => voices = self.voices(value, is_voice_name),
                "max_seconds" => {
                    let parse = |t: &str| t.parse::<u32>().ok().filter(|s| (1..=3600).contains(s));
                    if let Some(seconds) = self.setting(value, MAX_SECONDS_USAGE, parse) {
                        speech.max_seconds = seconds;
                    }
                }
                _ => {
                    let parse = |t: &str| t.parse::<u32>().ok().filter(|r| (40..=600).contains(r));
                    if let Some(rate) = self.setting(value, RATE_USAGE, parse) {
                        speech.rate_wpm = rate;
                    }
                }
            }
        }
        voices
    }

    pub(super) fn drive(&mut self, node: &Node, config: &mut SiteConfig) {
        let drive = &mut config.drive;
        for (field, value) in self.entries(node, &DRIVE) {
            match field.key {
                "adapter" => {
                    let kinds = [
                        AdapterKind::DriveSim,
                        AdapterKind::Ws,
                        AdapterKind::Rosbridge,
                    ];
                    if let Some(kind) = self.pick(value, "drive adapter", &field.shape, &kinds) {
                        drive.adapter = kind;
                    }
                }
                "speed" => {
                    if let Some(speed) = self.setting(value, SPEED_USAGE, positive) {
                        drive.speed = speed;
                    }
                }
                "pose_rate" => {
                    let parse = |t: &str| positive(t).filter(|r| *r <= 50.0);
                    if let Some(rate) = self.setting(value, POSE_RATE_USAGE, parse) {
                        drive.pose_hz = rate;
                    }
                }
                _ => drive.bounds = self.bounds(value).or(drive.bounds),
            }
        }
    }

    pub(super) fn bounds(&mut self, node: &Node) -> Option<Bounds> {
        let mut values = [None; 4];
        let mut all_numbers = true;
        for (field, value) in self.entries(node, &BOUNDS) {
            let index = BOUNDS.fields.iter().position(|f| f.key == field.key)?;
            values[index] = self.setting(value, BOUNDS_USAGE, |t| {
                t.parse::<f64>().ok().filter(|n| n.is_finite())
            });
            all_numbers &= values[index].is_some();
        }
        let [Some(min_x), Some(min_y), Some(max_x), Some(max_y)] = values else {
            // A key left out; wrong values and wrong shapes were reported already.
            if all_numbers && matches!(node.kind, Kind::Map(_)) {
                self.bad(node, BOUNDS_USAGE);
            }
            return None;
        };
        if min_x >= max_x || min_y >= max_y {
            self.bad(node, BOUNDS_USAGE);
            return None;
        }
        Some(Bounds {
            min_x,
            min_y,
            max_x,
            max_y,
        })
    }
}
