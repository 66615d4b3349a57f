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

/// Where a conversion writes before the result is complete.
pub(super) fn partial(result: &Path) -> PathBuf {
    let mut name = result.file_name().unwrap_or_default().to_os_string();
    name.push(".partial");
    result.with_file_name(name)
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
        assert_eq!(
            partial(Path::new("/c/k-r1.webm")),
            Path::new("/c/k-r1.webm.partial")
        );
    }
}
