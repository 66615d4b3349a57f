//! The media cache: one folder of converted files, each named by the content of the file it
//! was made from and by the recipe, so a restart (or a second bundle with the same film)
//! finds it again, and an edited file, or a new recipe, gets a new name. A file is written
//! under a temporary name and renamed when complete: a crash or `kill -9` mid-conversion
//! leaves no half file that could be served.

use std::io::{self, Read};
use std::path::{Path, PathBuf};

use sha2::{Digest, Sha256};

/// The recipes' version: raised when a recipe changes, so old results are made again.
const RECIPE_VERSION: u32 = 1;

/// The name of a cached result: the source's content hash, the recipe version and `ext`.
pub(super) fn cached_name(content: &str, recipe: &str, ext: &str) -> String {
    format!("{content}-r{RECIPE_VERSION}{recipe}.{ext}")
}

/// The SHA-256 of a file's content, as 32 hex digits (half the digest is plenty to tell
/// files apart and keeps names short). Reads in 1 MiB pieces.
pub(super) fn content_key(path: &Path) -> io::Result<String> {
    let mut file = std::fs::File::open(path)?;
    let mut hasher = Sha256::new();
    let mut buffer = vec![0; 1 << 20];
    loop {
        let read = file.read(&mut buffer)?;
        if read == 0 {
            break;
        }
        hasher.update(&buffer[..read]);
    }
    let digest = hasher.finalize();
    Ok(digest[..16].iter().map(|b| format!("{b:02x}")).collect())
}

/// Where a conversion writes before the result is complete: named for this process, so two
/// Docents sharing a cache never finish each other's half-written file.
pub(super) fn partial(result: &Path) -> PathBuf {
    let mut name = result.file_name().unwrap_or_default().to_os_string();
    name.push(format!(".{}{PARTIAL}", std::process::id()));
    result.with_file_name(name)
}

/// A scratch file of the conversion of content `key` (a decoded HEIC photo), for this process.
pub(super) fn scratch(cache: &Path, key: &str, ext: &str) -> PathBuf {
    cache.join(format!("{key}.{}{PARTIAL}.{ext}", std::process::id()))
}

/// What marks a file the cache holds only while a conversion runs.
const PARTIAL: &str = ".partial";

/// Removes what conversions stopped by a crash or `kill -9` left in `cache` (their partial and
/// scratch files); called when Docent starts, before any conversion of its own.
pub(super) fn sweep(cache: &Path) {
    let Ok(entries) = std::fs::read_dir(cache) else {
        return;
    };
    for entry in entries.flatten() {
        if entry.file_name().to_string_lossy().contains(PARTIAL) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// Sets a cached result's modification time to now (it was taken again).
pub(super) fn touch(result: &Path) {
    let now = std::time::SystemTime::now();
    let touched = std::fs::File::options()
        .write(true)
        .open(result)
        .and_then(|f| f.set_modified(now));
    if let Err(e) = touched {
        tracing::debug!(file = %result.display(), "the cached file's time is not changed: {e}");
    }
}

/// The default cache folder: systemd's `CACHE_DIRECTORY` for a service, else
/// `$XDG_CACHE_HOME/docent/media`, else `~/.cache/docent/media`, else a folder in the
/// system's temporary folder.
pub fn default_folder() -> PathBuf {
    let var = |name: &str| {
        std::env::var_os(name)
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
    };
    if let Some(dir) = var("CACHE_DIRECTORY") {
        return dir.join("media");
    }
    if let Some(dir) = var("XDG_CACHE_HOME") {
        return dir.join("docent").join("media");
    }
    if let Some(home) = var("HOME") {
        return home.join(".cache").join("docent").join("media");
    }
    std::env::temp_dir().join("docent-media")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_key_is_the_content_not_the_name() {
        let dir = tempfile::tempdir().expect("temp dir");
        let (a, b, c) = (
            dir.path().join("a.mpg"),
            dir.path().join("b.mov"),
            dir.path().join("c"),
        );
        std::fs::write(&a, b"same bytes").expect("write");
        std::fs::write(&b, b"same bytes").expect("write");
        std::fs::write(&c, b"other bytes").expect("write");
        let key = content_key(&a).expect("key");
        assert_eq!(key.len(), 32);
        assert_eq!(key, content_key(&b).expect("key"));
        assert_ne!(key, content_key(&c).expect("key"));
        let id = std::process::id();
        assert_eq!(
            partial(Path::new("/c/k-r1.webm")),
            Path::new(&format!("/c/k-r1.webm.{id}.partial"))
        );
        std::fs::write(dir.path().join("k-r1.webm.77.partial"), b"half").expect("write");
        std::fs::write(dir.path().join("k.77.partial.heic.png"), b"half").expect("write");
        sweep(dir.path());
        let mut left: Vec<_> = (std::fs::read_dir(dir.path()).expect("read").flatten())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .collect();
        left.sort();
        assert_eq!(left, ["a.mpg", "b.mov", "c"], "only what is complete stays");
    }
}
