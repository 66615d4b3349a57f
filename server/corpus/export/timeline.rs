//! A session's log read once into what every export writes: the robot's utterances, its other
//! commands, the pages the touchscreen showed, the visitors' touches and the operator's marks,
//! each placed on the session clock (`session_us`, microseconds from `session.started`). This
//! is the only reader of the log for exports, so the formats cannot disagree about what
//! happened; `tiers.rs` lays it out as tiers, `csv.rs` as rows.
//!
//! Each line is read through the protocol's own types (`docent_protocol::events::LineEvent`, the
//! `EventKind` the server wrote it with): a renamed event type or field does not compile here,
//! or fails the corpus tests, instead of emptying a tier. Types newer than this Docent are
//! passed over, so a log with them still exports.

use std::collections::{BTreeMap, HashMap};
use std::sync::Arc;

use docent_protocol::EVENT_FORMAT_VERSION;
use docent_protocol::events::{
    self, ActRef, CommandCancelled, CommandDone, CommandFailed, CommandSent, CommandStarted,
    EventKind, Head, LineEvent, NoteWritten, SessionStarted, SituationMarked, Source, VisitorGroup,
    is_pose,
};

mod parts;

pub use parts::{
    CommandRun, LineProblem, Mark, Marked, Outcome, PageShown, Timeline, Touch, Touched,
    UNKNOWN_TEXT, Utterance,
};

/// The first event format whose visitors' touches are `touch` events; before it, a kiosk's
/// `act.triggered` and a page change no `DISPLAY_PAGE` asked for are taken for touches.
const EXPLICIT_TOUCHES: u32 = 4;

/// A command as its events told it so far.
struct Pending {
    verb: String,
    arg: Option<String>,
    trigger: u64,
    label: String,
    source: Source,
    first_us: u64,
    sent_us: Option<u64>,
    started_us: Option<u64>,
    end: Option<(u64, Outcome)>,
}

/// What an `act.triggered` said about the text it chose.
struct ChosenText {
    text: Option<String>,
    variant: Option<String>,
    alternative: Option<u64>,
    /// Whether a `SAY` has already been matched with this text.
    said: bool,
}

/// Builds a [`Timeline`] from a session's lines, one at a time, in log order.
#[derive(Default)]
pub struct TimelineReader {
    timeline: Timeline,
    commands: BTreeMap<u64, Pending>,
    chosen: HashMap<u64, ChosenText>,
    /// The page shown and when it began.
    page: Option<(u64, String)>,
    last_us: u64,
    /// The log names its touches (`touch` events, format 4 on): nothing else is taken for one.
    explicit_touches: bool,
}

impl TimelineReader {
    /// Reads one line of the log (without its `\n`): its stamps first (a line of a newer
    /// format or of a day log is told as such, whatever its fields), then its event.
    pub fn read_line(&mut self, line: &[u8]) -> Result<(), LineProblem> {
        let head = Head::parse(line).map_err(|e| LineProblem(plain(&e)))?;
        let Some(v) = head.v else {
            let missing = <serde_json::Error as serde::de::Error>::missing_field("v");
            return Err(LineProblem(format!("{missing} (column {})", line.len())));
        };
        if v > EVENT_FORMAT_VERSION {
            return Err(LineProblem(format!(
                "event format {v} is newer than this Docent reads ({EVENT_FORMAT_VERSION}): \
                 export it with the Docent that wrote it"
            )));
        }
        let Some(at) = head.session_us else {
            return Err(LineProblem(
                "the line has no `session_us`: this is not a session's log (a day log's \
                 events belong to no session)"
                    .into(),
            ));
        };
        // No tier draws the robot's poses, most of a log: their stamps are enough here (MCAP
        // reads them whole, `export/mcap`).
        let event = match head.kind.as_deref().is_some_and(is_pose) {
            true => None,
            false => Some(LineEvent::parse(line, &head).map_err(|e| LineProblem(plain(&e)))?),
        };
        self.last_us = self.last_us.max(at);
        self.explicit_touches |= v >= EXPLICIT_TOUCHES;
        if let Some(LineEvent::Event(kind)) = event {
            self.take(at, kind);
        }
        Ok(())
    }

    fn take(&mut self, at: u64, event: EventKind) {
        match event {
            EventKind::ActTriggered {
                act,
                variant,
                alternative,
                text,
                ..
            } => {
                let label = act.label.to_string();
                if act.source == Source::Kiosk && !self.explicit_touches {
                    let what = Touched::Act {
                        label: label.clone(),
                    };
                    self.timeline.touches.push(Touch { at_us: at, what });
                }
                self.timeline.labels.insert(label);
                let chosen = ChosenText {
                    text,
                    variant,
                    alternative: alternative.map(|a| a as u64),
                    said: false,
                };
                self.chosen.insert(act.trigger, chosen);
            }
            EventKind::TriggerRefused {
                source: Source::Kiosk,
                label,
                code,
                ..
            } => {
                // The touch that asked for it (logged just before) was refused.
                let asked = self.timeline.touches.last_mut().filter(|t| {
                    self.explicit_touches
                        && matches!(&t.what, Touched::Act { label: l } if *l == label)
                });
                let what = Touched::Refused {
                    label,
                    code: code.to_string(),
                };
                match asked {
                    Some(touch) => touch.what = what,
                    None => self.timeline.touches.push(Touch { at_us: at, what }),
                }
            }
            EventKind::Touch(events::Touch { act, link, .. }) => {
                let what = match (act, link) {
                    (Some(label), _) => Touched::Act { label },
                    (None, Some(page)) => Touched::Page { page },
                    (None, None) => return,
                };
                self.timeline.touches.push(Touch { at_us: at, what });
            }
            EventKind::CommandSent(CommandSent {
                command,
                act,
                verb,
                arg,
                ..
            }) => {
                let pending = self.command(at, command, &act, verb);
                pending.sent_us = Some(at);
                if arg.is_some() {
                    pending.arg = arg;
                }
            }
            EventKind::CommandStarted(CommandStarted { command, act, verb }) => {
                self.command(at, command, &act, verb).started_us = Some(at);
            }
            EventKind::CommandDone(CommandDone { command, act, verb }) => {
                self.command(at, command, &act, verb).end = Some((at, Outcome::Done));
            }
            EventKind::CommandFailed(CommandFailed {
                command,
                act,
                verb,
                reason,
            }) => {
                self.command(at, command, &act, verb).end = Some((at, Outcome::Failed(reason)));
            }
            EventKind::CommandCancelled(CommandCancelled {
                command,
                act,
                verb,
                reason,
            }) => {
                let end = Some((at, Outcome::Cancelled(reason)));
                self.command(at, command, &act, verb).end = end;
            }
            EventKind::DisplayChanged { page, .. } => self.page_changed(at, page),
            EventKind::SituationMarked(SituationMarked { situation, .. }) => {
                let what = Marked::Situation(situation);
                self.timeline.marks.push(Mark { at_us: at, what });
            }
            EventKind::NoteWritten(NoteWritten { text, .. }) => {
                let what = Marked::Note(text);
                self.timeline.marks.push(Mark { at_us: at, what });
            }
            EventKind::VisitorGroup(VisitorGroup { group, .. }) => {
                let what = Marked::Group(group);
                self.timeline.marks.push(Mark { at_us: at, what });
            }
            EventKind::SessionStarted(SessionStarted {
                page: Some(page), ..
            }) => self.page = Some((at, page)),
            EventKind::SessionEnded { .. } => self.timeline.ended = true,
            // Every other event draws nothing on the timeline (MCAP reads the lines again).
            _ => {}
        }
    }

    /// The command `command` of the trigger `act`, begun at `at` when this is its first event.
    fn command(&mut self, at: u64, command: u64, act: &Arc<ActRef>, verb: String) -> &mut Pending {
        self.timeline.labels.insert(act.label.to_string());
        self.commands.entry(command).or_insert(Pending {
            verb,
            arg: None,
            trigger: act.trigger,
            label: act.label.to_string(),
            source: act.source,
            first_us: at,
            sent_us: None,
            started_us: None,
            end: None,
        })
    }

    /// A `display.changed`: a new page begins when the touchscreen's page is another. A change
    /// to a page that no `DISPLAY_PAGE` still under way asked for was the kiosk's own (a
    /// visitor followed a link), so it is a touch too.
    fn page_changed(&mut self, at: u64, page: Option<String>) {
        if self.page.as_ref().map(|(_, p)| p) == page.as_ref() {
            return;
        }
        if let Some((start_us, page)) = self.page.take() {
            let shown = PageShown {
                start_us,
                end_us: at,
                page,
            };
            self.timeline.pages.push(shown);
        }
        let Some(page) = page else { return };
        let asked = self.commands.values().any(|c| {
            c.verb == "DISPLAY_PAGE" && c.end.is_none() && c.arg.as_deref() == Some(page.as_str())
        });
        if !asked && !self.explicit_touches {
            let what = Touched::Page { page: page.clone() };
            self.timeline.touches.push(Touch { at_us: at, what });
        }
        self.page = Some((at, page));
    }

    /// The timeline, with whatever was still under way ending at the session's end.
    pub fn finish(mut self) -> Timeline {
        let end_us = self.last_us;
        self.timeline.end_us = end_us;
        if let Some((start_us, page)) = self.page.take() {
            let shown = PageShown {
                start_us,
                end_us,
                page,
            };
            self.timeline.pages.push(shown);
        }
        for (_, mut c) in std::mem::take(&mut self.commands) {
            let (end_us, outcome) = c.end.take().unwrap_or((end_us, Outcome::Open));
            match (c.verb.as_str(), c.started_us) {
                ("SAY", Some(start_us)) => {
                    let utterance = self.utterance(&c, start_us, end_us, outcome);
                    self.timeline.utterances.push(utterance);
                }
                _ => self.timeline.commands.push(CommandRun {
                    start_us: c.started_us.or(c.sent_us).unwrap_or(c.first_us),
                    end_us,
                    verb: c.verb,
                    arg: c.arg,
                    outcome,
                }),
            }
        }
        (self.timeline.utterances).sort_by_key(|u| (u.start_us, u.end_us));
        (self.timeline.commands).sort_by_key(|c| (c.start_us, c.end_us));
        self.timeline
    }

    /// A begun `SAY`. Its text is its argument (the act's chosen text for the act's own
    /// `SAY`); the variant and alternative belong to the first `SAY` that says that text.
    fn utterance(
        &mut self,
        c: &Pending,
        start_us: u64,
        end_us: u64,
        outcome: Outcome,
    ) -> Utterance {
        let chosen = self.chosen.get_mut(&c.trigger);
        let text = c
            .arg
            .clone()
            .or_else(|| chosen.as_ref().and_then(|t| t.text.clone()))
            .unwrap_or_else(|| UNKNOWN_TEXT.to_owned());
        let (mut variant, mut alternative) = (None, None);
        if let Some(chosen) = chosen
            && !chosen.said
            && chosen.text.as_deref() == Some(text.as_str())
        {
            chosen.said = true;
            variant = chosen.variant.clone();
            alternative = chosen.alternative;
        }
        Utterance {
            start_us,
            end_us,
            text,
            label: c.label.clone(),
            source: c.source,
            variant,
            alternative,
            outcome,
        }
    }
}

/// serde_json's message without its "at line 1 column N" (a log line is one line; the column
/// is given separately).
fn plain(error: &serde_json::Error) -> String {
    let message = error.to_string();
    let cut = message.rfind(" at line ").unwrap_or(message.len());
    format!("{} (column {})", &message[..cut], error.column())
}

#[cfg(test)]
#[path = "timeline_tests.rs"]
mod tests;
