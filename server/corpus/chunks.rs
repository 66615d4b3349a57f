//! One recording's file on disk, grown chunk by chunk: a chunk is appended only when its number
//! is the next one, the file is synced, and only then is the new length recorded in the index
//! beside it (`audio-1.webm.chunks`, one line `SEQ END` per chunk, synced too). The index is
//! the truth: whatever lies in the media file beyond the last indexed end (a torn append, a
//! crash between the two syncs) was never acknowledged, and is cut off before the next append
//! and whenever the file is opened again ([`ChunkFile::open`]), so the file is always a WebM
//! that plays up to its last acknowledged chunk.

use std::fs::{File, OpenOptions};
use std::io::{self, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

/// What became of a chunk.
#[derive(Debug, PartialEq, Eq)]
pub enum Appended {
    /// Stored now (`true`) or stored before and not appended again (`false`); the file holds
    /// `acked` bytes and expects chunk `next`.
    Stored {
        /// Whether this call appended it.
        new: bool,
        /// Bytes acknowledged.
        acked: u64,
        /// The next chunk's number.
        next: u64,
    },
    /// A chunk after a gap: the file expects chunk `next` first.
    Gap {
        /// The next chunk's number.
        next: u64,
    },
}

/// An open recording file and its index.
#[derive(Debug)]
pub struct ChunkFile {
    media: File,
    index: File,
    path: PathBuf,
    /// Bytes acknowledged: the media file's true length.
    acked: u64,
    /// The number of the next chunk; chunks are numbered from 0.
    next: u64,
}

/// The index file of the media file at `media`.
pub fn index_path(media: &Path) -> PathBuf {
    let mut name = media.as_os_str().to_owned();
    name.push(".chunks");
    PathBuf::from(name)
}

impl ChunkFile {
    /// Opens (or makes) the media file at `path` and its index, and cuts the media file back
    /// to the last acknowledged length (and the index to its last whole line).
    pub fn open(path: &Path) -> io::Result<ChunkFile> {
        let open = |p: &Path| {
            OpenOptions::new()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(p)
        };
        let mut index = open(&index_path(path))?;
        let media = open(path)?;
        let mut text = String::new();
        index.read_to_string(&mut text)?;
        let whole = text.rfind('\n').map_or(0, |at| at + 1);
        let (mut acked, mut next) = (0, 0);
        for line in text[..whole].lines() {
            let mut fields = line.split(' ').map(str::parse::<u64>);
            let (Some(Ok(seq)), Some(Ok(end))) = (fields.next(), fields.next()) else {
                return Err(io::Error::new(
                    io::ErrorKind::InvalidData,
                    format!(
                        "{} has a damaged line: {line:?}",
                        index_path(path).display()
                    ),
                ));
            };
            (acked, next) = (end, seq + 1);
        }
        if whole < text.len() {
            index.set_len(whole as u64)?;
            index.sync_data()?;
        }
        index.seek(SeekFrom::End(0))?;
        let mut file = ChunkFile {
            media,
            index,
            path: path.to_owned(),
            acked,
            next,
        };
        file.cut_unacknowledged()?;
        Ok(file)
    }

    /// Stores chunk `seq` with `bytes`, once: see [`Appended`].
    pub fn append(&mut self, seq: u64, bytes: &[u8]) -> io::Result<Appended> {
        if seq < self.next {
            return Ok(Appended::Stored {
                new: false,
                acked: self.acked,
                next: self.next,
            });
        }
        if seq > self.next {
            return Ok(Appended::Gap { next: self.next });
        }
        // A torn append left bytes behind: they go before anything is added.
        self.cut_unacknowledged()?;
        self.media.seek(SeekFrom::Start(self.acked))?;
        if let Err(e) = self
            .media
            .write_all(bytes)
            .and_then(|()| self.media.sync_data())
        {
            // Best effort: the next append or opening cuts it anyway.
            let _ = self.media.set_len(self.acked);
            return Err(e);
        }
        let end = self.acked + bytes.len() as u64;
        self.index.write_all(format!("{seq} {end}\n").as_bytes())?;
        self.index.sync_data()?;
        (self.acked, self.next) = (end, seq + 1);
        Ok(Appended::Stored {
            new: true,
            acked: self.acked,
            next: self.next,
        })
    }

    /// Bytes acknowledged.
    pub fn acked(&self) -> u64 {
        self.acked
    }

    /// Chunks acknowledged.
    pub fn chunks(&self) -> u64 {
        self.next
    }

    /// The media file's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    fn cut_unacknowledged(&mut self) -> io::Result<()> {
        if self.media.metadata()?.len() != self.acked {
            self.media.set_len(self.acked)?;
            self.media.sync_data()?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunks_are_appended_in_order_once_and_a_gap_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("audio-1.webm");
        let mut file = ChunkFile::open(&path).unwrap();
        let stored = |new, acked, next| Appended::Stored { new, acked, next };
        assert_eq!(file.append(0, b"head").unwrap(), stored(true, 4, 1));
        assert_eq!(file.append(0, b"head").unwrap(), stored(false, 4, 1));
        assert_eq!(file.append(2, b"late").unwrap(), Appended::Gap { next: 1 });
        assert_eq!(file.append(1, b"body").unwrap(), stored(true, 8, 2));
        assert_eq!(std::fs::read(&path).unwrap(), b"headbody");
        assert_eq!(
            std::fs::read_to_string(index_path(&path)).unwrap(),
            "0 4\n1 8\n"
        );
    }

    #[test]
    fn bytes_beyond_the_index_are_cut_on_opening_and_before_the_next_append() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("audio-1.webm");
        let mut file = ChunkFile::open(&path).unwrap();
        file.append(0, b"head").unwrap();
        // A torn append: bytes written, never indexed.
        std::fs::OpenOptions::new()
            .append(true)
            .open(&path)
            .unwrap()
            .write_all(b"TORN")
            .unwrap();
        file.append(1, b"body").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"headbody");
        drop(file);
        // A crash mid-way through an index line and after a media write.
        let mut index = OpenOptions::new()
            .append(true)
            .open(index_path(&path))
            .unwrap();
        index.write_all(b"2 1").unwrap();
        let mut media = OpenOptions::new().append(true).open(&path).unwrap();
        media.write_all(b"more").unwrap();
        let reopened = ChunkFile::open(&path).unwrap();
        assert_eq!((reopened.acked(), reopened.chunks()), (8, 2));
        assert_eq!(std::fs::read(&path).unwrap(), b"headbody");
        assert_eq!(
            std::fs::read_to_string(index_path(&path)).unwrap(),
            "0 4\n1 8\n"
        );
    }
}
