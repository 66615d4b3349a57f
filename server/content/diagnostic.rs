//! Problems found in a bundle, each with a stable code, a place and a plain-language message
//! written for museum staff rather than programmers.

use std::fmt;

use serde::Serialize;

use crate::model::Pos;

/// How bad a problem is: errors stop `docent serve`, warnings do not, and notes are no
/// mistake at all (so `docent check --deny-warnings` passes a bundle with notes only).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    /// The bundle cannot be served until this is fixed.
    Error,
    /// Worth fixing; the bundle still runs.
    Warning,
    /// Something the author should know that is not a mistake (files ignored, media that
    /// Docent converts); nothing needs fixing.
    Note,
}

impl Severity {
    /// The word `docent check` prints and `--format json` carries: `error`, `warning`, `note`.
    pub fn as_str(self) -> &'static str {
        match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
            Severity::Note => "note",
        }
    }
}

impl fmt::Display for Severity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Defines [`DiagnosticCode`] and its words from one list, so a code is written once. Each row's
/// doc comment is the code's one-paragraph summary, and each code has its page,
/// `diagnostics/CODE.md` (severity, kind, fix, then a broken example and its fix), compiled in:
/// a code without its page does not build. `docent explain CODE` prints them and
/// `docs/DIAGNOSTICS.md` is generated from them ([`crate::explain`]).
///
/// To add a code: its row here, its page (copy one of the same kind), then
/// `DOCENT_BLESS=1 cargo test --locked -p docent-content --test content diagnostics_reference`
/// rewrites `docs/DIAGNOSTICS.md`; without `DOCENT_BLESS` that test fails while the file is
/// stale. A row's place here is its place in the reference's table.
macro_rules! diagnostic_codes {
    ($($(#[doc = $doc:literal])* $variant:ident = $text:literal,)*) => {
        /// A problem's stable code (`duplicate-label`, `unknown-verb`, ...): what `docent check
        /// --format json`, `/report` and the `bundle.refused` event carry, each explained in
        /// `docs/DIAGNOSTICS.md` and by `docent explain CODE`.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub enum DiagnosticCode {
            $($(#[doc = $doc])* $variant,)*
        }

        impl DiagnosticCode {
            /// Every code, in the order of the reference's tables.
            pub const ALL: &'static [DiagnosticCode] = &[$(DiagnosticCode::$variant,)*];

            /// The code as written (`duplicate-label`).
            pub fn as_str(self) -> &'static str {
                match self {
                    $(DiagnosticCode::$variant => $text,)*
                }
            }

            /// The lines of the code's doc comment above: its summary, as written.
            pub(crate) fn summary_lines(self) -> &'static [&'static str] {
                match self {
                    $(DiagnosticCode::$variant => &[$($doc),*],)*
                }
            }

            /// The code's page, `diagnostics/CODE.md`, as written.
            pub(crate) fn page_source(self) -> &'static str {
                match self {
                    $(DiagnosticCode::$variant => include_str!(concat!("diagnostics/", $text, ".md")),)*
                }
            }
        }
    };
}

diagnostic_codes! {
    /// The folder given to `docent check` or `docent serve` does not exist or is not a folder.
    NotABundle = "not-a-bundle",
    /// There is no `.yaml` or `.yml` acts file at the top of the bundle.
    NoActs = "no-acts",
    /// An acts file holds no acts (only comments, or nothing).
    EmptyFile = "empty-file",
    /// Docent could not open or read the file (permissions, for example).
    UnreadableFile = "unreadable-file",
    /// A YAML file is larger than 32 MB.
    FileTooLarge = "file-too-large",
    /// An acts file is a link to somewhere outside the bundle, or a `DISPLAY_PAGE`, `PROJECT`,
    /// `home` or `operator: map` path leaves `pages/` or `media/` (`..`, a leading `/`, a
    /// backslash, a drive letter, or a link pointing outside).
    PathOutsideBundle = "path-outside-bundle",
    /// The `home` page does not exist. An error when `home` is set in `docent.yaml`; a warning
    /// when the default `index.html` is missing.
    NoHomePage = "no-home-page",
    /// Files computers and editors leave in copied folders (`._name` Mac resource forks,
    /// `.DS_Store`, `Thumbs.db`, `desktop.ini`, editor backups `name~`, `.bak`, `.swp`, `.#name`)
    /// were found and ignored: one note for the whole bundle, saying how many of each.
    IgnoredFiles = "ignored-files",
    /// An acts file renamed so that Docent does not read it (`acts.yaml.bak`, `acts.yaml.old`,
    /// `acts.yaml.disabled`, `acts.yml~`, `acts.yaml.txt`) holds acts that no loaded acts file has:
    /// they are missing from the console and the pages. Once per file, naming how many acts it
    /// holds and which are missing. A renamed copy whose acts are all loaded counts among the
    /// `ignored-files`.
    DisabledActsFile = "disabled-acts-file",
    /// YAML cannot read the file at this place: an unclosed quote or bracket, a `: ` inside
    /// unquoted text, a stray indentation, a `---` line, a value starting with `*`, `&`, `!`,
    /// `@`, or a file not saved as UTF-8. Only the broken act is skipped; the rest of the file
    /// is still checked.
    YamlSyntax = "yaml-syntax",
    /// A line is indented with a tab. An error when it stops YAML from reading the file,
    /// otherwise a warning. Also used for `docent.yaml`.
    YamlTab = "yaml-tab",
    /// The file is not a list of acts (for example the acts have no `- `), or one item of the
    /// list is not an act (a bare text, or keys indented wrongly).
    NotAList = "not-a-list",
    /// The same key appears twice in one act (two `Text:` lines), or the same setting twice in
    /// `docent.yaml`.
    DuplicateKey = "duplicate-key",
    /// An act has no `Label`.
    MissingLabel = "missing-label",
    /// `Label:` is there but empty.
    EmptyLabel = "empty-label",
    /// Two acts have the same label, in the same file or in different files. Reported at both
    /// places, each naming the other.
    DuplicateLabel = "duplicate-label",
    /// An acts file repeats most labels of another acts file with texts in another language
    /// (`acts_de.yaml` beside `acts.yaml`): a translation in a file of its own. Reported once,
    /// at its first act, instead of a `duplicate-label` for each of its acts; its repeated acts
    /// are not used. Translations go beside the original, as `Text@de:`.
    TranslatedActsFile = "translated-acts-file",
    /// A key that is not `Label`, `Cmds`, `Group`, `Key` or a `Text...` key, often a typing or
    /// capital-letter slip (`Lable`, `label`, `textGroup`, `Commands`, `Grup`). The message
    /// suggests the right key when it can.
    UnknownKey = "unknown-key",
    /// A value has the wrong shape: a label that is a list, a text or command that YAML read as
    /// a key and value because of `: `, a list inside a list, an empty command, or a `Group`
    /// that is empty or a list.
    BadValue = "bad-value",
    /// A `Key` is not one letter (`A` to `Z`) or digit (`0` to `9`): empty, two letters,
    /// `Alt+W`, `F2`, an accented letter or a list.
    BadKey = "bad-key",
    /// Two acts have the same `Key` (`w` and `W` count as the same). Reported at the later act,
    /// naming the file and line of the first.
    DuplicateKeyBinding = "duplicate-key-binding",
    /// A `Text...` key, or one alternative, is empty (`Text:` with nothing, `[]`, `-` alone,
    /// `~`, `null`, or only spaces).
    EmptyText = "empty-text",
    /// A text or label is only `yes`, `no`, `on`, `off`, `true`, `false` or a number, without
    /// quotes. Docent keeps it as written.
    UnquotedScalar = "unquoted-scalar",
    /// An act has neither text nor commands, so triggering it does nothing.
    EmptyAct = "empty-act",
    /// An act has `Text...` variants (such as `TextChild`) but no `Text`, so it says nothing in
    /// any other context. Reported at the first variant key.
    NoDefaultText = "no-default-text",
    /// `docent.yaml` lists `contexts:` and this `Text...` key is not among them. Also used in
    /// `docent.yaml` for an `operator: visitor_groups` entry naming a context the bundle does
    /// not have.
    UnknownContext = "unknown-context",
    /// The first word of a command is not a known verb. Verbs are in capitals: `say` is not
    /// `SAY`. The message suggests the nearest verb or lists the known ones.
    UnknownVerb = "unknown-verb",
    /// The verb's argument is missing or wrong: `SAY`, `DISPLAY_PAGE` or `PROJECT` without
    /// anything after it, `DRIVE_START now`, `SET_WAYPOINT` without two or three numbers, `WAIT
    /// 2` without a unit, a `HIGHLIGHT` area that is not four fractions from 0 to 1 fitting on
    /// the projection (or has a shape other than `ellipse` or `rect`), or a site verb against
    /// its `argument:` rule.
    BadArgument = "bad-argument",
    /// A `SET_WAYPOINT` point lies outside the area set by `drive: bounds` in `docent.yaml`.
    WaypointOutOfBounds = "waypoint-out-of-bounds",
    /// The file named by `DISPLAY_PAGE`, `PROJECT` or `operator: map` does not exist, or is a
    /// folder. The message suggests a similar file name when there is one.
    MissingFile = "missing-file",
    /// The file exists, but with different upper and lower case (also for `home` and `operator:
    /// map`). The message gives the right spelling.
    MiscasedFile = "miscased-file",
    /// A text without quotes has ` #` in it: YAML reads ` #` as the start of a comment, so the
    /// text stops there (`- Talk in Room #4 at four` becomes "Talk in Room"). An error when a
    /// word or number follows the `#` or the text does not end a sentence; a warning for what
    /// looks like a note after a finished sentence.
    TextCutByComment = "text-cut-by-comment",
    /// A text without quotes goes on over several lines, and YAML joins them into one. An error
    /// when a following line starts with `- ` (a list item indented one space too far, or a
    /// first alternative without its own `- `, which swallowed the next ones); a warning
    /// otherwise (a missing `- `, or a long text wrapped by hand).
    JoinedLines = "joined-lines",
    /// A text starts with `–`, `—`, `−` or `•`: a word processor's dash or bullet, not YAML's
    /// `-`, so a whole list became one text.
    WordProcessorDash = "word-processor-dash",
    /// A text starts with `-` glued to a word (`-Hello`): YAML reads it as text, not as a list
    /// item, and the robot says the dash.
    DashWithoutSpace = "dash-without-space",
    /// A text is wrapped in typographic quotes (“…”, ‘…’, „…“, «…»). YAML only knows straight
    /// quotes, so the curly ones stay in the text.
    CurlyQuotes = "curly-quotes",
    /// A no-break space (from a word processor, a web page or an e-mail) sits where YAML needs
    /// a plain space: in the indentation, after the `-` of a list item, or after `Text:`. The
    /// line is not read as you see it.
    NonBreakingSpace = "non-breaking-space",
    /// The file is not saved as UTF-8: Windows "ANSI" (Windows-1252, the message names the
    /// character it found, such as `Ö`) or UTF-16 ("Unicode" in Notepad). Also for
    /// `docent.yaml`. A UTF-8 byte-order mark and Windows line ends (CRLF) are fine.
    FileEncoding = "file-encoding",
    /// A `.yaml` file (an acts file or `docent.yaml`) is not plain text at all: a Word
    /// document (`.docx`, `.doc`), an OpenDocument text (`.odt`), RTF, PDF, a spreadsheet,
    /// a ZIP archive or another binary file saved under that name. Reported at line 1, naming
    /// what the file is and how to save it as plain text.
    NotPlainText = "not-plain-text",
    /// The text has an emoji (😊, ❤, ⭐). The robot reads it by its name, "smiling face with
    /// smiling eyes".
    SpeechEmoji = "speech-emoji",
    /// The text has a web or e-mail address. The robot spells it sign by sign: "h t t p s colon
    /// slash slash".
    SpeechAddress = "speech-address",
    /// The text has HTML (`<b>`, `&amp;`) or Markdown (`**bold**`, `[link](url)`). Speech has
    /// no formatting; the robot reads the signs or stumbles.
    SpeechMarkup = "speech-markup",
    /// The text has a placeholder never filled in: `{name}`, `{{name}}`, `${name}`, `%s`,
    /// `[TIME]`, `TODO`, `XXX`, `TBD`, `Lorem ipsum`. Docent replaces nothing in texts.
    SpeechPlaceholder = "speech-placeholder",
    /// Saying the text takes longer than `speech.max_seconds` in `docent.yaml` (30 s unless
    /// set), estimated from the speaking rate (`speech.rate`, 160 words a minute unless set). A
    /// warning above the limit; an error above four times the limit (2 minutes by default),
    /// which is usually a pasted document.
    SpeechTooLong = "speech-too-long",
    /// Without `contexts:` in `docent.yaml`: a `Text...` key is one slip away from a name at least
    /// as many acts use (`TextChlid` beside `TextChild`; the message says "did you mean"), or is
    /// not `Text` followed by a capitalised word (`Textchild`, `Text_child`). A visitor in the
    /// context then hears the act's `Text`. A well-formed context only one act uses is fine.
    ContextTypo = "context-typo",
    /// Only in a bundle where some acts have a `Group` or `Key` (the operator's acts are sorted
    /// out): nothing triggers this act, which has neither. No page offers it (`data-act`) and it is
    /// not the kiosk's `idle_act`. In a bundle without any `Group` or `Key`, an act no page offers
    /// is the operator's button, as in the paper's Fig. 4, and not a problem.
    UnusedAct = "unused-act",
    /// A language in `languages:`, in `speech: voices:`, after the `@` of a text key or in
    /// `data-language` is not a short language tag. A language written by its name (`English`,
    /// `Deutsch`) gets its tag suggested, and in `languages:` is read as that tag meanwhile; so
    /// is a list written without brackets (`languages: en, de`).
    BadLanguage = "bad-language",
    /// A text (`Text@fr`), a voice or a `data-language` button names a language that is not in
    /// `languages:`; or a folder under `pages/` named like a language tag holds copies of pages
    /// (`pages/de/index.html`) when that language is not in `languages:` (reported once, at the
    /// folder's first page; its links are read as a language folder's).
    UnknownLanguage = "unknown-language",
    /// A text variant has no translation into one of the bundle's other languages: a visitor in
    /// that language hears the default text.
    MissingTranslation = "missing-translation",
    /// A translation (`TextChild@de`) whose act has no original (`TextChild`) in the default
    /// language.
    TranslationWithoutOriginal = "translation-without-original",
    /// A translation (`Text@fr`) has more or fewer texts than its original (`Text`). Text N
    /// goes with text N (the translators' table pairs them by number), so a missing one leaves
    /// a text untranslated and an extra one never appears in a table.
    TranslationCount = "translation-count",
    /// A translation is its original itself (`Text@de: [Welcome to the museum!]` beside `Text:
    /// [Welcome to the museum!]`): copied, not translated, so a visitor in that language hears the
    /// original. Reported at the text. A name, a number or a single word may stay the same: a text
    /// without letters (`1642`, `10:00–18:00`), one word (`Rembrandt`, `OK`), or words that each
    /// start with a capital letter (`Mona Lisa`, `Van Gogh Museum`).
    TranslationSameAsOriginal = "translation-same-as-original",
    /// A page of the default language has no version in one of the bundle's other languages
    /// (once per page and language): a visitor in that language sees the default page.
    MissingPageTranslation = "missing-page-translation",
    /// A language of `languages:` (not the default) that no page offers with a `data-language`
    /// button: visitors cannot choose it; only an operator or a dialog manager can. Reported at
    /// the language in `languages:`.
    LanguageUnreachable = "language-unreachable",
    /// `languages:` is written the wrong way round: its first language, the one of the plain
    /// `Text:` keys, is the one the acts' translations are in (`Text@de:`), and a later one
    /// has no translation at all, so the plain texts are in that one (`languages: [de, en]`
    /// over English `Text:` and German `Text@de:`). Reported once, at the first language; the
    /// acts and pages are checked in the order meant.
    LanguagesReversed = "languages-reversed",
    /// A language of `languages:` for which the kiosk shell has no words of its own (its "Stop
    /// speaking" button, its notices, the outage notice): neither built in (English, German,
    /// French, Spanish, Italian, Dutch) nor given in `kiosk: strings:`. Its visitors read the
    /// default language's words there. Reported at the language, naming the missing keys.
    ShellStringsMissing = "shell-strings-missing",
    /// When espeak-ng speaks the bundle (`speech: {adapter: espeak}`, or no adapter written and
    /// espeak-ng installed), from `docent check` on the computer it runs on:
    /// no installed espeak-ng voice speaks one of the bundle's languages (its voice in `speech:
    /// voices:`, or the language's own name, is not in `espeak-ng --voices`). Visitors in that
    /// language would hear espeak-ng's default voice.
    NoVoice = "no-voice",
    /// A page has `data-act="LABEL"` but no act has that label. Reported at the value in the
    /// page.
    UnknownAct = "unknown-act",
    /// YAML cannot read `docent.yaml`. The acts are then checked against the default settings.
    ConfigSyntax = "config-syntax",
    /// A setting Docent does not know, often a typing slip (`hoem`, `rat`). The message
    /// suggests the right name and lists the known ones.
    ConfigUnknownKey = "config-unknown-key",
    /// A setting has a value Docent cannot use. The message says what is allowed and what it
    /// found. The default is used meanwhile.
    ConfigBadValue = "config-bad-value",
    /// A token under `access:` is shorter than 16 characters, or holds a space or a character
    /// other than plain letters, digits and punctuation. The message never repeats the token.
    WeakCredential = "weak-credential",
    /// Two codes of `codebook:` have the same shortcut key (`Q` and `q` count as the same), in
    /// one tier or two. Reported at the later key, naming the code that has it first; the later
    /// code keeps no key.
    CodebookKeyTaken = "codebook-key-taken",
    /// A code's shortcut in `codebook:` is not one letter or one digit (`qq`, a space, a list).
    CodebookBadKey = "codebook-bad-key",
    /// `operator: map` is set but `drive: bounds` is not, so the console could not place the
    /// robot on the map. Reported at the map.
    MapNeedsBounds = "map-needs-bounds",
    /// Two opening-hours ranges of `schedule:` in `docent.yaml` cover the same time of one day
    /// (a weekday, or a special day): the kiosk cannot be in both. Reported at the range
    /// written second, once.
    ScheduleOverlap = "schedule-overlap",
    /// `priorities:` in `docent.yaml` lets visitors' taps cut the operator off: the kiosk's
    /// priority is higher than the operator's, or the same while speech is `when_busy: replace`.
    /// Reported at `kiosk:` (else at `operator:`).
    KioskOverOperator = "kiosk-over-operator",
    /// A `schedule: special_days:` date in `docent.yaml` is before today (by the clock of the
    /// computer running `docent check` or `docent serve`): most often last year's holiday,
    /// whose special hours will never apply again. Reported at the date.
    PastSpecialDay = "past-special-day",
    /// A reaction's `if:` in `docent.yaml` cannot be read: a field name missing, no comparison
    /// sign, text without double quotes, or words other than `and` between comparisons.
    /// Reported at the character concerned; the reaction is left out.
    ReactionBadCondition = "reaction-bad-condition",
    /// `drive: adapter: rosbridge` is set, or a `rosbridge:` section is written, but
    /// `rosbridge:` has no `url`, so Docent would never reach the robot. Reported at the
    /// drive's `adapter` or at the `rosbridge:` section.
    RosbridgeUrlMissing = "rosbridge-url-missing",
    /// `server: connections: per_address` in `docent.yaml` is more than `total` (written, or
    /// the default 1024): one address can never hold more connections than the whole server,
    /// so the file promises a site more than it gets. Reported at `per_address`.
    PerAddressOverTotal = "per-address-over-total",
    /// A comment `<!--` without `-->`, or a `<script>`, `<style>`, `<textarea>`, `<title>`,
    /// `<template>` (and similar) without its end tag, swallows the rest of the page: buttons
    /// after it never show. Reported at the opening tag; the message says which lines and how
    /// many `data-act` buttons are hidden. Also a start tag without its `>`, which swallows
    /// the text after it up to the next tag: reported where the `>` belongs.
    PageHiddenContent = "page-hidden-content",
    /// The quotes around a `data-act` value do not match (`data-act="WELCOME>`,
    /// `data-act=WELCOME"`) or are curly quotes from a word processor (`data-act=“WELCOME”`).
    ActQuoting = "act-quoting",
    /// A `data-act-after` value the page script cannot read (`20`, `20 sec`, `2,5s`, `1h`), so
    /// the act is never triggered.
    BadActDelay = "bad-act-delay",
    /// `data-act-after` on an element without `data-act`: there is no act to trigger.
    ActAfterWithoutAct = "act-after-without-act",
    /// An attribute that looks like a slip for `data-act` (`data-action`, `data_act`, `act`)
    /// on an element without `data-act`: the page script does not read it, so a touch does
    /// nothing.
    ActAttributeTypo = "act-attribute-typo",
    /// A page script calls `docent.trigger("LABEL")` for an act that no page offers with
    /// `data-act` (nor is the `idle_act`), so the touchscreen is refused it. A label matching
    /// no act is `unknown-act`.
    TriggerNotOffered = "trigger-not-offered",
    /// An `href`, `src`, `srcset` candidate, `poster`, CSS `url()` or `@import` in a page or a
    /// `.css` file under `pages/` leads to a missing file, to a file whose upper and lower case
    /// differ, outside `pages/` and `media/`, or to a file on your own computer (`C:\...`,
    /// `file:`). Links are read as the browser reads them: relative to the page's folder,
    /// `/pages/...` and `/media/...`, `%20` for spaces, `?v=2` and `#top` ignored.
    BrokenLink = "broken-link",
    /// A link to the internet: the kiosk does not open addresses outside the bundle, so an `<a
    /// href="https://...">` does nothing, and a picture or font from the internet may not load.
    ExternalLink = "external-link",
    /// A page is not saved as UTF-8: Windows-1252 ("ANSI", reported at the first letter that is
    /// not UTF-8) or UTF-16 ("Unicode"). A UTF-8 byte-order mark and Windows line ends are
    /// fine.
    PageEncoding = "page-encoding",
    /// A page declares another character set (`<meta charset="windows-1252">`, or `charset=` in
    /// an `http-equiv` tag): an error. A page with letters beyond plain English and no
    /// declaration at all: a warning, since the browser may guess wrongly.
    PageCharset = "page-charset",
    /// The page's markup could not be followed to the end (rare: a `<script>` or `<textarea>`
    /// inside `<svg>` or `<select>`), so the rest was not checked.
    PageNotChecked = "page-not-checked",
    /// A page's `<html lang>` names another language than its folder's: `lang="en"` on a page
    /// of `pages/de/`, or another language's tag on a page of the default language (directly
    /// in `pages/`). Checked when `languages:` is written; `en-gb` agrees with `en`.
    PageLanguageMismatch = "page-language-mismatch",
    /// A `<video autoplay>` or `<audio autoplay>` without `muted` on a page: its sound starts
    /// by itself and plays over the robot's speech.
    AutoplaySound = "autoplay-sound",
    /// A page the attract loop shows (`kiosk: attract: pages:`, or a schedule range's) holds a
    /// `<form>`, `<input>`, `<textarea>` or `<select>`: the first touch ends the loop and returns
    /// home, so it can never be filled in (a hidden `<input>` does not count). Once per page, at
    /// its first field.
    AttractPageForm = "attract-page-form",
    /// A `PROJECT` file, or a picture, video or sound of a page, is in a format neither
    /// Chromium nor Docent's converter can show (MIDI; see [Which picture and video formats
    /// work](#which-picture-and-video-formats-work-and-how-to-convert)), judged by its content;
    /// or a `PROJECT` file has an ending the projector does not show. The message says what to
    /// do.
    MediaUnplayable = "media-unplayable",
    /// A file's content does not match its name. An error when the name makes it shown as the
    /// wrong thing (a video named `.png`, a picture used as a video); a warning when it still
    /// shows (a PNG named `.jpg`).
    MediaMisnamed = "media-misnamed",
    /// A file named as a picture, video or sound holds something else (damaged, empty, or a web
    /// page saved under that name).
    MediaUnrecognised = "media-unrecognised",
    /// A note: a picture, video or sound file Chromium cannot show as it is (MPEG-1/2 `.mpg`,
    /// MPEG-TS, QuickTime `.mov`, AVI, Windows Media, Matroska, Flash, 3GP, Ogg Theora, HEIC,
    /// TIFF, BMP, Photoshop, JPEG 2000, JPEG XL, AIFF, AMR, RealMedia), or a picture more than
    /// 4096 pixels wide or high. Docent converts it once with ffmpeg when the bundle is served
    /// and shows the result under the same name; the file itself is not changed. Becomes a
    /// warning when ffmpeg is not installed on the computer running `docent check`.
    MediaConverted = "media-converted",
    /// A file Docent would convert (see `media-converted`) that ffmpeg cannot read: damaged,
    /// cut short, or not what its name says. ffmpeg's own words are quoted.
    MediaUndecodable = "media-undecodable",
    /// An SVG picture shown on the projector or with a page's `<img>` (or CSS) has a script
    /// (`<script>`, or an `onload=`-style handler): a browser runs no script in a picture, so
    /// what the script would draw stays blank. Once per file, at its first use.
    SvgScript = "svg-script",
}

impl Serialize for DiagnosticCode {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.as_str())
    }
}

impl fmt::Display for DiagnosticCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Tests and callers comparing with the written code (`d.code == "unused-act"`).
impl PartialEq<&str> for DiagnosticCode {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

/// One problem, as `docent check` reports it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Diagnostic {
    /// Error, warning or note.
    pub severity: Severity,
    /// Its stable code.
    pub code: DiagnosticCode,
    /// What is wrong and how to fix it, in plain words.
    pub message: String,
    /// File relative to the bundle root, `/`-separated.
    pub file: String,
    /// 1-based line; 1 when the problem concerns the whole file, never 0.
    pub line: u32,
    /// 1-based column in characters; 1 when the problem concerns the whole file, never 0.
    pub column: u32,
}

impl Diagnostic {
    /// An error at `pos`.
    pub fn error(code: DiagnosticCode, pos: &Pos, message: impl Into<String>) -> Self {
        Self::at(Severity::Error, code, pos, message)
    }

    /// A warning at `pos`.
    pub fn warning(code: DiagnosticCode, pos: &Pos, message: impl Into<String>) -> Self {
        Self::at(Severity::Warning, code, pos, message)
    }

    /// A note at `pos`: no mistake, something the author should know.
    pub fn note(code: DiagnosticCode, pos: &Pos, message: impl Into<String>) -> Self {
        Self::at(Severity::Note, code, pos, message)
    }

    fn at(severity: Severity, code: DiagnosticCode, pos: &Pos, message: impl Into<String>) -> Self {
        Diagnostic {
            severity,
            code,
            message: message.into(),
            file: pos.file.to_string(),
            line: pos.line,
            column: pos.column,
        }
    }

    /// True for errors.
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    /// True for warnings (not for errors, nor for notes).
    pub fn is_warning(&self) -> bool {
        self.severity == Severity::Warning
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}:{}: {}[{}]: {}",
            self.file, self.line, self.column, self.severity, self.code, self.message
        )
    }
}
