//! The argument of a command as a typed value, parsed once when the bundle is loaded. The
//! dispatcher, the adapters and the browser pages (through the `args` of `command` frames) use
//! these values; nothing parses a command's text again, so the check and the run can never
//! disagree about what `WAIT 2s`, `SET_WAYPOINT 3 2 90` or a HIGHLIGHT area means.

use std::time::Duration;

use serde::{Serialize, Serializer};

use crate::duration::parse_duration;
use crate::highlight::{Area, parse_highlight};
use crate::language::Language;
use crate::media::sniff::{Kind, Support, by_extension};
use crate::model::Verb;

/// What the projector does with a `PROJECT` file, decided by its name's ending (the media
/// check makes sure the content matches).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MediaKind {
    /// Shown as a picture until something replaces it.
    Image,
    /// Played with its sound; the command is done when the film ends.
    Video,
}

/// The endings the projector shows as pictures, and as videos.
pub(crate) const PROJECTOR_IMAGES: &[&str] = &["png", "jpg", "jpeg", "gif", "webp", "svg"];
pub(crate) const PROJECTOR_VIDEOS: &[&str] = &["webm", "mp4", "ogv"];

impl MediaKind {
    /// The kind the projector gives `file`, or `None` for an ending it does not show. A
    /// format Docent converts (`.mpg`, `.tif`) is shown by what it becomes.
    pub fn of(file: &str) -> Option<MediaKind> {
        let ext = file.rsplit_once('.')?.1.to_ascii_lowercase();
        if PROJECTOR_IMAGES.contains(&ext.as_str()) {
            Some(MediaKind::Image)
        } else if PROJECTOR_VIDEOS.contains(&ext.as_str()) {
            Some(MediaKind::Video)
        } else {
            let format = by_extension(&ext).filter(|f| f.support == Support::Converted)?;
            Some(match format.kind {
                Kind::Image => MediaKind::Image,
                Kind::Video | Kind::Audio => MediaKind::Video,
            })
        }
    }
}

/// A command's argument, typed by its verb. Serialized as the `args` object of `command`
/// frames (docs/PROTOCOL.md): a compatibility boundary.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Args {
    /// `DRIVE_START`, `DRIVE_STOP`: nothing.
    None {},
    /// `SAY text`.
    Say {
        /// What to say.
        text: String,
        /// The language it is in (the dispatcher sets it: the visitor's language when the
        /// text was translated, else the bundle's default); the voice speaks in it.
        #[serde(skip_serializing_if = "Option::is_none")]
        language: Option<Language>,
    },
    /// `DISPLAY_PAGE page`.
    Page {
        /// The page, relative to `pages/`.
        page: String,
    },
    /// `PROJECT file`.
    Project {
        /// The file, relative to `media/`.
        file: String,
        /// Picture or video.
        kind: MediaKind,
    },
    /// `SET_WAYPOINT x y [heading]`.
    Waypoint {
        /// Metres.
        x: f64,
        /// Metres.
        y: f64,
        /// Degrees counter-clockwise from the x axis, if given.
        heading: Option<f64>,
    },
    /// `WAIT` (until the act's earlier commands are done) or `WAIT 2s` (a pause).
    Wait {
        /// The pause, in seconds on the wire; `None` for a plain `WAIT`.
        #[serde(rename = "seconds", serialize_with = "seconds")]
        pause: Option<Duration>,
    },
    /// `HIGHLIGHT areas`; no areas turns the light off.
    Highlight {
        /// The lit areas.
        areas: Vec<Area>,
    },
    /// A site verb's argument, as written (its adapter reads it).
    Site {
        /// The argument, if any.
        arg: Option<String>,
    },
}

impl Args {
    /// The typed argument of `verb` with the argument text `arg`, which the checker has
    /// accepted; `None` if it does not parse (a checker bug, reported as such).
    pub(crate) fn parse(verb: &Verb, arg: Option<&str>) -> Option<Args> {
        let text = || arg.map(str::to_owned);
        Some(match verb {
            Verb::Say => Args::Say {
                text: text()?,
                language: None,
            },
            Verb::DisplayPage => Args::Page { page: text()? },
            Verb::Project => {
                let file = text()?;
                let kind = MediaKind::of(&file)?;
                Args::Project { file, kind }
            }
            Verb::SetWaypoint => {
                let numbers: Vec<f64> = arg?
                    .split_whitespace()
                    .map(str::parse)
                    .collect::<Result<_, _>>()
                    .ok()?;
                match numbers[..] {
                    [x, y] => Args::Waypoint {
                        x,
                        y,
                        heading: None,
                    },
                    [x, y, heading] => Args::Waypoint {
                        x,
                        y,
                        heading: Some(heading),
                    },
                    _ => return None,
                }
            }
            Verb::DriveStart | Verb::DriveStop => Args::None {},
            Verb::Wait => Args::Wait {
                pause: match arg {
                    Some(text) => Some(parse_duration(text)?),
                    None => None,
                },
            },
            Verb::Highlight => Args::Highlight {
                areas: parse_highlight(arg.unwrap_or_default()).ok()?,
            },
            Verb::Site(_) => Args::Site { arg: text() },
        })
    }

    /// The language a `SAY` is in, when the dispatcher said.
    pub fn say_language(&self) -> Option<&Language> {
        match self {
            Args::Say { language, .. } => language.as_ref(),
            _ => None,
        }
    }

    /// The text to speak, for a `SAY`.
    pub fn say_text(&self) -> Option<&str> {
        match self {
            Args::Say { text, .. } => Some(text),
            _ => None,
        }
    }
}

fn seconds<S: Serializer>(pause: &Option<Duration>, serializer: S) -> Result<S::Ok, S::Error> {
    match pause {
        Some(pause) => serializer.serialize_some(&pause.as_secs_f64()),
        None => serializer.serialize_none(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::highlight::Shape;

    #[test]
    fn each_verb_gets_its_typed_argument() {
        let parse = |verb: Verb, arg: Option<&str>| Args::parse(&verb, arg);
        assert_eq!(
            parse(Verb::SetWaypoint, Some("3.5 2 90")),
            Some(Args::Waypoint {
                x: 3.5,
                y: 2.0,
                heading: Some(90.0)
            })
        );
        assert_eq!(
            parse(Verb::Wait, Some("1.5s")),
            Some(Args::Wait {
                pause: Some(Duration::from_millis(1500))
            })
        );
        assert_eq!(parse(Verb::Wait, None), Some(Args::Wait { pause: None }));
        assert_eq!(
            parse(Verb::Project, Some("Exhibit/film.WEBM")),
            Some(Args::Project {
                file: "Exhibit/film.WEBM".into(),
                kind: MediaKind::Video
            })
        );
        let Some(Args::Highlight { areas }) = parse(Verb::Highlight, Some("0 0 0.5 0.5 ellipse"))
        else {
            panic!("areas")
        };
        assert_eq!(areas[0].shape, Shape::Ellipse);
        assert_eq!(
            parse(Verb::Highlight, None),
            Some(Args::Highlight { areas: vec![] })
        );
        assert_eq!(parse(Verb::Project, Some("notes.txt")), None);
    }

    #[test]
    fn args_travel_as_plain_objects() {
        let json = |args: Args| serde_json::to_string(&args).expect("json");
        assert_eq!(
            json(Args::Wait {
                pause: Some(Duration::from_millis(2500))
            }),
            r#"{"seconds":2.5}"#
        );
        assert_eq!(json(Args::Wait { pause: None }), r#"{"seconds":null}"#);
        assert_eq!(json(Args::None {}), "{}");
        assert_eq!(
            json(Args::Project {
                file: "a.png".into(),
                kind: MediaKind::Image
            }),
            r#"{"file":"a.png","kind":"image"}"#
        );
    }
}
