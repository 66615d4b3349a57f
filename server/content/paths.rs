//! The single gate for every file path inside a bundle, used by the checker (for `PROJECT`,
//! `DISPLAY_PAGE` and the home page) and by the HTTP file routes.
//!
//! Paths must match the directory entries with exact case on every file system: a bundle
//! authored on a case-insensitive laptop must not break when it is copied to the robot.
//! A path is accepted only when its canonical form stays inside the area folder, so neither
//! `..` nor a symlink can reach outside the bundle.

use std::collections::HashMap;
use std::ffi::OsString;
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::litter::litter_kind;

/// The bundle folders that files may be served from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BundleArea {
    /// `pages/`: touchscreen pages and their assets.
    Pages,
    /// `media/`: images and videos for the projector.
    Media,
}

impl BundleArea {
    /// The folder name under the bundle root.
    pub fn dir_name(self) -> &'static str {
        match self {
            BundleArea::Pages => "pages",
            BundleArea::Media => "media",
        }
    }
}

/// Why a path was refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum PathError {
    /// The path is malformed (empty, absolute, `..`, `.`, backslash, NUL, drive prefix) or
    /// leads outside the area folder (for example through a symlink).
    #[error("the path leads outside the bundle folder or is not a plain relative path")]
    Outside,
    /// Nothing exists at the path.
    #[error("no such file")]
    NotFound,
    /// The file exists, but the path's upper and lower case differ from the real names.
    #[error("the file exists as `{actual}` (upper and lower case differ)")]
    Miscased {
        /// The correctly cased path, relative to the area folder like the input.
        actual: String,
    },
    /// The path names a folder or something else that is not a regular file.
    #[error("not a file")]
    NotAFile,
}

/// Resolves `rel` (already percent-decoded, `/`-separated) inside `root/<area>`.
///
/// `root` must be the canonical bundle root. On success the result is the canonical path of
/// a regular file inside the area folder. The area folder itself must be a real folder: if
/// `pages` is a link, everything under it counts as outside.
pub fn resolve_in_bundle(root: &Path, area: BundleArea, rel: &str) -> Result<PathBuf, PathError> {
    resolve_listed(root, area, rel, &read_listing)
}

/// The names in a folder with what each is, or `None` when it cannot be read.
pub(crate) type Listing = Option<Arc<HashMap<OsString, EntryType>>>;

/// What a folder entry is, as the listing tells it (links not followed).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum EntryType {
    File,
    Folder,
    /// A link, a special file, or a type the system did not say.
    Other,
}

/// The names in `dir`, read now.
pub(crate) fn read_listing(dir: &Path) -> Listing {
    let names = fs::read_dir(dir)
        .ok()?
        .flatten()
        .map(|entry| {
            let kind = match entry.file_type() {
                Ok(kind) if kind.is_file() => EntryType::File,
                Ok(kind) if kind.is_dir() => EntryType::Folder,
                _ => EntryType::Other,
            };
            (entry.file_name(), kind)
        })
        .collect();
    Some(Arc::new(names))
}

/// [`resolve_in_bundle`] with folder listings from `list`: a check resolving thousands of
/// paths in one folder reads it once (the same rules, so the same answers).
pub(crate) fn resolve_listed(
    root: &Path,
    area: BundleArea,
    rel: &str,
    list: &dyn Fn(&Path) -> Listing,
) -> Result<PathBuf, PathError> {
    let components = split_relative(rel)?;
    let area_dir = root.join(area.dir_name());
    let mut current = area_dir.clone();
    let mut actual_names: Vec<String> = Vec::with_capacity(components.len());
    let mut miscased = false;
    // Whether the listings show a real folder at every step and a regular file at the end,
    // no link anywhere: then `current` already is the canonical path (`root` is canonical).
    let mut plain = find_entry(list(root), area.dir_name())
        .is_ok_and(|(entry, kind)| matches!(entry, Entry::Exact) && kind == EntryType::Folder);
    for (i, component) in components.iter().enumerate() {
        let (entry, kind) = find_entry(list(&current), component)?;
        let wanted = if i + 1 == components.len() {
            EntryType::File
        } else {
            EntryType::Folder
        };
        plain &= kind == wanted;
        match entry {
            Entry::Exact => {
                actual_names.push((*component).to_owned());
                current.push(component);
            }
            Entry::CaseDiffers(real) => {
                miscased = true;
                actual_names.push(real.to_string_lossy().into_owned());
                current.push(real);
            }
        }
    }
    let canonical = if plain {
        current
    } else {
        // Canonicalizing resolves every symlink; the containment test is on the real
        // location, and comes before the case check so that no answer tells what exists
        // outside.
        let canonical = current.canonicalize().map_err(|_| PathError::NotFound)?;
        if !canonical.starts_with(&area_dir) {
            return Err(PathError::Outside);
        }
        canonical
    };
    if miscased {
        return Err(PathError::Miscased {
            actual: actual_names.join("/"),
        });
    }
    if !plain && !fs::metadata(&canonical).is_ok_and(|m| m.is_file()) {
        return Err(PathError::NotAFile);
    }
    Ok(canonical)
}

/// Splits a relative path into its names, refusing anything that could step out or that
/// means different things on different systems.
fn split_relative(rel: &str) -> Result<Vec<&str>, PathError> {
    if rel.is_empty() || rel.starts_with('/') || rel.contains(['\\', '\0']) || has_drive_prefix(rel)
    {
        return Err(PathError::Outside);
    }
    let components: Vec<&str> = rel.split('/').collect();
    if components
        .iter()
        .any(|c| c.is_empty() || *c == "." || *c == "..")
    {
        return Err(PathError::Outside);
    }
    Ok(components)
}

/// `C:`, `c:foo`: a Windows drive prefix, meaningless (and unsafe) inside a bundle.
fn has_drive_prefix(rel: &str) -> bool {
    let bytes = rel.as_bytes();
    bytes.len() >= 2 && bytes[0].is_ascii_alphabetic() && bytes[1] == b':'
}

enum Entry {
    Exact,
    CaseDiffers(OsString),
}

/// Looks `name` up in the listing of a folder, so that case is compared exactly even where
/// the file system itself ignores it.
fn find_entry(listing: Listing, name: &str) -> Result<(Entry, EntryType), PathError> {
    let listing = listing.ok_or(PathError::NotFound)?;
    // The exact name first, without lower-casing every entry: a folder of 1,000 pages is
    // searched for each of them.
    if let Some(&kind) = listing.get(std::ffi::OsStr::new(name)) {
        return Ok((Entry::Exact, kind));
    }
    let wanted = name.to_lowercase();
    // On a case-sensitive system `a.html` and `A.html` may both exist: pick one stably.
    listing
        .iter()
        .filter(|(entry_name, _)| entry_name.to_string_lossy().to_lowercase() == wanted)
        .min_by(|a, b| a.0.cmp(b.0))
        .map(|(real, &kind)| (Entry::CaseDiffers(real.clone()), kind))
        .ok_or(PathError::NotFound)
}

/// Every file under `root/<area>` but what computers and editors leave behind (`._name`,
/// `.DS_Store`, backups: see `litter`), as `/`-separated paths relative to the area folder,
/// sorted. Folder symlinks are not followed (no loops, nothing outside); used for "did you
/// mean" and for finding pages to scan, never to decide access.
pub(crate) fn list_files(root: &Path, area: BundleArea) -> Vec<String> {
    list_files_and_litter(root, area).0
}

/// [`list_files`], and the leftover files it leaves out, both sorted.
pub(crate) fn list_files_and_litter(root: &Path, area: BundleArea) -> (Vec<String>, Vec<String>) {
    const MAX_DEPTH: usize = 16;
    const MAX_FILES: usize = 100_000;
    let mut files = Vec::new();
    let mut litter = Vec::new();
    let mut pending = vec![(root.join(area.dir_name()), String::new(), 0)];
    while let Some((dir, prefix, depth)) = pending.pop() {
        let Ok(listing) = fs::read_dir(&dir) else {
            continue;
        };
        for entry in listing.flatten() {
            let Ok(kind) = entry.file_type() else {
                continue;
            };
            let name = entry.file_name().to_string_lossy().into_owned();
            let rel = if prefix.is_empty() {
                name
            } else {
                format!("{prefix}/{name}")
            };
            if kind.is_dir() && depth < MAX_DEPTH {
                pending.push((entry.path(), rel, depth + 1));
            } else if kind.is_dir() {
                continue;
            } else if litter_kind(&entry.file_name().to_string_lossy()).is_some() {
                if litter.len() < MAX_FILES {
                    litter.push(rel);
                }
            } else if files.len() < MAX_FILES
                && (kind.is_file() || (kind.is_symlink() && entry.path().is_file()))
            {
                files.push(rel);
            }
        }
    }
    files.sort();
    litter.sort();
    (files, litter)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bundle(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("docent-paths-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(dir.join("pages/Welcome")).expect("create pages");
        fs::create_dir_all(dir.join("media")).expect("create media");
        fs::write(dir.join("pages/Welcome/Welcome.html"), "<p>hi</p>").expect("write page");
        dir.canonicalize().expect("canonical root")
    }

    #[test]
    fn resolves_an_exactly_cased_file() {
        let root = bundle("exact");
        let found = resolve_in_bundle(&root, BundleArea::Pages, "Welcome/Welcome.html");
        assert_eq!(found, Ok(root.join("pages/Welcome/Welcome.html")));
    }

    #[test]
    fn reports_the_correctly_cased_path() {
        let root = bundle("miscase");
        let found = resolve_in_bundle(&root, BundleArea::Pages, "welcome/WELCOME.html");
        assert_eq!(
            found,
            Err(PathError::Miscased {
                actual: "Welcome/Welcome.html".into()
            })
        );
    }

    #[test]
    fn refuses_malformed_paths() {
        let root = bundle("malformed");
        for rel in [
            "",
            "/etc/passwd",
            "../secret",
            "Welcome/../Welcome/Welcome.html",
            "./Welcome/Welcome.html",
            "Welcome//Welcome.html",
            "Welcome\\Welcome.html",
            "C:/x",
            "c:x",
            "Welcome/\0",
            "Welcome/",
        ] {
            assert_eq!(
                resolve_in_bundle(&root, BundleArea::Pages, rel),
                Err(PathError::Outside),
                "{rel:?}"
            );
        }
    }

    #[test]
    fn distinguishes_missing_files_and_folders() {
        let root = bundle("kinds");
        assert_eq!(
            resolve_in_bundle(&root, BundleArea::Pages, "nope.html"),
            Err(PathError::NotFound)
        );
        assert_eq!(
            resolve_in_bundle(&root, BundleArea::Pages, "Welcome"),
            Err(PathError::NotAFile)
        );
        assert_eq!(
            resolve_in_bundle(&root, BundleArea::Media, "Welcome/Welcome.html"),
            Err(PathError::NotFound)
        );
        // A still-encoded name is just a name that does not exist.
        assert_eq!(
            resolve_in_bundle(&root, BundleArea::Pages, "%2e%2e/secret"),
            Err(PathError::NotFound)
        );
    }

    #[test]
    fn lists_files_relative_to_the_area() {
        let root = bundle("listing");
        fs::write(root.join("pages/index.html"), "").expect("write index");
        assert_eq!(
            list_files(&root, BundleArea::Pages),
            ["Welcome/Welcome.html", "index.html"]
        );
        assert!(list_files(&root, BundleArea::Media).is_empty());
    }
}
