//! A session's log read once into what every export writes: the robot's utterances, its other
//! commands, the pages the touchscreen showed, the visitors' touches and the operator's marks,
//! each placed on the session clock (`session_us`, microseconds from `session.started`). This
//! is the only reader of the log for exports, so the formats cannot disagree about what
//! happened; `tiers.rs` lays it out as tiers, `csv.rs` as rows.

use std::collections::{BTreeMap, HashMap};

use crate::export::log_line::{CommandFields, EXPLICIT_TOUCHES, Event, KNOWN_FORMAT, LogLine};

mod parts;

pub use parts::{
    CommandRun, LineProblem, Mark, Marked, Outcome, PageShown, Timeline, Touch, Touched,
    UNKNOWN_TEXT, Utterance,
};

/// A command as its events told it so far.
struct Pending {
    verb: String,
    arg: Option<String>,
    trigger: u64,
    label: String,
    source: String,
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
    /// Reads one line of the log (without its `\n`).
    pub fn read_line(&mut self, line: &[u8]) -> Result<(), LineProblem> {
        let line = LogLine::parse(line).map_err(LineProblem)?;
        if line.v > KNOWN_FORMAT {
            return Err(LineProblem(format!(
                "event format {} is newer than this Docent reads ({KNOWN_FORMAT}): export it \
                 with the Docent that wrote it",
                line.v
            )));
        }
        let Some(at) = line.session_us else {
            return Err(LineProblem(
                "the line has no `session_us`: this is not a session's log (a day log's \
                 events belong to no session)"
                    .into(),
            ));
        };
        self.last_us = self.last_us.max(at);
        self.explicit_touches |= line.v >= EXPLICIT_TOUCHES;
        self.take(at, line.event);
        Ok(())
    }

    fn take(&mut self, at: u64, event: Event) {
        match event {
            Event::ActTriggered {
                trigger,
                source,
                label,
                variant,
                alternative,
                text,
            } => {
                if source == "kiosk" && !self.explicit_touches {
                    let what = Touched::Act {
                        label: label.clone(),
                    };
                    self.timeline.touches.push(Touch { at_us: at, what });
                }
                self.timeline.labels.insert(label);
                let chosen = ChosenText {
                    text,
                    variant,
                    alternative,
                    said: false,
                };
                self.chosen.insert(trigger, chosen);
            }
            Event::TriggerRefused {
                source,
                label,
                code,
            } if source == "kiosk" => {
                // The touch that asked for it (logged just before) was refused.
                let asked = self.timeline.touches.last_mut().filter(|t| {
                    self.explicit_touches
                        && matches!(&t.what, Touched::Act { label: l } if *l == label)
                });
                let what = Touched::Refused { label, code };
                match asked {
                    Some(touch) => touch.what = what,
                    None => self.timeline.touches.push(Touch { at_us: at, what }),
                }
            }
            Event::Touch { act, link } => {
                let what = match (act, link) {
                    (Some(label), _) => Touched::Act { label },
                    (None, Some(page)) => Touched::Page { page },
                    (None, None) => return,
                };
                self.timeline.touches.push(Touch { at_us: at, what });
            }
            Event::TriggerRefused { .. } | Event::Other => {}
            Event::CommandSent(c) => self.command(at, c).sent_us = Some(at),
            Event::CommandStarted(c) => self.command(at, c).started_us = Some(at),
            Event::CommandDone(c) => self.command(at, c).end = Some((at, Outcome::Done)),
            Event::CommandFailed(mut c) => {
                let reason = c.reason.take().unwrap_or_default();
                self.command(at, c).end = Some((at, Outcome::Failed(reason)));
            }
            Event::CommandCancelled(mut c) => {
                let reason = c.reason.take().unwrap_or_default();
                self.command(at, c).end = Some((at, Outcome::Cancelled(reason)));
            }
            Event::DisplayChanged { page } => self.page_changed(at, page),
            Event::SituationMarked { situation } => {
                let what = Marked::Situation(situation);
                self.timeline.marks.push(Mark { at_us: at, what });
            }
            Event::NoteWritten { text } => {
                let what = Marked::Note(text);
                self.timeline.marks.push(Mark { at_us: at, what });
            }
            Event::VisitorGroup { group } => {
                let what = Marked::Group(group);
                self.timeline.marks.push(Mark { at_us: at, what });
            }
            Event::SessionStarted { page } => {
                if let Some(page) = page {
                    self.page = Some((at, page));
                }
            }
            Event::SessionEnded => self.timeline.ended = true,
        }
    }

    /// The command `fields` names, begun at `at` when this is its first event.
    fn command(&mut self, at: u64, fields: CommandFields) -> &mut Pending {
        self.timeline.labels.insert(fields.label.clone());
        let pending = self.commands.entry(fields.command).or_insert(Pending {
            verb: fields.verb,
            arg: None,
            trigger: fields.trigger,
            label: fields.label,
            source: fields.source,
            first_us: at,
            sent_us: None,
            started_us: None,
            end: None,
        });
        if fields.arg.is_some() {
            pending.arg = fields.arg;
        }
        pending
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
            source: c.source.clone(),
            variant,
            alternative,
            outcome,
        }
    }
}

#[cfg(test)]
#[path = "timeline_tests.rs"]
mod tests;
