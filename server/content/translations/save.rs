//! Writing an import's translations: each acts file edited in memory, the whole bundle
//! loaded from those edits as the server would load it, every text compared with what was
//! meant (the originals untouched, each translation exactly the table's), and only then each
//! file replaced atomically (a temporary file beside it, synced, renamed over it).
//!
//! An error the load finds inside a text the import wrote (an unfilled `{placeholder}`,
//! markup) leaves that text's variant out: it is reported by the table's row and key, and the
//! rest is loaded again without it. A bundle that would still not load (an error outside the
//! written texts), or a text that would not read back exactly, writes nothing.

use std::collections::BTreeMap;
use std::fs::{self, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use crate::{
    ActsReplacements, Bundle, Diagnostic, DiagnosticCode, Language, load_bundle_replacing,
};

use super::import::{Change, language_name};
use super::located::{WrittenText, told_by_row, written_text_of};
use super::write::{Edit, EditError, edit_file};

/// What was written.
#[derive(Debug, Default)]
pub struct Saved {
    /// The acts files replaced, by name.
    pub files: Vec<String>,
    /// The translations written (those of the changes given that had no error).
    pub written: Vec<Change>,
    /// The errors that left a translation out, each by its row and key.
    pub left_out: Vec<String>,
    /// Warnings the new texts bring: by row and key when in a written text, else the
    /// loader's own.
    pub new_warnings: Vec<String>,
}

/// Why nothing was written (or, for [`SaveError::Write`], not everything).
#[derive(Debug, thiserror::Error)]
pub enum SaveError {
    /// An acts file cannot be edited.
    #[error("{0}")]
    Edit(#[from] EditError),
    /// An acts file cannot be read.
    #[error("{file}: cannot be read ({error}); nothing was written")]
    Unreadable {
        /// The file.
        file: String,
        /// Why.
        error: io::Error,
    },
    /// The bundle would not load with the translations written, for errors outside the
    /// written texts (those inside leave their translation out instead): the errors.
    #[error(
        "with these translations written the bundle would not load, so nothing was written \
         (the lines are those of the files as the import would have written them):\n{}",
        .0.iter().map(|d| format!("  {d}")).collect::<Vec<_>>().join("\n")
    )]
    WouldNotLoad(Vec<Diagnostic>),
    /// A text would not read back as it was meant (a fault in Docent: reported, never written).
    #[error(
        "{key} would read back as {read:?} instead of {meant:?}, so nothing was written; please \
         report this as a Docent bug with the text"
    )]
    NotAsWritten {
        /// The text's key or variant.
        key: String,
        /// What the table gave.
        meant: Vec<String>,
        /// What the loader read from the edited file.
        read: Vec<String>,
    },
    /// Writing a file failed; the files named before it were written.
    #[error("{file}: could not be written ({error}); written before it: {}", written_list(.written))]
    Write {
        /// The file.
        file: String,
        /// Why.
        error: io::Error,
        /// The files written before it.
        written: Vec<String>,
    },
}

fn written_list(files: &[String]) -> String {
    if files.is_empty() {
        "none".to_owned()
    } else {
        files.join(", ")
    }
}

/// Writes `changes` (translations into `language`) into `bundle`'s acts files, leaving out
/// (and reporting) each whose texts the loader finds an error in.
pub fn save(bundle: &Bundle, language: &Language, changes: &[Change]) -> Result<Saved, SaveError> {
    let mut kept = changes.to_vec();
    let mut left_out = Vec::new();
    loop {
        if kept.is_empty() {
            return Ok(Saved {
                left_out,
                ..Saved::default()
            });
        }
        let (files, written) = edited(bundle, language, &kept)?;
        let replaced: ActsReplacements = (files.iter())
            .map(|(file, text)| (file.clone(), text.as_bytes().to_vec()))
            .collect();
        let report = load_bundle_replacing(&bundle.root, &replaced);
        let mut failed = Vec::new();
        for d in report.diagnostics.iter().filter(|d| d.is_error()) {
            if let Some(text) = written_text_of(d, &files, &written) {
                let outcome = outcome(bundle, language, &kept[text.change]);
                left_out.push(told_by_row(d, text, Some(&outcome)));
                failed.push(text.change);
            }
        }
        if !failed.is_empty() {
            // Loaded again without them: an error may hide others behind it.
            kept = (kept.into_iter().enumerate())
                .filter(|(i, _)| !failed.contains(i))
                .map(|(_, c)| c)
                .collect();
            continue;
        }
        let Some(after) = report.bundle else {
            let errors = report.diagnostics.into_iter().filter(Diagnostic::is_error);
            return Err(SaveError::WouldNotLoad(errors.collect()));
        };
        verify(bundle, &after, language, &kept)?;
        let (in_texts, elsewhere): (Vec<&Diagnostic>, Vec<&Diagnostic>) = (after.diagnostics)
            .iter()
            .filter(|d| !d.is_error())
            .partition(|d| written_text_of(d, &files, &written).is_some());
        let mut new_warnings: Vec<String> = (in_texts.iter())
            .filter_map(|d| Some(told_by_row(d, written_text_of(d, &files, &written)?, None)))
            .collect();
        new_warnings.extend(fresh_warnings(&bundle.diagnostics, &elsewhere));
        let mut saved = Saved {
            left_out,
            new_warnings,
            ..Saved::default()
        };
        for (file, bytes) in &replaced {
            replace_file(&bundle.root.join(file), bytes).map_err(|error| SaveError::Write {
                file: file.clone(),
                error,
                written: saved.files.clone(),
            })?;
            saved.files.push(file.clone());
        }
        saved.written = kept;
        return Ok(saved);
    }
}

/// What becomes of a change left out: `GOODBYE/Text is not imported: it stays untranslated.`
fn outcome(bundle: &Bundle, language: &Language, change: &Change) -> String {
    let act = &bundle.acts[change.act];
    let name = format!("{}/{}", act.label, change.variant);
    if change.replaces {
        format!(
            "{name} is not imported: it keeps its current {} texts.",
            language_name(language)
        )
    } else {
        format!("{name} is not imported: it stays untranslated.")
    }
}

/// The acts files with `changes` written, by name, and where each written text is in them.
fn edited(
    bundle: &Bundle,
    language: &Language,
    changes: &[Change],
) -> Result<(BTreeMap<String, String>, Vec<WrittenText>), SaveError> {
    // Per file: the edits, and for each the change it writes.
    let mut edits: BTreeMap<String, Vec<(Edit, usize)>> = BTreeMap::new();
    for (index, change) in changes.iter().enumerate() {
        let act = &bundle.acts[change.act];
        let Some(variant) = act.variant(&change.variant) else {
            continue; // the plan names only variants of this bundle
        };
        let edit = Edit {
            original: variant.pos.clone(),
            existing: variant.translations.get(language).map(|t| t.pos.clone()),
            key: format!("{}@{language}", variant.name),
            texts: change.texts.clone(),
        };
        let file = variant.pos.file.to_string();
        edits.entry(file).or_default().push((edit, index));
    }
    let mut files = BTreeMap::new();
    let mut written = Vec::new();
    for (file, file_edits) in edits {
        let path = bundle.root.join(&file);
        let source = fs::read_to_string(&path).map_err(|error| SaveError::Unreadable {
            file: file.clone(),
            error,
        })?;
        let only: Vec<Edit> = file_edits.iter().map(|(e, _)| e.clone()).collect();
        let out = edit_file(&source, &only)?;
        for ((_, index), ranges) in file_edits.iter().zip(out.texts) {
            let change = &changes[*index];
            let label = &bundle.acts[change.act].label;
            for (n, (range, place)) in ranges.into_iter().zip(&change.places).enumerate() {
                written.push(WrittenText {
                    file: file.clone(),
                    range,
                    change: *index,
                    key: format!("{label}/{}/{}", change.variant, n + 1),
                    place: *place,
                });
            }
        }
        files.insert(file, out.text);
    }
    Ok((files, written))
}

/// Every text of `after` is `before`'s, except the changed translations, which are the table's.
fn verify(
    before: &Bundle,
    after: &Bundle,
    language: &Language,
    changes: &[Change],
) -> Result<(), SaveError> {
    let texts = |list: &[crate::Located<String>]| -> Vec<String> {
        list.iter().map(|t| t.value.clone()).collect()
    };
    let mismatch = |key: String, meant: Vec<String>, read: Vec<String>| {
        Err(SaveError::NotAsWritten { key, meant, read })
    };
    if before.acts.len() != after.acts.len() {
        return mismatch("the acts".to_owned(), Vec::new(), Vec::new());
    }
    for (i, (old, new)) in before.acts.iter().zip(&after.acts).enumerate() {
        for old_variant in &old.variants {
            let key = format!("{}/{}", old.label, old_variant.name);
            let Some(new_variant) = new.variant(&old_variant.name) else {
                return mismatch(key, texts(&old_variant.alternatives), Vec::new());
            };
            let (meant, read) = (
                texts(&old_variant.alternatives),
                texts(&new_variant.alternatives),
            );
            if meant != read {
                return mismatch(key, meant, read);
            }
            let languages = old_variant
                .translations
                .keys()
                .chain(new_variant.translations.keys());
            for other in languages {
                let changed = (other == language)
                    .then(|| {
                        changes
                            .iter()
                            .find(|c| c.act == i && c.variant == old_variant.name)
                    })
                    .flatten();
                let meant = match changed {
                    Some(change) => change.texts.clone(),
                    None => (old_variant.translations.get(other))
                        .map(|t| texts(&t.alternatives))
                        .unwrap_or_default(),
                };
                let read = (new_variant.translations.get(other))
                    .map(|t| texts(&t.alternatives))
                    .unwrap_or_default();
                if meant != read {
                    return mismatch(format!("{key}@{other}"), meant, read);
                }
            }
        }
    }
    Ok(())
}

/// The warnings of `after` that `before` did not have (by code, file and message).
fn fresh_warnings(before: &[Diagnostic], after: &[&Diagnostic]) -> Vec<String> {
    let mut known: Vec<(DiagnosticCode, &str, &str)> = before
        .iter()
        .map(|d| (d.code, d.file.as_str(), d.message.as_str()))
        .collect();
    let mut fresh = Vec::new();
    for d in after.iter().filter(|d| !d.is_error()) {
        let id = (d.code, d.file.as_str(), d.message.as_str());
        match known.iter().position(|k| *k == id) {
            Some(i) => {
                known.swap_remove(i);
            }
            None => fresh.push(d.to_string()),
        }
    }
    fresh
}

/// Replaces `path` with `bytes` atomically: a temporary file in the same folder (with the
/// old file's permissions), synced, renamed over it, and the folder synced. A link is
/// followed, so the file it names is replaced and the link stays.
pub fn replace_file(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let target: PathBuf = path.canonicalize().unwrap_or_else(|_| path.to_owned());
    let folder = match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_owned(),
        _ => PathBuf::from("."),
    };
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let temporary = folder.join(format!(".{name}.{}.docent-tmp", std::process::id()));
    let written = (|| {
        let mut file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&temporary)?;
        if let Ok(meta) = fs::metadata(&target) {
            file.set_permissions(meta.permissions())?;
        }
        file.write_all(bytes)?;
        file.sync_all()?;
        fs::rename(&temporary, &target)
    })();
    if written.is_err() {
        let _ = fs::remove_file(&temporary);
    }
    written?;
    // The rename itself is durable once the folder is synced; not every system allows it.
    if let Ok(dir) = fs::File::open(&folder) {
        let _ = dir.sync_all();
    }
    Ok(())
}
