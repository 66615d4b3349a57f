//! The log file the writer appends to now, and its sync thread. Events go to several files
//! (a day log, a session's log); the writer switches when the next lines belong elsewhere,
//! syncing the file it leaves completely first, so that a finished session is on disk.

use std::collections::HashSet;
use std::fs::{File, OpenOptions};
use std::io::{self, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::time::Duration;

use crate::sync::Syncer;

/// Where the writer's lines go: the file they belong in, opened on demand.
pub(super) trait Sink {
    /// The file at `path`, open for appending.
    fn file_for(&mut self, path: &Path) -> io::Result<&mut dyn Write>;
    /// Lines were written to the current file.
    fn written(&mut self);
    /// Syncs the open file completely and closes it.
    fn close(&mut self) -> io::Result<()>;
    /// Whether the open file was removed (its folder deleted, say) since it was opened: lines
    /// written to it are then in no file anyone can read.
    fn removed(&mut self) -> io::Result<bool>;
    /// Closes the open file without waiting for it (it was removed): the next
    /// [`Sink::file_for`] makes it again, with its folders.
    fn forget(&mut self);
    /// A file this run wrote before, closed, and found missing when it opened it again (so
    /// made it again), once.
    fn take_remade(&mut self) -> Option<PathBuf>;
}

/// The open log file and its syncer.
pub(super) struct Files {
    sync_interval: Duration,
    open: Option<Open>,
    /// Every file opened in this run (the day log is opened again after each session).
    opened: HashSet<PathBuf>,
    /// One of them, found missing when opened again.
    remade: Option<PathBuf>,
}

struct Open {
    path: PathBuf,
    file: File,
    syncer: Syncer,
}

impl Files {
    /// No file open yet; each one opened is synced every `sync_interval` while written.
    pub(super) fn new(sync_interval: Duration) -> Self {
        Files {
            sync_interval,
            open: None,
            opened: HashSet::new(),
            remade: None,
        }
    }

    fn open(&mut self, path: &Path) -> io::Result<&mut Open> {
        if self.open.as_ref().is_some_and(|o| o.path != path) {
            self.close()?;
        }
        if self.open.is_none() {
            if self.opened.contains(path) && !path.exists() {
                tracing::warn!(path = %path.display(), "a corpus log this run wrote was removed: making it again");
                self.remade = Some(path.to_owned());
            }
            let file = open_for_append(path)?;
            self.opened.insert(path.to_owned());
            let syncer = Syncer::start(file.try_clone()?, self.sync_interval)?;
            self.open = Some(Open {
                path: path.to_owned(),
                file,
                syncer,
            });
        }
        Ok(self.open.as_mut().expect("opened above"))
    }
}

impl Sink for Files {
    fn file_for(&mut self, path: &Path) -> io::Result<&mut dyn Write> {
        Ok(&mut self.open(path)?.file)
    }

    fn written(&mut self) {
        if let Some(open) = &self.open {
            open.syncer.written();
        }
    }

    fn close(&mut self) -> io::Result<()> {
        match self.open.take() {
            Some(open) => open.syncer.finish(&open.file),
            None => Ok(()),
        }
    }

    fn removed(&mut self) -> io::Result<bool> {
        use std::os::unix::fs::MetadataExt;
        match &self.open {
            // One `fstat` per batch written: no name left means removed.
            Some(open) => Ok(open.file.metadata()?.nlink() == 0),
            None => Ok(false),
        }
    }

    fn take_remade(&mut self) -> Option<PathBuf> {
        self.remade.take()
    }

    fn forget(&mut self) {
        if let Some(open) = self.open.take() {
            // Told by the writer already: not again when it is made again.
            self.opened.remove(&open.path);
            // Syncing a removed file keeps nothing; only its thread is stopped.
            drop(open.syncer);
            tracing::warn!(
                path = %open.path.display(),
                "the corpus log was removed under the running server: making it again and \
                 writing its last lines there"
            );
        }
    }
}

/// Opens `path` for appending, creating it and its folders, and locks it (an advisory lock,
/// released when it is closed or the server dies), so that `docent corpus` can tell a session
/// being recorded from one a killed server left open. A file a crash left ending in the middle
/// of a line first gets the missing `\n`: the torn line stays a line of its own (which readers
/// skip), and the next one is whole.
fn open_for_append(path: &Path) -> io::Result<File> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let mut file = OpenOptions::new().create(true).append(true).open(path)?;
    if let Err(error) = file.try_lock() {
        // Every file a run writes is its own; only the lock's readers are misled.
        tracing::warn!(path = %path.display(), %error, "cannot lock the corpus file being written");
    }
    if !ends_a_line(path)? {
        file.write_all(b"\n")?;
    }
    Ok(file)
}

/// Whether the file at `path` is empty or ends with `\n`.
fn ends_a_line(path: &Path) -> io::Result<bool> {
    let mut file = File::open(path)?;
    if file.metadata()?.len() == 0 {
        return Ok(true);
    }
    file.seek(SeekFrom::End(-1))?;
    let mut last = [0u8];
    file.read_exact(&mut last)?;
    Ok(last[0] == b'\n')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_torn_last_line_is_ended_before_anything_is_appended() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("days/2026-11-24.jsonl");
        let mut files = Files::new(Duration::from_secs(3600));
        files
            .file_for(&path)
            .unwrap()
            .write_all(b"{\"seq\":1}\n{\"se")
            .unwrap();
        files.close().unwrap();
        files
            .file_for(&path)
            .unwrap()
            .write_all(b"{\"seq\":3}\n")
            .unwrap();
        files.close().unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(text, "{\"seq\":1}\n{\"se\n{\"seq\":3}\n");
    }

    #[test]
    fn the_file_being_written_is_locked_until_it_is_closed() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir
            .path()
            .join("sessions/2026-11-24T10-00-00Z/events.jsonl");
        let mut files = Files::new(Duration::from_secs(3600));
        files.file_for(&path).unwrap();
        let reader = File::open(&path).unwrap();
        assert!(matches!(
            reader.try_lock_shared(),
            Err(std::fs::TryLockError::WouldBlock)
        ));
        files.close().unwrap();
        reader.try_lock_shared().expect("free once closed");
    }
}
