//! Parsing and checking the `VERB argument` strings of an act's `Cmds` list.
//!
//! The verb is the first word; the argument is everything after it, trimmed. Built-in verbs
//! have fixed argument rules; verbs declared in `docent.yaml` carry their own rule. File
//! arguments go through the bundle's path gate, exactly as the HTTP routes will later.

use std::cell::{OnceCell, RefCell};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

mod arguments;
mod files;
mod misplaced;

pub(crate) use files::path_error_code;
pub(crate) use misplaced::{acts_files_elsewhere, bundles_inside, folder_of_bundles, no_acts};

use crate::DiagnosticCode;
use crate::args::Args;
use crate::config::SiteConfig;
use crate::diagnostic::Diagnostic;
use crate::media::MediaSniffs;
use crate::model::{CommandSpec, Located, Pos, Verb};
use crate::paths::{BundleArea, Listing, PathError};
use crate::suggest::closest;

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

    /// The site settings the bundle is checked against.
    pub fn config(&self) -> &SiteConfig {
        self.config
    }

    /// The bundle's languages (pages in `pages/de/` fall back to `pages/`).
    pub fn languages(&self) -> &crate::config::Languages {
        &self.config.languages
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
                DiagnosticCode::BadValue,
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
                DiagnosticCode::UnknownVerb,
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
            out.push(Diagnostic::error(
                DiagnosticCode::BadArgument,
                &cmd.pos,
                message,
            ));
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
mod tests;
