//! Parsing and checking the `VERB argument` strings of an act's `Cmds` list.
//!
//! The verb is the first word; the argument is everything after it, trimmed. Built-in verbs
//! have fixed argument rules; verbs declared in `docent.yaml` carry their own rule. File
//! arguments go through the bundle's path gate, exactly as the HTTP routes will later.

use std::cell::OnceCell;
use std::path::Path;
use std::sync::Arc;

use crate::content::config::{ArgRule, SiteConfig};
use crate::content::diagnostic::Diagnostic;
use crate::content::duration::parse_duration;
use crate::content::model::{CommandSpec, Located, Pos, Verb};
use crate::content::paths::{BundleArea, PathError, list_files, resolve_in_bundle};
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

/// Video and audio formats Chromium (kiosk and projector) cannot play.
const UNPLAYABLE_VIDEO: &[&str] = &[
    "mpg", "mpeg", "mpe", "m1v", "m2v", "vob", "avi", "wmv", "asf", "flv", "f4v", "rm", "rmvb",
    "3gp", "3g2",
];
const UNPLAYABLE_AUDIO: &[&str] = &["wma", "aif", "aiff", "amr", "mid", "midi", "ra"];

/// Checks commands against the site settings and the bundle's files.
pub(crate) struct CommandChecker<'a> {
    root: &'a Path,
    config: &'a SiteConfig,
    /// File listings for suggestions, made only when a file is missing.
    pages: OnceCell<Vec<String>>,
    media: OnceCell<Vec<String>>,
}

impl<'a> CommandChecker<'a> {
    /// A checker for the bundle at the canonical `root`.
    pub fn new(root: &'a Path, config: &'a SiteConfig) -> Self {
        CommandChecker {
            root,
            config,
            pages: OnceCell::new(),
            media: OnceCell::new(),
        }
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
        let arg_pos = self.offset_pos(cmd, arg_start);
        let before = out.iter().filter(|d| d.is_error()).count();
        self.check_argument(&verb, arg, cmd, arg_start, &arg_pos, out);
        if out.iter().filter(|d| d.is_error()).count() > before {
            return None;
        }
        let spec = CommandSpec {
            verb,
            arg: arg.map(str::to_owned),
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
        let bad = |out: &mut Vec<Diagnostic>, pos: &Pos, msg: String| {
            out.push(Diagnostic::error("bad-argument", pos, msg))
        };
        match (verb, arg) {
            (Verb::Say, None) => bad(out, &cmd.pos, "SAY needs the text to speak, e.g. `SAY Welcome to the museum`.".into()),
            (Verb::Project, None) => bad(out, &cmd.pos, "PROJECT needs a file from the media folder, e.g. `PROJECT Exhibit/video.webm`.".into()),
            (Verb::DisplayPage, None) => bad(out, &cmd.pos, "DISPLAY_PAGE needs a page from the pages folder, e.g. `DISPLAY_PAGE Welcome/Welcome.html`.".into()),
            (Verb::Project, Some(file)) => {
                self.check_file(BundleArea::Media, file, arg_pos, out);
                media_format(file, arg_pos, out);
            }
            (Verb::DisplayPage, Some(file)) => self.check_file(BundleArea::Pages, file, arg_pos, out),
            (Verb::SetWaypoint, _) => self.check_waypoint(arg.unwrap_or(""), cmd, arg_start, out),
            (Verb::DriveStart | Verb::DriveStop, Some(extra)) => {
                bad(out, arg_pos, format!("{verb} takes nothing after it. Remove `{extra}`."));
            }
            (Verb::Wait, Some(wait)) if parse_duration(wait).is_none() => bad(out, arg_pos, format!(
                "`{wait}` is not a length of time. Write `WAIT` alone to wait until the act's \
                 earlier commands are done, or a time with its unit such as `WAIT 2s` or `WAIT 500ms`."
            )),
            (Verb::Site(name), _) => {
                let rule = self.config.verbs.get(name.as_ref()).map_or(ArgRule::Optional, |v| v.argument);
                match (rule, arg) {
                    (ArgRule::Required, None) => bad(out, &cmd.pos, format!(
                        "{name} needs something after it (docent.yaml says `argument: required`)."
                    )),
                    (ArgRule::None, Some(extra)) => bad(out, arg_pos, format!(
                        "{name} takes nothing after it (docent.yaml says `argument: none`). Remove `{extra}`."
                    )),
                    _ => {}
                }
            }
            _ => {}
        }
    }

    fn check_waypoint(
        &self,
        arg: &str,
        cmd: &WrittenCommand,
        arg_start: usize,
        out: &mut Vec<Diagnostic>,
    ) {
        let usage = "SET_WAYPOINT needs two or three numbers: x and y in metres, and optionally \
                     the heading, e.g. `SET_WAYPOINT 3.5 2` or `SET_WAYPOINT 3.5 2 90`.";
        let words = words_with_offsets(arg, arg_start);
        if !(2..=3).contains(&words.len()) {
            let pos = if words.is_empty() {
                cmd.pos.clone()
            } else {
                self.offset_pos(cmd, arg_start)
            };
            out.push(Diagnostic::error(
                "bad-argument",
                &pos,
                format!("Found {} value(s). {usage}", words.len()),
            ));
            return;
        }
        let mut numbers = Vec::with_capacity(3);
        for &(offset, word) in &words {
            match word.parse::<f64>() {
                Ok(n) if n.is_finite() => numbers.push(n),
                _ => {
                    let pos = self.offset_pos(cmd, offset);
                    out.push(Diagnostic::error(
                        "bad-argument",
                        &pos,
                        format!("`{word}` is not a number. {usage}"),
                    ));
                }
            }
        }
        let (Some(bounds), [x, y, ..]) = (self.config.drive.bounds, numbers.as_slice()) else {
            return;
        };
        if numbers.len() == words.len() && !bounds.contains(*x, *y) {
            let pos = self.offset_pos(cmd, arg_start);
            out.push(Diagnostic::error("waypoint-out-of-bounds", &pos, format!(
                "The point ({x}, {y}) lies outside the area the robot may drive in: x from {} to {}, \
                 y from {} to {} (set in docent.yaml under `drive: bounds`).",
                bounds.min_x, bounds.max_x, bounds.min_y, bounds.max_y
            )));
        }
    }

    fn check_file(&self, area: BundleArea, rel: &str, pos: &Pos, out: &mut Vec<Diagnostic>) {
        if let Some((err, message)) = self.path_problem(area, rel) {
            out.push(Diagnostic::error(path_error_code(&err), pos, message));
        }
    }

    /// Why `rel` is not a usable file under `area`, in words, or `None` when it is.
    pub fn path_problem(&self, area: BundleArea, rel: &str) -> Option<(PathError, String)> {
        let err = resolve_in_bundle(self.root, area, rel).err()?;
        let folder = area.dir_name();
        let message = match &err {
            PathError::Outside => format!(
                "`{rel}` leads outside the {folder} folder. Write the file's path relative to \
                 `{folder}/`, without `..`, a leading `/`, backslashes or a drive letter; links \
                 pointing outside the bundle are refused too."
            ),
            PathError::Miscased { actual } => format!(
                "The file is called `{actual}`, with different upper and lower case. Write it \
                 exactly like that: on the robot `{rel}` and `{actual}` are different names."
            ),
            PathError::NotAFile => {
                format!("`{folder}/{rel}` is a folder, not a file. Name a file inside it.")
            }
            PathError::NotFound => {
                let files = self.listing(area);
                let hint = closest(rel, files.iter().map(String::as_str))
                    .map_or_else(String::new, |s| format!(" Did you mean `{s}`?"));
                format!("There is no file `{folder}/{rel}`.{hint}")
            }
        };
        Some((err, message))
    }

    fn listing(&self, area: BundleArea) -> &[String] {
        let cell = match area {
            BundleArea::Pages => &self.pages,
            BundleArea::Media => &self.media,
        };
        cell.get_or_init(|| list_files(self.root, area))
    }

    /// The position `byte` bytes into the command text, when the text is verbatim in the file.
    fn offset_pos(&self, cmd: &WrittenCommand, byte: usize) -> Pos {
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
}

/// The diagnostic code for a path refused by the gate.
pub(crate) fn path_error_code(err: &PathError) -> &'static str {
    match err {
        PathError::Outside => "path-outside-bundle",
        PathError::Miscased { .. } => "miscased-file",
        PathError::NotFound | PathError::NotAFile => "missing-file",
    }
}

fn media_format(file: &str, pos: &Pos, out: &mut Vec<Diagnostic>) {
    let Some((_, ext)) = file.rsplit_once('.') else {
        return;
    };
    let ext = ext.to_ascii_lowercase();
    let advice = if UNPLAYABLE_VIDEO.contains(&ext.as_str()) {
        "Convert the video to WebM (VP9 or AV1 video with Opus sound), or to MP4 with H.264 video."
    } else if UNPLAYABLE_AUDIO.contains(&ext.as_str()) {
        "Convert the sound to WebM or Ogg with Opus, or to MP3."
    } else {
        return;
    };
    out.push(Diagnostic::warning(
        "media-format",
        pos,
        format!("The projector's browser (Chromium) cannot play `.{ext}` files. {advice}"),
    ));
}

/// The words of `s` with their byte offsets, shifted by `base`.
fn words_with_offsets(s: &str, base: usize) -> Vec<(usize, &str)> {
    let mut words = Vec::new();
    let mut rest = s;
    let mut offset = base;
    while let Some(start) = rest.find(|c: char| !c.is_whitespace()) {
        let tail = &rest[start..];
        let end = tail.find(char::is_whitespace).unwrap_or(tail.len());
        words.push((offset + start, &tail[..end]));
        offset += start + end;
        rest = &tail[end..];
    }
    words
}
