//! The loaded form of a content bundle: acts, their text variants and commands, each with the
//! place it was written. Everything here is plain data, built by the loader and read by the
//! dispatcher, the HTTP API and the checker; nothing here touches the file system.

use std::collections::{BTreeMap, HashMap};
use std::fmt;
use std::path::PathBuf;
use std::sync::Arc;

use crate::args::Args;
use crate::config::SiteConfig;
use crate::diagnostic::Diagnostic;
use crate::language::Language;

/// Where something was written: a file relative to the bundle root, 1-based line and column.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
pub struct Pos {
    /// Path relative to the bundle root, with `/` separators (e.g. `acts.yaml`).
    pub file: Arc<str>,
    /// 1-based line.
    pub line: u32,
    /// 1-based column, counted in characters.
    pub column: u32,
}

impl Pos {
    /// The start of `file` (1:1): for problems that concern a whole file, and for a missing
    /// file at the place it was expected.
    pub fn start_of(file: impl Into<Arc<str>>) -> Self {
        Pos::new(file, 1, 1)
    }

    /// A position in `file` at `line`:`column`.
    pub fn new(file: impl Into<Arc<str>>, line: u32, column: u32) -> Self {
        Pos {
            file: file.into(),
            line,
            column,
        }
    }
}

impl fmt::Display for Pos {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file, self.line, self.column)
    }
}

/// A value together with the place it was written.
#[derive(Clone, Debug, PartialEq)]
pub struct Located<T> {
    /// The value itself.
    pub value: T,
    /// Where it was written.
    pub pos: Pos,
}

/// The name of the default text variant every act falls back to.
pub const DEFAULT_VARIANT: &str = "Text";

/// One dialog act (paper, Fig. 4): a unique label, text variants and commands.
#[derive(Clone, Debug)]
pub struct Act {
    /// The unique label (`WELCOME`).
    pub label: String,
    /// Where the label's value was written.
    pub pos: Pos,
    /// Text variants in the order written (`Text`, `TextGroup`, ...). May be empty.
    pub variants: Vec<Variant>,
    /// The act's commands in the order written, without the implicit SAY.
    pub commands: Vec<Located<CommandSpec>>,
    /// The operator console's group for the act (`Group:`), when written. See
    /// [`Act::group_name`] for the group shown when it is not.
    pub group: Option<String>,
    /// The console shortcut (`Key:`): `A`-`Z` or `0`-`9`, stored upper case. Alt+key fires
    /// the act; no two acts of a bundle share a key.
    pub key: Option<char>,
    /// Words the console's search also finds the act by (`Keywords:`): what the act means
    /// that it neither says nor shows (`film` for a projected video). Never spoken.
    pub keywords: Vec<String>,
}

impl Act {
    /// The console group: `Group` when written, else the acts file's name without its
    /// extension (`smalltalk` for `smalltalk.yaml`).
    pub fn group_name(&self) -> &str {
        if let Some(group) = &self.group {
            return group;
        }
        let file = self.pos.file.rsplit('/').next().unwrap_or_default();
        match file.rsplit_once('.') {
            Some((stem, ext))
                if ext.eq_ignore_ascii_case("yaml") || ext.eq_ignore_ascii_case("yml") =>
            {
                stem
            }
            _ => file,
        }
    }

    /// The variant named `name`, if the act has it.
    pub fn variant(&self, name: &str) -> Option<&Variant> {
        self.variants.iter().find(|v| v.name == name)
    }
}

/// One named list of alternative texts (`TextGroup: [...]`).
#[derive(Clone, Debug)]
pub struct Variant {
    /// The key as written (`Text`, `TextGroup`, `TextChild`, ...).
    pub name: String,
    /// Where the key was written.
    pub pos: Pos,
    /// The alternatives, at least one, in the bundle's default language.
    pub alternatives: Vec<Located<String>>,
    /// The same texts in the bundle's other languages (`TextChild@de:` beside `TextChild:`),
    /// by language; a language missing here speaks the default language's texts.
    pub translations: BTreeMap<Language, Translation>,
}

impl Variant {
    /// The alternatives in `language` and the language they are in: the translation when
    /// there is one, else the default language's texts (`None` for `default` then).
    pub fn in_language(&self, language: &Language) -> (&[Located<String>], Option<&Language>) {
        match self.translations.get_key_value(language) {
            Some((language, translation)) => (&translation.alternatives, Some(language)),
            None => (&self.alternatives, None),
        }
    }
}

/// A variant's texts in one of the bundle's other languages (`TextChild@de:`). Translators
/// name each text by its stable key `LABEL/Variant/N` (N from 1, in written order).
#[derive(Clone, Debug)]
pub struct Translation {
    /// Where the key (`TextChild@de`) was written.
    pub pos: Pos,
    /// The alternatives, at least one.
    pub alternatives: Vec<Located<String>>,
}

/// The closed set of built-in verbs (paper, Table 1, plus `WAIT` and `HIGHLIGHT`); verbs a
/// site declares in `docent.yaml` are [`Verb::Site`].
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Verb {
    /// `SAY text`: speak the text.
    Say,
    /// `PROJECT file`: show an image or video from `media/` on the projector.
    Project,
    /// `DISPLAY_PAGE file`: show a page from `pages/` on the touchscreen.
    DisplayPage,
    /// `SET_WAYPOINT x y [heading]`: set the drive target in map coordinates.
    SetWaypoint,
    /// `DRIVE_START`: start or continue driving to the waypoint; done on arrival.
    DriveStart,
    /// `DRIVE_STOP`: stop driving; preempts everything.
    DriveStop,
    /// `WAIT` (until the act's earlier commands are done) or `WAIT 2s` (pause).
    Wait,
    /// `HIGHLIGHT left top width height [ellipse]; ...`: light areas of the projected image in
    /// white on black; `HIGHLIGHT` alone turns the light off.
    Highlight,
    /// A verb declared in `docent.yaml`, routed with its argument to the adapter named there.
    Site(Arc<str>),
}

impl Verb {
    /// Every built-in verb, in the order the docs list them.
    pub const BUILT_IN: [Verb; 8] = [
        Verb::Say,
        Verb::Project,
        Verb::Highlight,
        Verb::DisplayPage,
        Verb::SetWaypoint,
        Verb::DriveStart,
        Verb::DriveStop,
        Verb::Wait,
    ];

    /// The verb as written in acts files and sent on the wire.
    pub fn as_str(&self) -> &str {
        match self {
            Verb::Say => "SAY",
            Verb::Project => "PROJECT",
            Verb::DisplayPage => "DISPLAY_PAGE",
            Verb::SetWaypoint => "SET_WAYPOINT",
            Verb::DriveStart => "DRIVE_START",
            Verb::DriveStop => "DRIVE_STOP",
            Verb::Wait => "WAIT",
            Verb::Highlight => "HIGHLIGHT",
            Verb::Site(name) => name,
        }
    }

    /// The built-in verb spelled exactly `word`, if any.
    pub fn built_in(word: &str) -> Option<Verb> {
        Verb::BUILT_IN.into_iter().find(|v| v.as_str() == word)
    }
}

impl fmt::Display for Verb {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// One command of an act: a verb and its argument (everything after the first space, trimmed),
/// as written and parsed.
#[derive(Clone, Debug, PartialEq)]
pub struct CommandSpec {
    /// What to do.
    pub verb: Verb,
    /// The argument as written, or `None` when there is none (for logs and the corpus).
    pub arg: Option<String>,
    /// The argument parsed: what the dispatcher and the devices act on.
    pub args: Args,
}

/// A loaded, checked content bundle. Only the loader builds one, and only when it has no errors.
#[derive(Debug)]
pub struct Bundle {
    /// The bundle folder, canonicalized.
    pub root: PathBuf,
    /// All acts of all acts files, in file-name order, then in written order.
    pub acts: Vec<Act>,
    /// Label to index into `acts`.
    pub index: HashMap<String, usize>,
    /// Site settings from `docent.yaml` (defaults when absent).
    pub config: SiteConfig,
    /// Every variant name usable as a context: `Text`, then declared or found names, sorted.
    pub contexts: Vec<String>,
    /// Labels that the bundle's pages trigger through `data-act` (what a kiosk may trigger).
    pub page_acts: Vec<String>,
    /// Every `data-act` value of the pages, in file order, with its place in the page.
    pub page_offers: Vec<Located<String>>,
    /// The languages pages offer through `data-language` buttons: (page inside `pages/`,
    /// language). A kiosk may switch only to a language its page offers.
    pub page_languages: Vec<(String, Language)>,
    /// The warnings and notes found while loading (a bundle has no errors), for the content
    /// report.
    pub diagnostics: Vec<Diagnostic>,
    /// Media files Docent converts before showing them (formats Chromium cannot show, and
    /// pictures far larger than any screen), each once, where first used.
    pub conversions: Vec<crate::media::convert::Conversion>,
    /// The `corpus_fingerprint` of the files it was loaded from, set by whoever puts it live
    /// (start-up, live reload) so that each trigger can name the bundle it was resolved in;
    /// `None` before that, or when a file could not be read.
    pub fingerprint: Option<std::sync::Arc<str>>,
}

impl Bundle {
    /// The act labelled `label`.
    pub fn act(&self, label: &str) -> Option<&Act> {
        self.index.get(label).map(|&i| &self.acts[i])
    }

    /// Whether the page `page` (as the kiosk names it, in the default language) offers
    /// `language` in any of its language versions (`pages/de/page` too).
    pub fn page_offers_language(&self, page: &str, language: &Language) -> bool {
        let languages = &self.config.languages;
        let logical = |rel: &str| languages.page_fallback(rel).unwrap_or(rel).to_owned();
        (self.page_languages.iter())
            .any(|(rel, offered)| offered == language && logical(rel) == logical(page))
    }

    /// Every label, in loaded order.
    pub fn labels(&self) -> impl Iterator<Item = &str> {
        self.acts.iter().map(|a| a.label.as_str())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn act(file: &str, group: Option<&str>) -> Act {
        Act {
            label: "A".to_owned(),
            pos: Pos::new(file, 1, 10),
            variants: Vec::new(),
            commands: Vec::new(),
            group: group.map(str::to_owned),
            key: None,
            keywords: Vec::new(),
        }
    }

    #[test]
    fn the_console_group_defaults_to_the_acts_file_name() {
        assert_eq!(act("smalltalk.yaml", None).group_name(), "smalltalk");
        assert_eq!(act("tour.yml", None).group_name(), "tour");
        assert_eq!(act("Tour.YAML", None).group_name(), "Tour");
        assert_eq!(act("notes.txt", None).group_name(), "notes.txt");
        assert_eq!(act("tour.yaml", Some("Stop 1")).group_name(), "Stop 1");
    }
}
