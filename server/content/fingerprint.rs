//! The bundle's fingerprint: a SHA-256 over every file a visitor or the robot can be shown
//! (the top-level files such as the acts files and `docent.yaml`, and everything under
//! `pages/` and `media/`), so a researcher can tell from a session's manifest exactly which
//! content it was recorded with, and whether two sessions had the same.
//!
//! Files computers and editors leave in copied folders (`.DS_Store`, `._name`, `Thumbs.db`,
//! backups) do not count: opening a folder on a Mac does not change the content.
//!
//! Computed when `docent serve` starts and each time a saved bundle goes live, never by
//! `docent check`. Links are not followed: a link's target path is hashed in its place, since
//! Docent itself never serves what a link leads out of the bundle to.

use std::fs;
use std::io::{self, Read};
use std::path::{Path, PathBuf};

use sha2::{Digest, Sha256};

use crate::BundleArea;
use crate::litter::is_litter;

/// `sha256:` and 64 hex digits over the bundle folder `root` (see the module's notes); the
/// error names the file that could not be read.
pub fn bundle_fingerprint(root: &Path) -> io::Result<String> {
    let mut files = Vec::new();
    for entry in fs::read_dir(root)? {
        let entry = entry?;
        let kind = entry.file_type()?;
        if !kind.is_dir() && !is_litter(&entry.file_name().to_string_lossy()) {
            files.push(PathBuf::from(entry.file_name()));
        }
    }
    for area in [BundleArea::Pages, BundleArea::Media] {
        collect(root, Path::new(area.dir_name()), &mut files)?;
    }
    // By the path's text with `/`, the same order on every system.
    let mut named: Vec<(String, PathBuf)> = (files.into_iter()).map(|p| (slashed(&p), p)).collect();
    named.sort();
    let mut hash = Sha256::new();
    let mut buffer = vec![0; 1 << 16];
    for (name, relative) in named {
        let path = root.join(&relative);
        let fail = |e: io::Error| io::Error::new(e.kind(), format!("{}: {e}", path.display()));
        hash.update(name.as_bytes());
        hash.update([0]);
        let meta = fs::symlink_metadata(&path).map_err(fail)?;
        if meta.file_type().is_symlink() {
            let target = fs::read_link(&path).map_err(fail)?;
            hash.update(b"link\0");
            hash.update(target.to_string_lossy().as_bytes());
        } else {
            hash.update(meta.len().to_le_bytes());
            let mut file = fs::File::open(&path).map_err(fail)?;
            loop {
                let n = file.read(&mut buffer).map_err(fail)?;
                if n == 0 {
                    break;
                }
                hash.update(&buffer[..n]);
            }
        }
        hash.update([0]);
    }
    let digest = hash.finalize();
    let hex: String = digest.iter().map(|b| format!("{b:02x}")).collect();
    Ok(format!("sha256:{hex}"))
}

/// The fingerprint for the corpus: a file that cannot be read is said in Docent's output, and
/// the sessions' manifests then have none rather than a wrong one.
pub fn corpus_fingerprint(root: &Path) -> Option<String> {
    bundle_fingerprint(root)
        .inspect_err(|e| tracing::warn!("the bundle's fingerprint could not be made: {e}"))
        .ok()
}

/// Every file (and link) under `root/folder`, relative to `root`; a missing folder has none.
fn collect(root: &Path, folder: &Path, files: &mut Vec<PathBuf>) -> io::Result<()> {
    let entries = match fs::read_dir(root.join(folder)) {
        Ok(entries) => entries,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(e),
    };
    for entry in entries {
        let entry = entry?;
        let relative = folder.join(entry.file_name());
        if entry.file_type()?.is_dir() {
            collect(root, &relative, files)?;
        } else if !is_litter(&entry.file_name().to_string_lossy()) {
            files.push(relative);
        }
    }
    Ok(())
}

fn slashed(path: &Path) -> String {
    let parts: Vec<String> = (path.components())
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    parts.join("/")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bundle(files: &[(&str, &str)]) -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        for (name, text) in files {
            let path = dir.path().join(name);
            fs::create_dir_all(path.parent().unwrap()).unwrap();
            fs::write(path, text).unwrap();
        }
        dir
    }

    #[test]
    fn the_same_content_has_the_same_fingerprint_and_any_change_another() {
        let files = [
            ("acts.yaml", "- Label: A\n"),
            ("pages/index.html", "<p>Hi</p>"),
            ("media/a.txt", "x"),
        ];
        let a = bundle(&files);
        let b = bundle(&files);
        let print = |d: &tempfile::TempDir| bundle_fingerprint(d.path()).unwrap();
        assert_eq!(print(&a), print(&b));
        assert!(print(&a).starts_with("sha256:") && print(&a).len() == 7 + 64);

        let edited = bundle(&[files[0], ("pages/index.html", "<p>Ho</p>"), files[2]]);
        assert_ne!(print(&a), print(&edited), "a page's text");
        let renamed = bundle(&[files[0], ("pages/home.html", "<p>Hi</p>"), files[2]]);
        assert_ne!(print(&a), print(&renamed), "a page's name");
        // The bytes of one file never run into the next one's name.
        let moved = bundle(&[
            files[0],
            ("pages/index.html", "<p>Hi</p>x"),
            ("media/a.txt", ""),
        ]);
        assert_ne!(print(&a), print(&moved));
    }

    #[test]
    fn files_a_mac_or_an_editor_leaves_do_not_count() {
        let dir = bundle(&[
            ("acts.yaml", "- Label: A\n"),
            ("pages/index.html", "<p>hi</p>"),
        ]);
        let before = bundle_fingerprint(dir.path()).expect("fingerprint");
        for litter in [
            ".DS_Store",
            "._acts.yaml",
            "pages/._index.html",
            "pages/Thumbs.db",
            "acts.yaml~",
        ] {
            std::fs::write(dir.path().join(litter), "left behind").expect("write");
        }
        assert_eq!(bundle_fingerprint(dir.path()).expect("fingerprint"), before);
        std::fs::write(dir.path().join("pages/new.html"), "<p>new</p>").expect("write");
        assert_ne!(bundle_fingerprint(dir.path()).expect("fingerprint"), before);
    }

    #[test]
    fn other_folders_such_as_a_corpus_inside_the_bundle_do_not_count() {
        let a = bundle(&[("acts.yaml", "- Label: A\n")]);
        let before = bundle_fingerprint(a.path()).unwrap();
        fs::create_dir_all(a.path().join("corpus/days")).unwrap();
        fs::write(a.path().join("corpus/days/log.jsonl"), "{}\n").unwrap();
        assert_eq!(bundle_fingerprint(a.path()).unwrap(), before);
    }
}
