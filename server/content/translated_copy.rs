//! An acts file that is another's translation: an author copies `acts.yaml` to `acts_de.yaml`
//! (or `acts-de.yml`, `acts.de.yaml`, `tour_deutsch.yaml`) and translates the texts, keeping
//! the labels. Docent reads each label once, so every act of the copy would be a
//! `duplicate-label`, whose advice ("rename one of them") is the wrong way. Found before the
//! acts are merged: such a file is told once, at its first act, that translations go beside
//! the original as `Text@de:`, and its repeated acts are left out without a duplicate each.
//! The same for a copy put in a folder (`de/acts.yaml`), which Docent never reads: without
//! this, its acts vanish without a word.
//!
//! A file is a translated copy of another when more than half of its labels are the other's
//! (at least two, or one in a file whose name carries a language) and its texts are in another
//! language: its name carries a language other than the other's, or its texts differ from the
//! originals in most repeated acts and are in another language by their common words (or share
//! few words with them). A copy with the same texts is a real duplicate, and told as one.

use std::collections::{BTreeMap, HashMap, HashSet};
use std::fmt::Write as _;
use std::path::Path;
use std::sync::Arc;

use crate::acts_file::{ActsFile, read_acts_file};
use crate::config::{Language, SiteConfig};
use crate::diagnostic::{Diagnostic, DiagnosticCode};
use crate::gather::{CheckedFile, read_limited};
use crate::model::{Located, Variant};

/// The acts files found to be translations of another, by file name, with the labels they
/// repeat: those acts are left out of the bundle without a `duplicate-label` each.
#[derive(Default)]
pub(crate) struct TranslatedCopies {
    repeated: BTreeMap<Arc<str>, HashSet<String>>,
}

impl TranslatedCopies {
    /// Whether the act `label` of `file` is a translation of an act of another file.
    pub(crate) fn leaves_out(&self, file: &str, label: &str) -> bool {
        self.repeated.get(file).is_some_and(|l| l.contains(label))
    }
}

/// One acts file as compared here: its name, its acts' labels and texts.
struct FileTexts<'f> {
    name: Arc<str>,
    acts: Vec<(&'f Located<String>, &'f [Variant])>,
    labels: HashSet<&'f str>,
    /// The language its name carries (`acts_de.yaml`, `de/acts.yaml`), if any.
    named: Option<Language>,
    /// An acts file at the top of the bundle; `false` for one in a folder, which Docent does
    /// not read (`de/acts.yaml`): only ever a copy, never an original.
    loaded: bool,
}

impl<'f> FileTexts<'f> {
    fn new(
        name: Arc<str>,
        acts: Vec<(&'f Located<String>, &'f [Variant])>,
        config: &SiteConfig,
        loaded: bool,
    ) -> Self {
        FileTexts {
            named: language_in_name(&name, config),
            labels: acts.iter().map(|(l, _)| l.value.as_str()).collect(),
            name,
            acts,
            loaded,
        }
    }
}

/// Acts files in folders at the top of the bundle (`de/acts.yaml`; not `pages/`, `media/` or
/// hidden ones), read only to be compared: Docent reads acts files at the top alone.
fn folder_acts_files(root: &Path, config: &SiteConfig) -> Vec<ActsFile> {
    let mut names: Vec<String> = Vec::new();
    for folder in std::fs::read_dir(root).into_iter().flatten().flatten() {
        let Ok(folder_name) = folder.file_name().into_string() else {
            continue;
        };
        let skipped =
            folder_name.starts_with('.') || ["pages", "media"].contains(&folder_name.as_str());
        if skipped || !folder.file_type().is_ok_and(|t| t.is_dir()) {
            continue;
        }
        for entry in std::fs::read_dir(folder.path())
            .into_iter()
            .flatten()
            .flatten()
        {
            let Ok(name) = entry.file_name().into_string() else {
                continue;
            };
            let lower = name.to_ascii_lowercase();
            let yaml = lower.ends_with(".yaml") || lower.ends_with(".yml");
            if yaml && !name.starts_with('.') && entry.file_type().is_ok_and(|t| t.is_file()) {
                names.push(format!("{folder_name}/{name}"));
            }
        }
    }
    names.sort();
    (names.into_iter())
        .filter_map(|name| {
            let file: Arc<str> = Arc::from(name.as_str());
            let bytes = read_limited(&root.join(&name), &file).ok()?;
            Some(read_acts_file(
                &file,
                &bytes,
                &config.speech,
                &config.languages,
            ))
        })
        .collect()
}

/// Finds the acts files that translate another and tells each once: among the loaded `files`,
/// and the acts files in folders of `root`, which are not loaded.
pub(crate) fn find_translated_copies(
    root: &Path,
    files: &[CheckedFile],
    config: &SiteConfig,
    out: &mut Vec<Diagnostic>,
) -> TranslatedCopies {
    let in_folders = folder_acts_files(root, config);
    let default = config.languages.default_language();
    let loaded = (files.iter()).filter_map(|f| {
        let name = f.acts.first()?.label.pos.file.clone();
        let acts = (f.acts.iter()).map(|a| (&a.label, a.variants.as_slice()));
        Some(FileTexts::new(name, acts.collect(), config, true))
    });
    let unloaded = (in_folders.iter()).filter_map(|f| {
        let acts: Vec<_> = (f.acts.iter())
            .filter_map(|a| Some((a.label.as_ref()?, a.variants.as_slice())))
            .collect();
        let name = acts.first()?.0.pos.file.clone();
        Some(FileTexts::new(name, acts, config, false))
    });
    let texts: Vec<FileTexts> = loaded.chain(unloaded).collect();
    let mut copies = TranslatedCopies::default();
    for copy in &texts {
        let Some(original) = (texts.iter())
            .filter(|o| o.loaded && o.name != copy.name && !copies.repeated.contains_key(&o.name))
            .find(|o| is_translation_of(copy, o, default))
        else {
            continue;
        };
        let repeated = repeated_labels(copy, original);
        out.push(told(copy, original, repeated.len(), config));
        copies.repeated.insert(copy.name.clone(), repeated);
    }
    copies
}

/// The labels of `copy` that `original` has too.
fn repeated_labels(copy: &FileTexts, original: &FileTexts) -> HashSet<String> {
    (copy.labels.iter())
        .filter(|l| original.labels.contains(*l))
        .map(|l| (*l).to_owned())
        .collect()
}

fn is_translation_of(copy: &FileTexts, original: &FileTexts, default: &Language) -> bool {
    let repeated = copy.labels.intersection(&original.labels).count();
    let least = if copy.named.is_some() { 1 } else { 2 };
    if repeated < least || repeated * 2 <= copy.labels.len() {
        return false;
    }
    match (&copy.named, &original.named) {
        // `acts_de.yaml` beside `acts.yaml` or `acts_en.yaml`: the one named otherwise than the
        // default language is the translation (of two named others, the first in file order).
        (Some(mine), Some(theirs)) => mine != theirs && (theirs == default || mine != default),
        (Some(mine), None) => mine != default,
        // `acts.yaml` beside `acts_en.yaml`, English the default: the texts tell.
        (None, Some(theirs)) => {
            theirs == default && texts_in_another_language(copy, original, default)
        }
        (None, None) => texts_in_another_language(copy, original, default),
    }
}

/// Neither name says: the copy's texts differ from most originals, in another language by
/// their common words (the original's being the default language, or unknown), or sharing few
/// words with them.
fn texts_in_another_language(copy: &FileTexts, original: &FileTexts, default: &Language) -> bool {
    let originals: HashMap<&str, &[Variant]> = (original.acts.iter())
        .map(|(l, v)| (l.value.as_str(), *v))
        .collect();
    let (mut compared, mut differing) = (0, 0);
    let (mut mine, mut theirs) = (Vec::new(), Vec::new());
    for (label, variants) in &copy.acts {
        let Some(other) = originals.get(label.value.as_str()) else {
            continue;
        };
        let (a, b): (Vec<&str>, Vec<&str>) = (
            plain_texts(variants).collect(),
            plain_texts(other).collect(),
        );
        if a.is_empty() || b.is_empty() {
            continue;
        }
        compared += 1;
        differing += usize::from(a != b);
        mine.extend(a);
        theirs.extend(b);
    }
    if compared == 0 || differing * 2 <= compared {
        return false;
    }
    let guessed = (
        guess_language(mine.iter().copied()),
        guess_language(theirs.iter().copied()),
    );
    match guessed {
        (Some(c), Some(o)) => c != o && (o == default.as_str() || c != default.as_str()),
        (Some(c), None) => c != default.as_str(),
        (None, Some(_)) => false,
        (None, None) => {
            let mine: HashSet<String> = mine.iter().flat_map(|t| words(t)).collect();
            let theirs: HashSet<String> = theirs.iter().flat_map(|t| words(t)).collect();
            let shared = mine.intersection(&theirs).count();
            shared * 3 < mine.len().min(theirs.len())
        }
    }
}

/// The texts of an act's plain `Text` variant.
pub(crate) fn plain_texts(variants: &[Variant]) -> impl Iterator<Item = &str> {
    (variants.iter())
        .filter(|v| v.name == "Text")
        .flat_map(|v| v.alternatives.iter().map(|a| a.value.as_str()))
}

/// The words of a text, lower case, of letters only.
fn words(text: &str) -> impl Iterator<Item = String> + '_ {
    text.split(|c: char| !c.is_alphabetic())
        .filter(|w| !w.is_empty())
        .map(str::to_lowercase)
}

/// The language a file's name carries: a part of it (split at `_`, `-`, `.`, a space or a
/// folder) that is one of the bundle's languages, a common language's tag, or a language's
/// name (`acts_de.yaml`, `tour-FR.yml`, `acts.deutsch.yaml`). The first part is the file's own
/// name, never a language (`de.yaml` is a file named "de").
fn language_in_name(name: &str, config: &SiteConfig) -> Option<Language> {
    let stem = name.rsplit_once('.').map_or(name, |(stem, _)| stem);
    let mut parts = stem
        .split(['_', '-', '.', ' ', '/'])
        .filter(|p| !p.is_empty());
    let first = parts.next();
    let folder = name.contains('/').then_some(first).flatten();
    folder.into_iter().chain(parts).find_map(|part| {
        let lower = part.to_ascii_lowercase();
        (config.languages.find(&lower).cloned())
            .or_else(|| Language::common(&lower))
            .or_else(|| Language::from_name(part))
    })
}

/// Very common words of the languages most often written beside one another in a museum,
/// enough to tell which one a file's texts are in.
const COMMON_WORDS: &[(&str, &[&str])] = &[
    (
        "en",
        &[
            "the", "and", "is", "you", "this", "of", "to", "with", "here", "are", "it", "we",
        ],
    ),
    (
        "de",
        &[
            "der", "die", "das", "und", "ist", "sie", "ein", "eine", "nicht", "hier", "mit", "wir",
            "ich", "zu",
        ],
    ),
    (
        "fr",
        &[
            "le", "la", "les", "et", "est", "vous", "une", "des", "ici", "avec", "nous", "je",
        ],
    ),
    (
        "es",
        &[
            "el", "los", "las", "y", "es", "usted", "una", "del", "aquí", "con", "nosotros", "yo",
        ],
    ),
    (
        "it",
        &[
            "il", "gli", "della", "e", "è", "una", "del", "qui", "con", "noi", "io", "sono",
        ],
    ),
    (
        "nl",
        &[
            "de", "het", "een", "en", "is", "u", "hier", "met", "wij", "ik", "van", "niet",
        ],
    ),
];

/// The language of `texts` by their common words: the one with most of them (at least three,
/// and more than any other), or `None`.
pub(crate) fn guess_language<'t>(texts: impl Iterator<Item = &'t str>) -> Option<&'static str> {
    let mut counts = [0usize; COMMON_WORDS.len()];
    for word in texts.flat_map(words) {
        for (i, (_, common)) in COMMON_WORDS.iter().enumerate() {
            counts[i] += usize::from(common.contains(&word.as_str()));
        }
    }
    let best = (0..counts.len()).max_by_key(|&i| counts[i])?;
    let second = (0..counts.len())
        .filter(|&i| i != best)
        .map(|i| counts[i])
        .max();
    (counts[best] >= 3 && Some(counts[best]) > second).then(|| COMMON_WORDS[best].0)
}

fn told(
    copy: &FileTexts,
    original: &FileTexts,
    repeated: usize,
    config: &SiteConfig,
) -> Diagnostic {
    let guessed = || guess_language(copy.acts.iter().flat_map(|(_, v)| plain_texts(v)));
    let language = (copy.named.clone()).or_else(|| guessed().and_then(Language::parse));
    let first = copy.acts[0].0;
    let example = (copy.acts.iter())
        .map(|(l, _)| l.value.as_str())
        .find(|l| original.labels.contains(l))
        .unwrap_or(first.value.as_str());
    let (file, theirs) = (&copy.name, &original.name);
    let unread = if copy.loaded {
        String::new()
    } else {
        " (and Docent reads acts files only at the top of the bundle folder)".to_owned()
    };
    let mut message = format!(
        "`{file}` repeats {repeated} of its {} act label(s) from `{theirs}` (such as \
         `{example}`) with texts in {}: it looks like a translation of `{theirs}`, and \
         Docent reads each label once{unread}, so these acts of `{file}` are not used.",
        copy.acts.len(),
        language
            .as_ref()
            .map_or("another language".to_owned(), |l| {
                Language::english_name(l).map_or(format!("`{l}`"), |n| format!("{n} (`{l}`)"))
            }),
    );
    let tag = language.as_ref().map_or("de", Language::as_str);
    let _ = write!(
        message,
        " Translations go beside the original, in `{theirs}`: under each act's `Text:` write \
         `Text@{tag}:` with the translated texts (and `TextChild@{tag}:` under `TextChild:`)"
    );
    match &language {
        None => message.push_str(
            ", with the language's short tag after the `@` (`de`, `fr`), and add that tag to \
             `languages:` in docent.yaml.",
        ),
        Some(l) if config.languages.find(l.as_str()).is_none() => {
            let listed = (config.languages.all().iter())
                .chain(std::iter::once(l))
                .map(Language::as_str)
                .collect::<Vec<_>>()
                .join(", ");
            let _ = write!(
                message,
                ", and list the language in docent.yaml: `languages: [{listed}]`."
            );
        }
        Some(_) => message.push('.'),
    }
    let _ = write!(
        message,
        " For a translator, `docent translations export BUNDLE --language {tag}` writes a table \
         of every text and `docent translations import` writes the filled table back. Then \
         delete `{file}` or move it out of the bundle folder."
    );
    Diagnostic::error(DiagnosticCode::TranslatedActsFile, &first.pos, message)
}
