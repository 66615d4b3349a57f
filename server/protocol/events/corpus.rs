//! What the corpus says about itself (`corpus.*`): the log could not be written (and why, in
//! the words the operator is shown), it can be again, events were lost in between, or its
//! folder was removed under the running server and made again. Written by the corpus writer,
//! which is the one that finds out; published through the hub like any event, so consoles
//! see it at once and the log has it once it can be written.

use std::io::ErrorKind;

use serde::{Deserialize, Serialize};

/// Why the corpus log cannot be written, as far as the operator can act on it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CorpusFault {
    /// No space left on the disk (or the user's quota is used up).
    DiskFull,
    /// The file system is read-only (remounted so after errors, or mounted so).
    ReadOnly,
    /// The folder is missing and cannot be made again (a parent gone, an unmounted disk).
    Missing,
    /// Docent may not write there.
    Denied,
    /// The log reached the largest file this process may write (`ulimit -f`).
    TooLarge,
    /// Any other write error (an I/O error of the disk).
    Io,
}

impl CorpusFault {
    /// The fault an operating system error stands for.
    pub fn of(kind: ErrorKind) -> Self {
        match kind {
            ErrorKind::StorageFull | ErrorKind::QuotaExceeded => CorpusFault::DiskFull,
            ErrorKind::ReadOnlyFilesystem => CorpusFault::ReadOnly,
            ErrorKind::NotFound => CorpusFault::Missing,
            ErrorKind::PermissionDenied => CorpusFault::Denied,
            ErrorKind::FileTooLarge => CorpusFault::TooLarge,
            _ => CorpusFault::Io,
        }
    }

    /// What the operator is told while the log of the corpus folder `dir` cannot be written:
    /// what happened, what to do, and what it means for the visit.
    pub fn operator_words(self, dir: &str, error: &str) -> String {
        let what = match self {
            CorpusFault::DiskFull => format!("The corpus disk is full ({dir}): free space on it"),
            CorpusFault::ReadOnly => format!(
                "The corpus disk is read-only ({dir}): make it writable again (remount it \
                 read-write, check the disk)"
            ),
            CorpusFault::Missing => format!(
                "The corpus folder {dir} is missing and cannot be made again ({error}): mount \
                 its disk or restore the folder"
            ),
            CorpusFault::Denied => {
                format!("Docent may not write the corpus folder {dir}: give it write permission")
            }
            CorpusFault::TooLarge => format!(
                "The corpus log reached the largest file Docent may write ({dir}): raise the \
                 file size limit (ulimit -f) and restart Docent"
            ),
            CorpusFault::Io => {
                format!("The corpus disk fails to write ({dir}: {error}): check the disk")
            }
        };
        format!("{what}; triggers are refused until then. Events wait in memory.")
    }
}

/// The log cannot be written (`corpus.unwritable`): said once when writing starts failing.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CorpusUnwritable {
    /// Why, for programs.
    pub fault: CorpusFault,
    /// The corpus folder.
    pub path: String,
    /// The operating system's error.
    pub error: String,
    /// What the operator is told ([`CorpusFault::operator_words`]).
    pub message: String,
}

/// The log is written again (`corpus.writable`), every event kept meanwhile included.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CorpusWritable {
    /// The corpus folder.
    pub path: String,
    /// Milliseconds the log could not be written.
    pub unwritable_ms: u64,
    /// What the operator is told.
    pub message: String,
}

/// Events that could not be kept while the log could not be written (`corpus.gap`): the
/// `seq`s from `from` through `to` are missing from the log, and this says so as soon as
/// the log is written again.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CorpusGap {
    /// The first `seq` lost.
    pub from: u64,
    /// The last `seq` lost.
    pub to: u64,
    /// How many events were lost (`to - from + 1`).
    pub count: u64,
    /// Why the log could not be written then; absent when it could, only slower than the
    /// events came (more than the memory bound in one batch).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fault: Option<CorpusFault>,
    /// Why they were dropped rather than kept, in words.
    pub reason: String,
}

/// A folder of the corpus was removed under the running server and made again
/// (`corpus.recreated`): the log goes on in it, what was in it before is gone.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CorpusRecreated {
    /// The log file that was removed and is written again from here on.
    pub path: String,
    /// What the operator is told.
    pub message: String,
}

impl CorpusRecreated {
    /// The event for the log file `path`, found removed.
    pub fn of(path: &str) -> Self {
        let message = format!(
            "The corpus log {path} was removed while Docent was running: Docent made it again \
             and goes on writing it. What it held before is gone unless it is restored from a \
             backup."
        );
        CorpusRecreated {
            path: path.to_owned(),
            message,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_full_disk_is_told_as_what_to_do_and_what_it_means() {
        let fault = CorpusFault::of(ErrorKind::StorageFull);
        assert_eq!(
            fault.operator_words("/srv/corpus", "No space left on device (os error 28)"),
            "The corpus disk is full (/srv/corpus): free space on it; triggers are refused \
             until then. Events wait in memory."
        );
        assert_eq!(
            CorpusFault::of(ErrorKind::ReadOnlyFilesystem),
            CorpusFault::ReadOnly
        );
    }
}
