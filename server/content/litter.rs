//! Files a bundle holds without its author meaning to: what operating systems and editors leave
//! behind when a folder is copied from a Mac (`._name` resource forks beside every file,
//! `.DS_Store`), opened on Windows (`Thumbs.db`, `desktop.ini`) or edited (`name~`, `.bak`,
//! `.swp`, `.#name`). They are never content: the pages check, the media listing and the "did
//! you mean" suggestions skip them (`paths::list_files`), and the whole lot is said once, as
//! one note (no mistake: `docent check --deny-warnings` passes), so a bundle from anywhere
//! checks as its author sees it.
//!
//! An acts file disabled by renaming (`acts.yaml.bak`, `acts.yaml.old`, `acts.yml~`) is the
//! exception: its acts silently vanish from the console and the pages, so each such file
//! holding acts no loaded file has gets a warning of its own. One whose acts are all loaded is
//! an old copy, and counts among the ignored files.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;
use std::sync::Arc;

use crate::DiagnosticCode;
use crate::acts_file::read_acts_file;
use crate::config::SiteConfig;
use crate::diagnostic::Diagnostic;
use crate::gather::read_limited;
use crate::model::Pos;
use crate::paths::{BundleArea, list_files_and_litter};

/// What kind of leftover a file is, in the order the note names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Litter {
    /// `._name`: a Mac's AppleDouble file holding `name`'s Finder information.
    MacResourceFork,
    /// `.DS_Store`: a Mac's Finder window settings.
    FinderSettings,
    /// `Thumbs.db`, `ehthumbs.db`: Windows' picture thumbnails.
    WindowsThumbnails,
    /// `desktop.ini`: Windows' folder settings.
    WindowsFolderSettings,
    /// `name~`, `name.bak`, `.name.swp`, `.#name`, and old copies of acts files whose acts
    /// are all loaded.
    Backup,
}

impl Litter {
    /// How the note names a number of them.
    fn described(self) -> &'static str {
        match self {
            Litter::MacResourceFork => "Mac resource fork(s) (`._` files)",
            Litter::FinderSettings => "Mac Finder settings (`.DS_Store`)",
            Litter::WindowsThumbnails => "Windows thumbnail cache(s) (`Thumbs.db`)",
            Litter::WindowsFolderSettings => "Windows folder settings (`desktop.ini`)",
            Litter::Backup => "editor backup(s) and old copies (`~`, `.bak`, `.swp`, `.#`)",
        }
    }
}

/// Whether a file called `name` is something computers and editors leave in copied folders
/// (`._name`, `.DS_Store`, `Thumbs.db`, `desktop.ini`, `name~`, `.bak`, `.swp`, `.#name`): not
/// content, so never checked, served, counted in the fingerprint or taken for a change.
pub fn is_litter(name: &str) -> bool {
    litter_kind(name).is_some()
}

/// The kind of leftover a file called `name` is, or `None` for a file that may be content.
pub(crate) fn litter_kind(name: &str) -> Option<Litter> {
    let lower = name.to_ascii_lowercase();
    if name.starts_with("._") {
        Some(Litter::MacResourceFork)
    } else if name == ".DS_Store" {
        Some(Litter::FinderSettings)
    } else if lower == "thumbs.db" || lower == "ehthumbs.db" {
        Some(Litter::WindowsThumbnails)
    } else if lower == "desktop.ini" {
        Some(Litter::WindowsFolderSettings)
    } else if name.ends_with('~')
        || lower.ends_with(".bak")
        || lower.ends_with(".swp")
        || name.starts_with(".#")
    {
        Some(Litter::Backup)
    } else {
        None
    }
}

/// Whether a top-level `name` is an acts file renamed so it is not read: `.yaml` or `.yml`
/// followed by `~` or one more ending (`acts.yaml.bak`, `acts.yaml.disabled`, `acts.yml~`).
fn disabled_acts_name(name: &str) -> bool {
    let lower = name.to_ascii_lowercase();
    if lower.starts_with('.') || lower.starts_with("docent.") {
        return false;
    }
    let is_yaml = |stem: &str| stem.ends_with(".yaml") || stem.ends_with(".yml");
    let unbacked = lower.trim_end_matches('~');
    if unbacked.len() < lower.len() {
        return is_yaml(unbacked);
    }
    lower
        .rsplit_once('.')
        .is_some_and(|(stem, ending)| !ending.is_empty() && is_yaml(stem) && !is_yaml(&lower))
}

/// The leftovers and renamed acts files of a bundle, found before it is read.
#[derive(Debug, Default)]
pub(crate) struct Survey {
    /// Bundle-relative paths of leftover files, with their kind.
    litter: Vec<(String, Litter)>,
    /// Top-level files that look like renamed acts files, sorted.
    disabled: Vec<String>,
}

impl Survey {
    /// Looks at the top of `root` and everything under `pages/` and `media/`.
    pub(crate) fn find(root: &Path) -> Survey {
        let mut survey = Survey::default();
        let mut top: Vec<String> = std::fs::read_dir(root)
            .into_iter()
            .flatten()
            .flatten()
            .filter(|entry| entry.file_type().is_ok_and(|t| !t.is_dir()))
            .filter_map(|entry| entry.file_name().into_string().ok())
            .collect();
        top.sort();
        for name in top {
            if disabled_acts_name(&name) {
                survey.disabled.push(name);
            } else if let Some(kind) = litter_kind(&name) {
                survey.litter.push((name, kind));
            }
        }
        for area in [BundleArea::Pages, BundleArea::Media] {
            let (_, litter) = list_files_and_litter(root, area);
            let folder = area.dir_name();
            survey.litter.extend(
                litter
                    .into_iter()
                    .filter_map(|rel| Some((format!("{folder}/{rel}"), leaf_kind(&rel)?))),
            );
        }
        survey
    }

    /// Warns about each renamed acts file holding acts that `loaded` does not know, and
    /// counts the others (old copies) as leftovers.
    pub(crate) fn check_disabled(
        &mut self,
        root: &Path,
        config: &SiteConfig,
        loaded: &dyn Fn(&str) -> bool,
        out: &mut Vec<Diagnostic>,
    ) {
        for name in std::mem::take(&mut self.disabled) {
            let file: Arc<str> = Arc::from(name.as_str());
            let labels = match read_limited(&root.join(&name), &file) {
                Ok(bytes) => {
                    let read = read_acts_file(&file, &bytes, &config.speech, &config.languages);
                    let mut labels: Vec<String> = (read.acts.into_iter())
                        .filter_map(|a| a.label.map(|l| l.value))
                        .chain(read.unread_labels)
                        .collect();
                    labels.dedup();
                    labels
                }
                Err(_) => Vec::new(),
            };
            let missing: Vec<&String> = labels.iter().filter(|l| !loaded(l)).collect();
            if missing.is_empty() {
                // An old copy, or not acts at all: only a backup ending makes it a leftover.
                if !labels.is_empty() || litter_kind(&name).is_some() {
                    self.litter.push((name, Litter::Backup));
                }
                continue;
            }
            out.push(Diagnostic::warning(
                DiagnosticCode::DisabledActsFile,
                &Pos::start_of(file),
                disabled_message(&name, labels.len(), &missing),
            ));
        }
    }

    /// The one note naming every leftover file ignored, if there is any.
    pub(crate) fn report(mut self, out: &mut Vec<Diagnostic>) {
        if self.litter.is_empty() {
            return;
        }
        self.litter.sort();
        let mut counts: BTreeMap<Litter, usize> = BTreeMap::new();
        for (_, kind) in &self.litter {
            *counts.entry(*kind).or_default() += 1;
        }
        let kinds: Vec<String> = counts
            .iter()
            .map(|(kind, n)| format!("{n} {}", kind.described()))
            .collect();
        let examples: Vec<String> = (self.litter.iter().take(3))
            .map(|(path, _)| format!("`{path}`"))
            .collect();
        let more = self.litter.len().saturating_sub(examples.len());
        let mut message = format!(
            "Docent ignored {} file(s) that computers and editors leave in copied folders, not \
             content: {} (such as {}",
            self.litter.len(),
            kinds.join(", "),
            examples.join(", ")
        );
        if more > 0 {
            let _ = write!(message, " and {more} more");
        }
        message.push_str(
            "). They are not checked, shown or listed. Nothing needs doing; you may delete them \
             to keep the bundle tidy.",
        );
        let first = Pos::start_of(self.litter[0].0.as_str());
        out.push(Diagnostic::note(
            DiagnosticCode::IgnoredFiles,
            &first,
            message,
        ));
    }
}

/// The kind of the file at the end of a `/`-separated path.
fn leaf_kind(rel: &str) -> Option<Litter> {
    litter_kind(rel.rsplit('/').next().unwrap_or(rel))
}

fn disabled_message(name: &str, holds: usize, missing: &[&String]) -> String {
    let shown: Vec<String> = missing.iter().take(5).map(|l| format!("`{l}`")).collect();
    let more = missing.len() - shown.len();
    let mut which = shown.join(", ");
    if more > 0 {
        let _ = write!(which, " and {more} more");
    }
    format!(
        "`{name}` holds {holds} act(s), but Docent reads only files ending in .yaml or .yml: \
         {} of them are in no loaded acts file, so these acts are not loaded: {which}. The \
         console and the pages cannot use them. Rename the file back to end in .yaml to use \
         them; if it is an old copy, delete it or move it out of the bundle folder.",
        missing.len()
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn leftovers_are_known_by_name_and_content_is_not() {
        for (name, kind) in [
            ("._index.html", Litter::MacResourceFork),
            ("._", Litter::MacResourceFork),
            (".DS_Store", Litter::FinderSettings),
            ("Thumbs.db", Litter::WindowsThumbnails),
            ("desktop.ini", Litter::WindowsFolderSettings),
            ("Desktop.ini", Litter::WindowsFolderSettings),
            ("index.html~", Litter::Backup),
            ("style.css.bak", Litter::Backup),
            (".index.html.swp", Litter::Backup),
            (".#index.html", Litter::Backup),
        ] {
            assert_eq!(litter_kind(name), Some(kind), "{name}");
        }
        for content in [
            "index.html",
            "_partial.html",
            ".htaccess",
            "thumbs.png",
            "backup.html",
        ] {
            assert_eq!(litter_kind(content), None, "{content}");
        }
    }

    #[test]
    fn renamed_acts_files_are_told_from_acts_files_and_settings() {
        for disabled in [
            "acts.yaml.bak",
            "acts.yaml.old",
            "acts.yaml.disabled",
            "acts.yml~",
            "Tour.YAML.orig",
            "acts.yaml.txt",
        ] {
            assert!(disabled_acts_name(disabled), "{disabled}");
        }
        for other in [
            "acts.yaml",
            "acts.yml",
            "acts.bak.yaml",
            "docent.yaml.bak",
            "._acts.yaml.bak",
            "notes.txt",
            "yaml.bak",
        ] {
            assert!(!disabled_acts_name(other), "{other}");
        }
    }
}
