//! The tiers ELAN and Praat both get, laid out once from a [`Timeline`] so that the EAF and
//! the TextGrid of a session have the same tiers, names and values: `speech` (with its `act`
//! labels), `commands`, `pages`, `touches` and `marks`. No interval tier may hold overlapping
//! intervals (praatio refuses them, Praat takes them silently, ELAN cannot show them), so
//! intervals that would overlap go to numbered tiers (`commands-2`, `speech-2` with `act-2`)
//! rather than being dropped or overlapped. An interval shorter than [`MIN_INTERVAL_US`] is
//! drawn that long, so that every tool can show it; a point takes as much room on its tier,
//! because ELAN draws it as a 1 ms annotation. Researchers' annotations (`annotations.jsonl`)
//! follow as tiers of their own, two per codebook tier: its intervals (`situation`,
//! `situation-2`, ...) and its points (`situation-points`, ...), each with the tier's codes as
//! its vocabulary.

use crate::annotations::Annotation as Coded;
use crate::export::timeline::{CommandRun, Marked, Outcome, Timeline, Touched};
use docent_content::config::Codebook;

/// The shortest interval drawn, and the room a point takes: 1 ms, ELAN's time unit.
pub const MIN_INTERVAL_US: u64 = 1_000;

/// The robot's utterances: the text said.
pub const SPEECH: &str = "speech";
/// The label of the act each utterance belongs to (EAF: a child tier of `speech`).
pub const ACT: &str = "act";
/// The other commands: `VERB argument` and how it ended.
pub const COMMANDS: &str = "commands";
/// The page the touchscreen showed.
pub const PAGES: &str = "pages";
/// The visitors' touches: acts triggered, refused, pages followed.
pub const TOUCHES: &str = "touches";
/// The operator's marks: dialog situations, visitor groups.
pub const MARKS: &str = "marks";

/// A labelled stretch of the session clock.
#[derive(Clone, Debug, PartialEq)]
pub struct Annotation {
    /// Start, microseconds on the session clock.
    pub start_us: u64,
    /// End, at least [`MIN_INTERVAL_US`] after the start.
    pub end_us: u64,
    /// What it says.
    pub value: String,
}

/// A tier of intervals that never overlap, sorted by start.
#[derive(Clone, Debug, PartialEq)]
pub struct IntervalTier {
    /// `commands`, `commands-2`, ...
    pub name: String,
    /// Its intervals.
    pub annotations: Vec<Annotation>,
}

/// A `speech` tier and the act labels of its utterances (one label per annotation).
#[derive(Clone, Debug, PartialEq)]
pub struct SpeechTier {
    /// The utterances.
    pub speech: IntervalTier,
    /// The name of the act tier beside it: `act`, `act-2`, ...
    pub act: String,
    /// The act label of each utterance, in the same order.
    pub labels: Vec<String>,
}

/// A labelled instant.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// Microseconds on the session clock.
    pub at_us: u64,
    /// What happened.
    pub value: String,
}

/// A tier of points at least [`MIN_INTERVAL_US`] apart, sorted.
#[derive(Clone, Debug, PartialEq)]
pub struct PointTier {
    /// `touches`, `touches-2`, ...
    pub name: String,
    /// Its points.
    pub points: Vec<Point>,
}

/// Every tier of a session, in the order the files list them.
#[derive(Clone, Debug, PartialEq)]
pub struct Tiers {
    /// The end of every tier: the session's end, or the end of a last interval drawn longer.
    pub end_us: u64,
    /// `speech` and `act`, then `speech-2` and `act-2`, ...
    pub speech: Vec<SpeechTier>,
    /// `commands`, `commands-2`, ...
    pub commands: Vec<IntervalTier>,
    /// `pages`, `pages-2`, ...
    pub pages: Vec<IntervalTier>,
    /// `touches`, ...
    pub touches: Vec<PointTier>,
    /// `marks`, ...
    pub marks: Vec<PointTier>,
    /// The researchers' annotations, one entry per codebook tier.
    pub coded: Vec<CodedTier>,
}

/// The annotations of one codebook tier.
#[derive(Clone, Debug, PartialEq)]
pub struct CodedTier {
    /// The codebook tier's name.
    pub name: String,
    /// Its codes (the vocabulary): the codebook's, then any other code its annotations use.
    pub codes: Vec<String>,
    /// Its intervals: `NAME`, `NAME-2`, ...
    pub intervals: Vec<IntervalTier>,
    /// Its points: `NAME-points`, `NAME-points-2`, ...
    pub points: Vec<PointTier>,
}

/// The suffix of a codebook tier's point tier.
pub const POINTS: &str = "-points";

impl Tiers {
    /// Lays `timeline` out as tiers. The first tier of each kind is always there, empty or not.
    pub fn of(timeline: &Timeline) -> Tiers {
        let utterances = (timeline.utterances.iter())
            .map(|u| (annotation(u.start_us, u.end_us, &u.text), u.label.clone()));
        let speech = spread(utterances, |(a, _)| (a.start_us, a.end_us));
        let speech = (speech.into_iter().enumerate())
            .map(|(n, tier)| {
                let (annotations, labels) = tier.into_iter().unzip();
                SpeechTier {
                    speech: IntervalTier {
                        name: numbered(SPEECH, n),
                        annotations,
                    },
                    act: numbered(ACT, n),
                    labels,
                }
            })
            .collect();
        let commands =
            (timeline.commands.iter()).map(|c| annotation(c.start_us, c.end_us, &command_value(c)));
        let pages = (timeline.pages.iter()).map(|p| annotation(p.start_us, p.end_us, &p.page));
        let touches = (timeline.touches.iter()).map(|t| Point {
            at_us: t.at_us,
            value: touch_value(&t.what),
        });
        let marks = (timeline.marks.iter()).map(|m| Point {
            at_us: m.at_us,
            value: match &m.what {
                Marked::Situation(situation) => format!("situation: {situation}"),
                Marked::Note(text) => format!("note: {text}"),
                Marked::Group(group) => format!("group: {group}"),
            },
        });
        let mut tiers = Tiers {
            end_us: timeline.end_us,
            speech,
            commands: interval_tiers(COMMANDS, commands),
            pages: interval_tiers(PAGES, pages),
            touches: point_tiers(TOUCHES, touches),
            marks: point_tiers(MARKS, marks),
            coded: Vec::new(),
        };
        tiers.end_us = tiers.latest().max(timeline.end_us).max(MIN_INTERVAL_US);
        tiers
    }

    /// Adds the researchers' `annotations` as tiers: one pair per tier of `codebook`, then
    /// one for any other tier the annotations name (a tier since taken out of the codebook
    /// keeps its annotations).
    pub fn with_annotations(mut self, codebook: &Codebook, annotations: &[Coded]) -> Tiers {
        let mut coded: Vec<CodedTier> = (codebook.tiers.iter())
            .map(|t| CodedTier {
                name: t.name.clone(),
                codes: t.codes.iter().map(|c| c.code.clone()).collect(),
                intervals: Vec::new(),
                points: Vec::new(),
            })
            .collect();
        for a in annotations {
            let at = match coded.iter().position(|t| t.name == a.tier) {
                Some(at) => at,
                None => {
                    coded.push(CodedTier {
                        name: a.tier.clone(),
                        codes: Vec::new(),
                        intervals: Vec::new(),
                        points: Vec::new(),
                    });
                    coded.len() - 1
                }
            };
            if !coded[at].codes.contains(&a.code) {
                coded[at].codes.push(a.code.clone());
            }
        }
        for tier in &mut coded {
            let mine = || annotations.iter().filter(|a| a.tier == tier.name);
            let intervals = mine()
                .filter(|a| !a.is_point())
                .map(|a| annotation(a.start_us, a.end_us, &a.code));
            tier.intervals = interval_tiers(&tier.name, intervals);
            let points = mine().filter(|a| a.is_point()).map(|a| Point {
                at_us: a.start_us,
                value: a.code.clone(),
            });
            tier.points = point_tiers(&format!("{}{POINTS}", tier.name), points);
        }
        self.coded = coded;
        self.end_us = self.latest().max(self.end_us);
        self
    }

    /// Every interval tier (the act tiers aside), in file order.
    pub fn interval_tiers(&self) -> impl Iterator<Item = &IntervalTier> {
        (self.speech.iter().map(|s| &s.speech))
            .chain(&self.commands)
            .chain(&self.pages)
    }

    /// Every point tier, in file order.
    pub fn point_tiers(&self) -> impl Iterator<Item = &PointTier> {
        self.touches.iter().chain(&self.marks)
    }

    /// The latest end of an interval or a point's room.
    fn latest(&self) -> u64 {
        let coded_intervals = self.coded.iter().flat_map(|c| &c.intervals);
        let coded_points = self.coded.iter().flat_map(|c| &c.points);
        let intervals = (self.interval_tiers().chain(coded_intervals)).flat_map(|t| &t.annotations);
        let points = (self.point_tiers().chain(coded_points)).flat_map(|t| &t.points);
        (intervals.map(|a| a.end_us))
            .chain(points.map(|p| p.at_us))
            .max()
            .unwrap_or(0)
    }
}

/// An annotation drawn at least [`MIN_INTERVAL_US`] long.
fn annotation(start_us: u64, end_us: u64, value: &str) -> Annotation {
    Annotation {
        start_us,
        end_us: end_us.max(start_us + MIN_INTERVAL_US),
        value: value.to_owned(),
    }
}

/// `VERB argument`, and how it ended unless it was done.
fn command_value(c: &CommandRun) -> String {
    let mut value = match &c.arg {
        Some(arg) => format!("{} {arg}", c.verb),
        None => c.verb.clone(),
    };
    let (word, reason) = match &c.outcome {
        Outcome::Done => return value,
        Outcome::Failed(reason) => ("failed", reason.as_str()),
        Outcome::Cancelled(reason) => ("cancelled", reason.as_str()),
        Outcome::Open => ("no outcome in the log", ""),
    };
    value.push_str(&match reason {
        "" => format!(" ({word})"),
        reason => format!(" ({word}: {reason})"),
    });
    value
}

/// What a touch did, as its point says it: the act's label, a refusal, or the page followed.
fn touch_value(touched: &Touched) -> String {
    match touched {
        Touched::Act { label } => label.clone(),
        Touched::Refused { label, code } => format!("{label} (refused: {code})"),
        Touched::Page { page } => format!("page: {page}"),
    }
}

/// `base` for the first tier of a kind, then `base-2`, `base-3`, ...
pub fn numbered(base: &str, n: usize) -> String {
    match n {
        0 => base.to_owned(),
        n => format!("{base}-{}", n + 1),
    }
}

fn interval_tiers(base: &str, items: impl Iterator<Item = Annotation>) -> Vec<IntervalTier> {
    let tiers = spread(items, |a| (a.start_us, a.end_us));
    (tiers.into_iter().enumerate())
        .map(|(n, annotations)| IntervalTier {
            name: numbered(base, n),
            annotations,
        })
        .collect()
}

fn point_tiers(base: &str, items: impl Iterator<Item = Point>) -> Vec<PointTier> {
    let tiers = spread(items, |p| (p.at_us, p.at_us + MIN_INTERVAL_US));
    (tiers.into_iter().enumerate())
        .map(|(n, points)| PointTier {
            name: numbered(base, n),
            points,
        })
        .collect()
}

/// Deals `items` out to as few tiers as keep each tier free of overlaps: each item, by start,
/// goes to the first tier whose last item has ended by then. Always at least one tier.
fn spread<T>(items: impl Iterator<Item = T>, span: impl Fn(&T) -> (u64, u64)) -> Vec<Vec<T>> {
    let mut items: Vec<T> = items.collect();
    items.sort_by_key(|item| span(item));
    let mut tiers: Vec<(u64, Vec<T>)> = vec![(0, Vec::new())];
    for item in items {
        let (start, end) = span(&item);
        match tiers.iter_mut().find(|(free_at, _)| *free_at <= start) {
            Some((free_at, tier)) => {
                *free_at = end;
                tier.push(item);
            }
            None => tiers.push((end, vec![item])),
        }
    }
    tiers.into_iter().map(|(_, tier)| tier).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::timeline::{CommandRun, Mark, Touch};

    fn run(start_us: u64, end_us: u64, verb: &str) -> CommandRun {
        let (arg, outcome) = (None, Outcome::Done);
        let verb = verb.to_owned();
        CommandRun {
            start_us,
            end_us,
            verb,
            arg,
            outcome,
        }
    }

    #[test]
    fn overlapping_commands_go_to_numbered_tiers_and_nothing_is_lost() {
        let timeline = Timeline {
            end_us: 10_000_000,
            commands: vec![
                run(0, 5_000_000, "DRIVE_START"),
                run(1_000_000, 2_000_000, "DISPLAY_PAGE"),
                run(2_000_000, 3_000_000, "LIGHTS"),
                run(2_500_000, 2_500_000, "CHIME"),
            ],
            ..Timeline::default()
        };
        let tiers = Tiers::of(&timeline);
        let names: Vec<_> = tiers.commands.iter().map(|t| t.name.as_str()).collect();
        assert_eq!(names, ["commands", "commands-2", "commands-3"]);
        let values = |n: usize| -> Vec<&str> {
            let tier = &tiers.commands[n].annotations;
            tier.iter().map(|a| a.value.as_str()).collect()
        };
        assert_eq!(values(0), ["DRIVE_START"]);
        assert_eq!(values(1), ["DISPLAY_PAGE", "LIGHTS"]);
        assert_eq!(
            values(2),
            ["CHIME"],
            "a command of no length drawn 1 ms long"
        );
        assert_eq!(tiers.commands[2].annotations[0].end_us, 2_501_000);
        assert_eq!(tiers.speech[0].speech.name, "speech", "always there");
    }

    #[test]
    fn points_less_than_a_millisecond_apart_share_no_tier() {
        let mark = |at_us, what| Mark { at_us, what };
        let touch = Touch {
            at_us: 9_000,
            what: Touched::Page {
                page: "about.html".into(),
            },
        };
        let timeline = Timeline {
            end_us: 9_000,
            marks: vec![
                mark(528, Marked::Group("children".into())),
                mark(1_006, Marked::Situation("laughter".into())),
                mark(1_528, Marked::Situation("question".into())),
            ],
            touches: vec![touch],
            ..Timeline::default()
        };
        let tiers = Tiers::of(&timeline);
        let marks: Vec<(&str, Vec<&str>)> = (tiers.marks.iter())
            .map(|t| {
                (
                    t.name.as_str(),
                    t.points.iter().map(|p| &*p.value).collect(),
                )
            })
            .collect();
        assert_eq!(
            marks,
            [
                ("marks", vec!["group: children", "situation: question"]),
                ("marks-2", vec!["situation: laughter"]),
            ]
        );
        assert_eq!(tiers.touches[0].points[0].value, "page: about.html");
        assert_eq!(tiers.end_us, 9_000);
    }
}
