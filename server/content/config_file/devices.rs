//! The device sections of `docent.yaml`: `speech:` (adapter, voice, rate, longest text) and
//! `drive:` (adapter, speed, pose rate, bounds). Separate from the top level because each
//! value here has its own range and wording for the author.

use crate::acts_file::yaml::{Kind, Node};
use crate::config::{AdapterKind, Bounds, Language, SiteConfig};
use crate::model::Located;

use super::Reader;

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
        const KEYS: [&str; 5] = ["adapter", "voice", "voices", "rate", "max_seconds"];
        for (key, value) in self.entries(node, &KEYS, "speech") {
            match key {
                "adapter" => {
                    let kinds = [
                        ("espeak", AdapterKind::Espeak),
                        ("log", AdapterKind::Log),
                        ("ws", AdapterKind::Ws),
                        ("browser", AdapterKind::Browser),
                    ];
                    speech.adapter = self
                        .choice(value, "speech adapter", &kinds)
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
        for (key, value) in
            self.entries(node, &["adapter", "speed", "pose_rate", "bounds"], "drive")
        {
            match key {
                "adapter" => {
                    let kinds = [
                        ("sim", AdapterKind::DriveSim),
                        ("ws", AdapterKind::Ws),
                        ("rosbridge", AdapterKind::Rosbridge),
                    ];
                    if let Some(kind) = self.choice(value, "drive adapter", &kinds) {
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
        const KEYS: &[&str] = &["min_x", "min_y", "max_x", "max_y"];
        let mut values = [None; 4];
        let mut all_numbers = true;
        for (key, value) in self.entries(node, KEYS, "bounds") {
            let index = KEYS.iter().position(|k| *k == key)?;
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
