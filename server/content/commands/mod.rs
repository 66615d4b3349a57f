//! Parsing and checking the `VERB argument` strings of an act's `Cmds` list.
//!
//! The verb is the first word; the argument is everything after it, trimmed. Built-in verbs
//! have fixed argument rules; verbs declared in `docent.yaml` carry their own rule. File
//! arguments go through the bundle's path gate, exactly as the HTTP routes will later.

use std::cell::{OnceCell, RefCell};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

mod files;

pub(crate) use files::path_error_code;

use crate::content::args::Args;
use crate::content::config::{ArgRule, SiteConfig};
use crate::content::diagnostic::Diagnostic;
use crate::content::duration::parse_duration;
use crate::content::highlight::{parse_highlight, words_with_offsets};
use crate::content::media::MediaSniffs;
use crate::content::model::{CommandSpec, Located, Pos, Verb};
use crate::content::paths::{BundleArea, Listing, PathError};
use crate::content::speech::{SpokenText, check_spoken};
use crate::content::suggest::closest;

/// A command string as written in an acts file.
#[derive(Debug)]
pub(crate) struct WrittenCommand {
    /// The text, e.g. `DISPLAY_PAGE Welcome/Welcome.html`.
    pub text: String,
    /// Where the string starts (its opening quote, if quoted).
    pub pos: Pos,
    /// Character offset from `pos` where `text` appears unchanged on the line, if it does;
    /// lets argument problems point at the argument itself.
    pub verbatim_at: Option<u32>,
}

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

/// Why a path was refused, and the message for people.
pub(crate) type PathProblem = (PathError, String);

/// Checks commands against the site settings and the bundle's files.
pub(crate) struct CommandChecker<'a> {
    root: &'a Path,
    config: &'a SiteConfig,
    /// File listings for suggestions, made only when a file is missing.
    pages: OnceCell<Vec<String>>,
    media: OnceCell<Vec<String>>,
    /// Verdicts per path: many acts show the same few pages, and each check lists folders.
    verdicts: RefCell<HashMap<(BundleArea, String), Option<PathProblem>>>,
    /// Paths resolved, and folders listed, during this load.
    resolved: RefCell<HashMap<(BundleArea, String), Result<PathBuf, PathError>>>,
    listings: RefCell<HashMap<PathBuf, Listing>>,
    /// What media files really are, read once however many acts and pages show them.
    sniffs: MediaSniffs,
}

impl<'a> CommandChecker<'a> {
    /// A checker for the bundle at the canonical `root`.
    pub fn new(root: &'a Path, config: &'a SiteConfig) -> Self {
        CommandChecker {
            root,
            config,
            pages: OnceCell::new(),
            media: OnceCell::new(),
            verdicts: RefCell::new(HashMap::new()),
            resolved: RefCell::new(HashMap::new()),
            listings: RefCell::new(HashMap::new()),
            sniffs: MediaSniffs::default(),
        }
    }

    /// The canonical bundle root.
    pub fn root(&self) -> &Path {
        self.root
    }

    /// The media formats sniffed so far, shared with the page checks.
    pub fn media(&self) -> &MediaSniffs {
        &self.sniffs
    }

    /// The parsed command, or `None` after reporting why it is unusable. Warnings may be
    /// reported for a usable command.
    pub fn check(
        &self,
        cmd: &WrittenCommand,
        out: &mut Vec<Diagnostic>,
    ) -> Option<Located<CommandSpec>> {
        let start = cmd.text.len() - cmd.text.trim_start().len();
        let trimmed = cmd.text.trim();
        if trimmed.is_empty() {
            out.push(Diagnostic::error(
                "bad-value",
                &cmd.pos,
                "This command is empty. Write a command such as `SAY Hello`, or remove the line.",
            ));
            return None;
        }
        let verb_end = trimmed.find(char::is_whitespace).unwrap_or(trimmed.len());
        let word = &trimmed[..verb_end];
        let rest = &trimmed[verb_end..];
        let arg_start = start + verb_end + (rest.len() - rest.trim_start().len());
        let arg = Some(rest.trim()).filter(|a| !a.is_empty());
        let Some(verb) = self.verb(word) else {
            out.push(Diagnostic::error(
                "unknown-verb",
                &cmd.pos,
                self.unknown_verb_message(word),
            ));
            return None;
        };
        let arg_pos = offset_pos(cmd, arg_start);
        let before = out.len();
        self.check_argument(&verb, arg, cmd, arg_start, &arg_pos, out);
        if out[before..].iter().any(Diagnostic::is_error) {
            return None;
        }
        let Some(args) = Args::parse(&verb, arg) else {
            // The checks above accept only what parses; this is Docent's fault, not the author's.
            let message = format!(
                "Docent accepted this command but could not read its argument. Please report \
                 this as a bug in Docent, with this line: `{trimmed}`."
            );
            out.push(Diagnostic::error("bad-argument", &cmd.pos, message));
            return None;
        };
        let spec = CommandSpec {
            verb,
            arg: arg.map(str::to_owned),
            args,
        };
        Some(Located {
            value: spec,
            pos: cmd.pos.clone(),
        })
    }

    fn verb(&self, word: &str) -> Option<Verb> {
        Verb::built_in(word).or_else(|| {
            let (name, _) = self.config.verbs.get_key_value(word)?;
            Some(Verb::Site(Arc::from(name.as_str())))
        })
    }

    fn known_verbs(&self) -> impl Iterator<Item = &str> + '_ {
        Verb::BUILT_IN
            .iter()
            .map(Verb::as_str)
            .chain(self.config.verbs.keys().map(String::as_str))
    }

    fn unknown_verb_message(&self, word: &str) -> String {
        let known: Vec<&str> = self.known_verbs().collect();
        let hint = match closest(word, known.iter().copied()) {
            Some(s) => format!("Did you mean `{s}`?"),
            None => format!("Known commands: {}.", known.join(", ")),
        };
        format!(
            "`{word}` is not a command Docent knows. {hint} A command is a word in capitals \
             followed by what it needs, e.g. `SAY Hello`; new commands can be declared in \
             docent.yaml under `verbs:`."
        )
    }

    fn check_argument(
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
                    out.push(Diagnostic::error("bad-argument", &pos, problem.message));
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
            out.push(Diagnostic::error("bad-argument", pos, message));
        }
    }

    fn check_waypoint(
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
                "bad-argument",
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
                        "bad-argument",
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
            out.push(Diagnostic::error("waypoint-out-of-bounds", &pos, message));
        }
    }
}

/// The position `byte` bytes into the command text, when the text is verbatim in the file.
fn offset_pos(cmd: &WrittenCommand, byte: usize) -> Pos {
    let (Some(at), Some(before)) = (cmd.verbatim_at, cmd.text.get(..byte)) else {
        return cmd.pos.clone();
    };
    let chars = u32::try_from(before.chars().count()).unwrap_or(0);
    Pos::new(
        cmd.pos.file.clone(),
        cmd.pos.line,
        cmd.pos.column.saturating_add(at).saturating_add(chars),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn command(text: &str, column: u32, verbatim_at: Option<u32>) -> WrittenCommand {
        WrittenCommand {
            text: text.to_owned(),
            pos: Pos::new("acts.yaml", 3, column),
            verbatim_at,
        }
    }

    fn check(cmd: &WrittenCommand) -> (Option<CommandSpec>, Vec<(&'static str, u32)>) {
        let root = std::env::temp_dir();
        let config = SiteConfig::default();
        let checker = CommandChecker::new(&root, &config);
        let mut out = Vec::new();
        let spec = checker.check(cmd, &mut out).map(|c| c.value);
        (spec, out.iter().map(|d| (d.code, d.column)).collect())
    }

    #[test]
    fn splits_the_verb_from_a_trimmed_argument() {
        let (spec, problems) = check(&command("SAY   Hello there  ", 7, Some(0)));
        assert_eq!(
            spec,
            Some(CommandSpec {
                verb: Verb::Say,
                arg: Some("Hello there".to_owned()),
                args: Args::Say {
                    text: "Hello there".to_owned()
                }
            })
        );
        assert!(problems.is_empty());
        let (spec, _) = check(&command("DRIVE_STOP", 7, Some(0)));
        assert_eq!(
            spec,
            Some(CommandSpec {
                verb: Verb::DriveStop,
                arg: None,
                args: Args::None {}
            })
        );
    }

    #[test]
    fn argument_problems_point_into_the_text_when_it_is_verbatim() {
        assert_eq!(
            check(&command("WAIT soon", 7, Some(0))).1,
            [("bad-argument", 12)]
        );
        assert_eq!(
            check(&command("WAIT soon", 7, Some(1))).1,
            [("bad-argument", 13)]
        );
        assert_eq!(
            check(&command("WAIT soon", 7, None)).1,
            [("bad-argument", 7)]
        );
        assert_eq!(
            check(&command("SET_WAYPOINT 1 é", 7, Some(0))).1,
            [("bad-argument", 22)]
        );
    }

    #[test]
    fn empty_and_lower_case_commands_are_refused() {
        assert_eq!(
            check(&command("  ", 7, Some(0))),
            (None, vec![("bad-value", 7)])
        );
        assert_eq!(
            check(&command("wait", 7, Some(0))),
            (None, vec![("unknown-verb", 7)])
        );
    }

    #[test]
    fn highlight_problems_point_at_the_bad_number() {
        let (spec, problems) = check(&command("HIGHLIGHT 0.1 0.2 0.35 0.25 ellipse", 7, Some(1)));
        assert_eq!(spec.map(|s| s.verb), Some(Verb::Highlight));
        assert!(problems.is_empty(), "{problems:?}");
        let (spec, problems) = check(&command("HIGHLIGHT", 7, Some(1)));
        assert_eq!(spec.and_then(|s| s.arg), None, "no argument clears");
        assert!(problems.is_empty(), "{problems:?}");
        // Column 7 is the quote; the argument starts at column 18.
        assert_eq!(
            check(&command("HIGHLIGHT 0.1 0.2 1.35 0.25", 7, Some(1))),
            (None, vec![("bad-argument", 26)])
        );
        assert_eq!(
            check(&command("HIGHLIGHT 0 0 1 1; 0.5 0.5 0.25 0.75", 7, Some(1))).1,
            [("bad-argument", 40)]
        );
        assert_eq!(
            check(&command("HIGHLIGHT 0.1 0.2 0.3", 7, None)).1,
            [("bad-argument", 7)]
        );
    }
}
