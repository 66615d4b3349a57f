//! Each verb's argument checked against its rule: text to speak, files, a waypoint inside
//! the drive's bounds, highlight areas, lengths of time, and the site verbs' declared rules.
//! Separate from `mod.rs`, which splits a command into verb and argument and parses it.

use crate::DiagnosticCode;
use crate::config::ArgRule;
use crate::diagnostic::Diagnostic;
use crate::duration::parse_duration;
use crate::highlight::{parse_highlight, words_with_offsets};
use crate::model::{Pos, Verb};
use crate::paths::BundleArea;
use crate::speech::{SpokenText, check_spoken};

use super::{CommandChecker, WrittenCommand, offset_pos};

const SAY_USAGE: &str = "SAY needs the text to speak, e.g. `SAY Welcome to the museum`.";
const PROJECT_USAGE: &str =
    "PROJECT needs a file from the media folder, e.g. `PROJECT Exhibit/video.webm`.";
const DISPLAY_PAGE_USAGE: &str =
    "DISPLAY_PAGE needs a page from the pages folder, e.g. `DISPLAY_PAGE Welcome/Welcome.html`.";
const WAIT_USAGE: &str = "Write `WAIT` alone to wait until the act's earlier commands are \
                          done, or a time with its unit such as `WAIT 2s` or `WAIT 500ms`.";
const WAYPOINT_USAGE: &str = "SET_WAYPOINT needs two or three numbers: x and y in metres, and \
                              optionally the heading, e.g. `SET_WAYPOINT 3.5 2` or \
                              `SET_WAYPOINT 3.5 2 90`.";

impl CommandChecker<'_> {
    pub(super) fn check_argument(
        &self,
        verb: &Verb,
        arg: Option<&str>,
        cmd: &WrittenCommand,
        arg_start: usize,
        arg_pos: &Pos,
        out: &mut Vec<Diagnostic>,
    ) {
        let problem: Option<(&Pos, String)> = match (verb, arg) {
            (Verb::Say, None) => Some((&cmd.pos, SAY_USAGE.to_owned())),
            (Verb::Say, Some(text)) => {
                let before = cmd.text.get(..arg_start).map_or(0, |t| t.chars().count());
                let spoken = SpokenText {
                    text,
                    pos: &cmd.pos,
                    verbatim_at: (cmd.verbatim_at)
                        .map(|at| at.saturating_add(u32::try_from(before).unwrap_or(0))),
                };
                check_spoken(&spoken, &self.config.speech, out);
                None
            }
            (Verb::Project, None) => Some((&cmd.pos, PROJECT_USAGE.to_owned())),
            (Verb::DisplayPage, None) => Some((&cmd.pos, DISPLAY_PAGE_USAGE.to_owned())),
            (Verb::Project, Some(file)) => {
                self.check_file(BundleArea::Media, file, arg_pos, out);
                self.media_format(file, arg_pos, out);
                None
            }
            (Verb::DisplayPage, Some(file)) => {
                self.check_file(BundleArea::Pages, file, arg_pos, out);
                None
            }
            (Verb::SetWaypoint, _) => {
                self.check_waypoint(arg.unwrap_or(""), cmd, arg_start, out);
                None
            }
            (Verb::Highlight, Some(areas)) => {
                for problem in parse_highlight(areas).err().unwrap_or_default() {
                    let pos = offset_pos(cmd, arg_start + problem.offset);
                    out.push(Diagnostic::error(
                        DiagnosticCode::BadArgument,
                        &pos,
                        problem.message,
                    ));
                }
                None
            }
            (Verb::DriveStart | Verb::DriveStop, Some(extra)) => Some((
                arg_pos,
                format!("{verb} takes nothing after it. Remove `{extra}`."),
            )),
            (Verb::Wait, Some(wait)) if parse_duration(wait).is_none() => Some((
                arg_pos,
                format!("`{wait}` is not a length of time. {WAIT_USAGE}"),
            )),
            (Verb::Site(name), _) => {
                let rule = self.config.verbs.get(name.as_ref()).map(|v| v.argument);
                match (rule, arg) {
                    (Some(ArgRule::Required), None) => Some((
                        &cmd.pos,
                        format!(
                            "{name} needs something after it (docent.yaml says \
                             `argument: required`)."
                        ),
                    )),
                    (Some(ArgRule::None), Some(extra)) => Some((
                        arg_pos,
                        format!(
                            "{name} takes nothing after it (docent.yaml says `argument: none`). \
                             Remove `{extra}`."
                        ),
                    )),
                    _ => None,
                }
            }
            _ => None,
        };
        if let Some((pos, message)) = problem {
            out.push(Diagnostic::error(DiagnosticCode::BadArgument, pos, message));
        }
    }

    pub(super) fn check_waypoint(
        &self,
        arg: &str,
        cmd: &WrittenCommand,
        arg_start: usize,
        out: &mut Vec<Diagnostic>,
    ) {
        let words = words_with_offsets(arg, arg_start);
        if !(2..=3).contains(&words.len()) {
            let pos = if words.is_empty() {
                cmd.pos.clone()
            } else {
                offset_pos(cmd, arg_start)
            };
            out.push(Diagnostic::error(
                DiagnosticCode::BadArgument,
                &pos,
                format!("Found {} value(s). {WAYPOINT_USAGE}", words.len()),
            ));
            return;
        }
        let mut numbers = Vec::with_capacity(3);
        for &(offset, word) in &words {
            match word.parse::<f64>() {
                Ok(n) if n.is_finite() => numbers.push(n),
                _ => {
                    let pos = offset_pos(cmd, offset);
                    out.push(Diagnostic::error(
                        DiagnosticCode::BadArgument,
                        &pos,
                        format!("`{word}` is not a number. {WAYPOINT_USAGE}"),
                    ));
                }
            }
        }
        let (Some(bounds), [x, y, ..]) = (self.config.drive.bounds, numbers.as_slice()) else {
            return;
        };
        if numbers.len() == words.len() && !bounds.contains(*x, *y) {
            let pos = offset_pos(cmd, arg_start);
            let message = format!(
                "The point ({x}, {y}) lies outside the area the robot may drive in: x from {} \
                 to {}, y from {} to {} (set in docent.yaml under `drive: bounds`).",
                bounds.min_x, bounds.max_x, bounds.min_y, bounds.max_y
            );
            out.push(Diagnostic::error(
                DiagnosticCode::WaypointOutOfBounds,
                &pos,
                message,
            ));
        }
    }
}
