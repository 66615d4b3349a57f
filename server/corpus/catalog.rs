//! The corpus folder as `docent corpus` sees it: its sessions oldest first (each read by
//! `session_folder.rs`), how many day logs it holds and its size; and the one way a SESSION
//! argument becomes a session folder, refusing anything that is not a folder directly inside
//! `sessions/`. Nothing here writes.

use std::io;
use std::path::{Component, Path, PathBuf};

use crate::layout::{SESSIONS_DIR, day_logs};
use crate::session_folder::SessionFolder;
use docent_content::closest;

/// Why `docent corpus` cannot do what it was asked; each says what to do about it.
#[derive(Debug, thiserror::Error)]
pub enum CorpusError {
    /// The corpus folder does not exist.
    #[error(
        "there is no corpus folder at {}: give the folder `docent serve --corpus` wrote into \
         with --corpus DIR (by default `corpus` in the folder Docent was started from)",
        shown(path)
    )]
    Missing {
        /// The folder as given.
        path: PathBuf,
    },
    /// The corpus path is not a folder.
    #[error("{} is not a folder: --corpus takes the corpus folder", shown(path))]
    NotAFolder {
        /// The path as given.
        path: PathBuf,
    },
    /// A file or folder could not be read.
    #[error("cannot read {}: {source}", path.display())]
    Unreadable {
        /// What could not be read.
        path: PathBuf,
        /// The operating system's error.
        source: io::Error,
    },
    /// The SESSION argument names no session at all (`..`, a path outside `sessions/`).
    #[error(
        "`{arg}` is not a session of {}: name a session by its folder in {} \
         (`docent corpus list` lists them), or give that folder's path",
        corpus.display(),
        corpus.join(SESSIONS_DIR).display()
    )]
    NotASession {
        /// The argument as given.
        arg: String,
        /// The corpus folder.
        corpus: PathBuf,
    },
    /// No session folder of that name.
    #[error(
        "no session {name} in {}{}; `docent corpus list` lists the sessions",
        corpus.display(),
        did_you_mean(closest.as_deref())
    )]
    UnknownSession {
        /// The name asked for.
        name: String,
        /// The corpus folder.
        corpus: PathBuf,
        /// The session name closest to it, if one is close.
        closest: Option<String>,
    },
    /// The session's folder (or `sessions/` itself) is a symbolic link: never followed.
    #[error(
        "{} is a symbolic link, not a folder: docent corpus does not follow links out of the \
         corpus folder; remove or replace the link yourself",
        path.display()
    )]
    Linked {
        /// The link.
        path: PathBuf,
    },
}

fn shown(path: &Path) -> String {
    match std::path::absolute(path) {
        Ok(absolute) if absolute != path => format!("{} ({})", path.display(), absolute.display()),
        _ => path.display().to_string(),
    }
}

fn did_you_mean(closest: Option<&str>) -> String {
    closest.map_or_else(String::new, |name| format!(" (did you mean {name}?)"))
}

/// The corpus folder, read.
pub struct Catalog {
    /// The corpus folder as given.
    pub corpus: PathBuf,
    /// Its sessions, oldest first.
    pub sessions: Vec<SessionFolder>,
    /// How many day logs it holds.
    pub day_logs: usize,
    /// The size of every file in it, in bytes (links are not followed).
    pub bytes: u64,
}

impl Catalog {
    /// Reads the corpus folder `corpus`: every session, the day logs, the size.
    pub fn read(corpus: &Path) -> Result<Catalog, CorpusError> {
        check_corpus(corpus)?;
        let sessions = session_names(corpus)?
            .iter()
            .map(|name| SessionFolder::read(name, &corpus.join(SESSIONS_DIR).join(name)))
            .collect();
        let day_logs = day_logs(corpus).map_err(|source| CorpusError::Unreadable {
            path: corpus.into(),
            source,
        })?;
        Ok(Catalog {
            corpus: corpus.to_owned(),
            sessions,
            day_logs: day_logs.len(),
            bytes: folder_size(corpus)?,
        })
    }
}

/// Fails unless `corpus` is an existing folder.
pub fn check_corpus(corpus: &Path) -> Result<(), CorpusError> {
    match std::fs::metadata(corpus) {
        Ok(meta) if meta.is_dir() => Ok(()),
        Ok(_) => Err(CorpusError::NotAFolder {
            path: corpus.into(),
        }),
        Err(e) if e.kind() == io::ErrorKind::NotFound => Err(CorpusError::Missing {
            path: corpus.into(),
        }),
        Err(source) => Err(CorpusError::Unreadable {
            path: corpus.into(),
            source,
        }),
    }
}

/// The names of the session folders (and links) in `corpus/sessions/`, oldest first; plain
/// files there are not sessions and are left out.
pub fn session_names(corpus: &Path) -> Result<Vec<String>, CorpusError> {
    let sessions = corpus.join(SESSIONS_DIR);
    let unreadable = |source| CorpusError::Unreadable {
        path: sessions.clone(),
        source,
    };
    let entries = match std::fs::read_dir(&sessions) {
        Ok(entries) => entries,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(unreadable(e)),
    };
    let mut names = Vec::new();
    for entry in entries {
        let entry = entry.map_err(unreadable)?;
        let kind = entry.file_type().map_err(unreadable)?;
        if kind.is_dir() || kind.is_symlink() {
            names.push(entry.file_name().to_string_lossy().into_owned());
        }
    }
    names.sort_by(|a, b| start_order(a).cmp(&start_order(b)));
    Ok(names)
}

/// A session name's place in time: its start stamp, then the `-N` Docent adds to a second
/// session starting in the same second (so `-10` comes after `-9`).
fn start_order(name: &str) -> (&str, u64, &str) {
    if let Some((stamp, n)) = name.rsplit_once('-')
        && stamp.ends_with('Z')
        && let Ok(n) = n.parse()
    {
        return (stamp, n, name);
    }
    (name, 0, name)
}

/// The session folder a SESSION argument names: a session's name (its folder's), or the path
/// of its folder, which must lie directly in this corpus's `sessions/`. Returns the name and
/// the folder (`corpus/sessions/NAME`), which exists and is a folder, not a link.
pub fn find_session(corpus: &Path, arg: &str) -> Result<(String, PathBuf), CorpusError> {
    check_corpus(corpus)?;
    let not_a_session = || CorpusError::NotASession {
        arg: arg.to_owned(),
        corpus: corpus.to_owned(),
    };
    let path = Path::new(arg);
    let mut parts = path.components();
    let name = match (parts.next(), parts.next()) {
        (Some(Component::Normal(name)), None) => name,
        (None, _) | (Some(Component::CurDir | Component::ParentDir), None) => {
            return Err(not_a_session());
        }
        _ => {
            // A path: its folder must be this corpus's `sessions/` itself.
            let name = path.file_name().ok_or_else(not_a_session)?;
            let parent = path.parent().ok_or_else(not_a_session)?;
            let parent = if parent.as_os_str().is_empty() {
                Path::new(".")
            } else {
                parent
            };
            let sessions = corpus.join(SESSIONS_DIR).canonicalize();
            match (parent.canonicalize(), sessions) {
                (Ok(given), Ok(sessions)) if given == sessions => name,
                _ => return Err(not_a_session()),
            }
        }
    };
    let name = name.to_str().ok_or_else(not_a_session)?.to_owned();
    let dir = corpus.join(SESSIONS_DIR).join(&name);
    match std::fs::symlink_metadata(&dir) {
        Ok(meta) if meta.file_type().is_symlink() => Err(CorpusError::Linked { path: dir }),
        Ok(meta) if meta.is_dir() => Ok((name, dir)),
        Ok(_) => Err(not_a_session()),
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            let names = session_names(corpus)?;
            Err(CorpusError::UnknownSession {
                closest: closest(&name, names.iter().map(String::as_str)).map(str::to_owned),
                name,
                corpus: corpus.to_owned(),
            })
        }
        Err(source) => Err(CorpusError::Unreadable { path: dir, source }),
    }
}

/// What a folder holds, links listed and never followed.
pub struct FolderContents {
    /// Every file (and link) under it with its size in bytes (a link's own), sorted by path.
    pub files: Vec<(PathBuf, u64)>,
    /// Every folder under it, each after its parent.
    pub folders: Vec<PathBuf>,
}

/// Lists everything under `dir`.
pub fn folder_contents(dir: &Path) -> Result<FolderContents, CorpusError> {
    let mut files = Vec::new();
    let mut folders = Vec::new();
    let mut pending = vec![dir.to_owned()];
    while let Some(folder) = pending.pop() {
        let unreadable = |source| CorpusError::Unreadable {
            path: folder.clone(),
            source,
        };
        for entry in std::fs::read_dir(&folder).map_err(unreadable)? {
            let path = entry.map_err(unreadable)?.path();
            let meta = std::fs::symlink_metadata(&path).map_err(unreadable)?;
            if meta.is_dir() {
                folders.push(path.clone());
                pending.push(path);
            } else {
                files.push((path, meta.len()));
            }
        }
    }
    files.sort();
    folders.sort_by_key(|f| f.components().count());
    Ok(FolderContents { files, folders })
}

/// The size of every file under `dir`, in bytes (a link counts as itself).
pub fn folder_size(dir: &Path) -> Result<u64, CorpusError> {
    Ok(folder_contents(dir)?
        .files
        .iter()
        .map(|(_, bytes)| bytes)
        .sum())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sessions_sort_by_their_start_and_then_their_number_in_that_second() {
        let corpus = tempfile::tempdir().unwrap();
        let names = [
            "2026-11-24T10-15-02Z-10",
            "2026-11-24T10-15-02Z",
            "2026-11-24T10-15-02Z-2",
            "2026-11-23T23-59-59Z",
            "2026-11-24T10-15-02Z-9",
        ];
        for name in names {
            std::fs::create_dir_all(corpus.path().join("sessions").join(name)).unwrap();
        }
        std::fs::write(corpus.path().join("sessions/notes.txt"), "not a session").unwrap();
        assert_eq!(
            session_names(corpus.path()).unwrap(),
            [
                "2026-11-23T23-59-59Z",
                "2026-11-24T10-15-02Z",
                "2026-11-24T10-15-02Z-2",
                "2026-11-24T10-15-02Z-9",
                "2026-11-24T10-15-02Z-10",
            ]
        );
    }

    #[test]
    fn a_session_is_found_by_name_or_by_its_folders_path_and_nothing_else() {
        let corpus = tempfile::tempdir().unwrap();
        let c = corpus.path();
        let dir = c.join("sessions/2026-11-24T10-15-02Z");
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::create_dir_all(c.join("days/2026-11-24")).unwrap();
        let (name, found) = find_session(c, "2026-11-24T10-15-02Z").unwrap();
        assert_eq!(
            (name.as_str(), found.as_path()),
            ("2026-11-24T10-15-02Z", dir.as_path())
        );
        let by_path = format!("{}/", dir.display());
        assert_eq!(find_session(c, &by_path).unwrap().1, dir);
        for refused in ["..", ".", "", "../x", "days/2026-11-24", "/", "sessions/.."] {
            let error = find_session(c, refused).unwrap_err();
            assert!(
                matches!(error, CorpusError::NotASession { .. }),
                "{refused}: {error}"
            );
        }
        let days = find_session(c, "days").unwrap_err();
        assert!(matches!(days, CorpusError::UnknownSession { .. }), "{days}");
        let typo = find_session(c, "2026-11-24T10-15-03Z")
            .unwrap_err()
            .to_string();
        assert!(
            typo.contains("(did you mean 2026-11-24T10-15-02Z?)"),
            "{typo}"
        );
    }
}
