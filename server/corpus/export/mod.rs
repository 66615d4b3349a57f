//! Exports one visitor session to the formats researchers open: ELAN's EAF 3.0 (`eaf.rs`),
//! Praat's TextGrid (`textgrid.rs`), a CSV of utterances and touches (`csv.rs`), MCAP for
//! Foxglove and Lichtblick (`mcap.rs`) and a copy of the JSON Lines log they are all made
//! from. The session's log is read once (`timeline.rs`) into intervals and points on the
//! session clock, which `tiers.rs` lays out as the tiers ELAN and Praat both get. The
//! researchers' annotations (`corpus/annotations.rs`) are their own tiers in each format, with
//! the codebook of the session's bundle (`docent.yaml`'s `codebook:`) as their vocabulary when
//! it still loads. With the EAF go WAV copies of the recordings' sound on the session clock
//! (`wav.rs`, decoded by `webm_audio.rs`), which it links. Formats, tiers and time base:
//! `docs/CORPUS.md`, "Exports".
//!
//! An export never writes half a file: each is written beside its place and renamed. A session
//! still being recorded is refused; one whose server was killed is exported up to its last
//! whole line, with a warning that says so.

mod csv;
mod eaf;
mod error;
mod mcap;
mod textgrid;
mod tiers;
pub mod timeline;
mod wav;
mod webm_audio;

use std::collections::BTreeSet;
use std::fmt;
use std::fs::{File, TryLockError};
use std::io::{self, Read, Write};
use std::path::{Path, PathBuf};
use std::str::FromStr;

pub use error::{ExportError, ExportWarning, UnknownFormat};

use crate::annotations::{ANNOTATIONS_FILE, Annotation, read_annotations};
use crate::layout::{SESSION_EVENTS, SESSION_MANIFEST};
use crate::manifest::SessionManifest;
use docent_content::config::Codebook;
use docent_content::load_bundle;
use tiers::Tiers;
use timeline::{Timeline, TimelineReader};

/// Where `docent corpus export` writes by default, inside the session's folder (so that the
/// exports are shared, and purged, with their session).
pub const EXPORTS_DIR: &str = "exports";

/// A format a session can be exported to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ExportFormat {
    /// ELAN's EAF 3.0, `NAME.eaf`.
    Eaf,
    /// Praat's TextGrid (long text format, UTF-8), `NAME.TextGrid`.
    TextGrid,
    /// Utterances and touches, one row each (RFC 4180), `NAME.csv`.
    Csv,
    /// The session's log as it is, `NAME.jsonl`, and its annotations as they stand,
    /// `NAME.annotations.jsonl` (when it has any).
    Jsonl,
    /// MCAP for Foxglove and Lichtblick, `NAME.mcap`.
    Mcap,
}

impl ExportFormat {
    /// Every format, in the order `--format` lists them.
    pub const ALL: [ExportFormat; 5] = [
        Self::Eaf,
        Self::TextGrid,
        Self::Csv,
        Self::Jsonl,
        Self::Mcap,
    ];

    /// The name `--format` takes.
    pub fn name(self) -> &'static str {
        match self {
            Self::Eaf => "eaf",
            Self::TextGrid => "textgrid",
            Self::Csv => "csv",
            Self::Jsonl => "jsonl",
            Self::Mcap => "mcap",
        }
    }

    /// The file name extension, as the tools that open it expect it.
    pub fn extension(self) -> &'static str {
        match self {
            Self::Eaf => "eaf",
            Self::TextGrid => "TextGrid",
            Self::Csv => "csv",
            Self::Jsonl => "jsonl",
            Self::Mcap => "mcap",
        }
    }
}

impl fmt::Display for ExportFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for ExportFormat {
    type Err = UnknownFormat;

    fn from_str(name: &str) -> Result<Self, Self::Err> {
        (Self::ALL.into_iter())
            .find(|f| f.name().eq_ignore_ascii_case(name))
            .ok_or_else(|| UnknownFormat(name.to_owned()))
    }
}

/// What an export wrote, and what the researcher should know about it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Exported {
    /// The files written.
    pub files: Vec<PathBuf>,
    /// What the export went through with (an incomplete last line, a session never ended...).
    pub warnings: Vec<ExportWarning>,
}

/// Exports the session in `session_dir` to `format` in `out_dir` (created if needed).
pub fn export_session(
    session_dir: &Path,
    format: ExportFormat,
    out_dir: &Path,
) -> Result<Exported, ExportError> {
    SessionExport::open(session_dir)?.write(format, out_dir)
}

/// A session read for export: its log read once, ready to be written in any format.
pub struct SessionExport {
    name: String,
    dir: PathBuf,
    manifest: SessionManifest,
    /// The log's whole lines, as they are.
    log: Vec<u8>,
    timeline: Timeline,
    /// The researchers' annotations as they stand.
    annotations: Vec<Annotation>,
    tiers: Tiers,
    /// The act labels of the EAF's controlled vocabulary, sorted.
    vocabulary: Vec<String>,
    warnings: Vec<ExportWarning>,
}

impl SessionExport {
    /// Reads the session in `dir`: its manifest, its log (refused while a running Docent still
    /// writes it), and the labels of its bundle when that still loads.
    pub fn open(dir: &Path) -> Result<SessionExport, ExportError> {
        if !dir.is_dir() {
            return Err(ExportError::UnknownSession(dir.to_owned()));
        }
        let name = dir.file_name().map_or_else(
            || dir.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        let events = dir.join(SESSION_EVENTS);
        if !events.is_file() {
            return Err(ExportError::NotASession(dir.to_owned()));
        }
        let (bytes, locked) = read_with_lock(&events)?;
        let mut manifest =
            SessionManifest::read_from(dir).map_err(|e| ExportError::DamagedManifest {
                path: dir.join(SESSION_MANIFEST),
                problem: e.to_string(),
            })?;
        let mut warnings = Vec::new();
        // Consent is read here, once, for every format: without it no recording is copied,
        // linked or named, whatever files a crash or an older Docent left behind.
        if !manifest.media_allowed() {
            let left = std::fs::read_dir(dir.join(crate::layout::MEDIA_DIR))
                .map_or(0, |entries| entries.count());
            warnings.push(ExportWarning::MediaWithheld {
                consent: manifest.consent.clone(),
                files: left.max(manifest.media.len()),
            });
            manifest.media.clear();
        }
        let (log, timeline) = read_log(&events, bytes, &mut warnings)?;
        // A running Docent keeps the file it writes locked, also for a while after the
        // session's end: the end in the log is what tells a finished session.
        if locked && !timeline.ended {
            return Err(ExportError::Recording(name));
        }
        if !timeline.ended {
            let end_s = textgrid::seconds(timeline.end_us);
            warnings.push(ExportWarning::NotEnded { end_s });
        }
        let (vocabulary, codebook) = vocabulary(&manifest, &timeline, &mut warnings);
        let annotated = read_annotations(dir).map_err(|source| ExportError::Read {
            path: dir.join(ANNOTATIONS_FILE),
            source,
        })?;
        for (line, problem) in annotated.problems {
            let path = dir.join(ANNOTATIONS_FILE);
            warnings.push(ExportWarning::AnnotationLineLeftOut {
                path,
                line,
                problem,
            });
        }
        let mut annotations = annotated.annotations;
        if timeline.ended {
            annotations.retain(|a| {
                let within = a.end_us <= timeline.end_us;
                if !within {
                    warnings.push(ExportWarning::AnnotationPastEnd {
                        id: a.id.clone(),
                        end_s: textgrid::seconds(a.end_us),
                        session_end_s: textgrid::seconds(timeline.end_us),
                    });
                }
                within
            });
        }
        let tiers = Tiers::of(&timeline).with_annotations(&codebook, &annotations);
        Ok(SessionExport {
            name,
            dir: dir.to_owned(),
            manifest,
            log,
            timeline,
            annotations,
            tiers,
            vocabulary,
            warnings,
        })
    }

    /// The session's name: its folder's.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// What reading the session went through with.
    pub fn warnings(&self) -> &[ExportWarning] {
        &self.warnings
    }

    /// The session as read: what every format is made from.
    pub fn timeline(&self) -> &Timeline {
        &self.timeline
    }

    /// The researchers' annotations as they stand.
    pub fn annotations(&self) -> &[Annotation] {
        &self.annotations
    }

    /// Writes the session in `format` to `out_dir` (created if needed), as `NAME.EXTENSION`.
    pub fn write(&self, format: ExportFormat, out_dir: &Path) -> Result<Exported, ExportError> {
        let mut warnings = self.warnings.clone();
        let file = out_dir.join(format!("{}.{}", self.name, format.extension()));
        let mut copies = Vec::new();
        let bytes = match format {
            ExportFormat::Eaf => {
                let media = &self.manifest.media;
                copies = wav::write_copies(&self.dir, &self.name, media, out_dir, &mut warnings)?;
                let media = wav::links(&copies, out_dir)?;
                let header = eaf::Header {
                    date: &self.manifest.started.time,
                    session: &self.name,
                    docent: &self.manifest.docent,
                    media: &media,
                };
                let written = eaf::write(&self.tiers, &self.vocabulary, &header);
                let (bytes, replaced) = written.map_err(|source| ExportError::Write {
                    path: file.clone(),
                    source,
                })?;
                if replaced > 0 {
                    let count = replaced;
                    warnings.push(ExportWarning::CharactersReplaced { count });
                }
                bytes
            }
            ExportFormat::TextGrid => textgrid::write(&self.tiers),
            ExportFormat::Csv => csv::write(&self.timeline, &self.annotations),
            ExportFormat::Jsonl => self.log.clone(),
            ExportFormat::Mcap => self.mcap(&file, &mut warnings)?,
        };
        write_whole(out_dir, &file, &bytes)?;
        let mut files = vec![file];
        files.extend(copies.into_iter().map(|c| c.wav));
        if format == ExportFormat::Jsonl && !self.annotations.is_empty() {
            let file = out_dir.join(format!("{}.annotations.jsonl", self.name));
            let mut bytes = Vec::new();
            for a in &self.annotations {
                let line = serde_json::to_vec(a).map_err(|e| ExportError::Write {
                    path: file.clone(),
                    source: io::Error::other(e),
                })?;
                bytes.extend(line);
                bytes.push(b'\n');
            }
            write_whole(out_dir, &file, &bytes)?;
            files.push(file);
        }
        Ok(Exported { files, warnings })
    }
}

/// The log's bytes, and whether a running Docent holds its lock (it locks the file it is
/// writing; a killed one's lock is gone with it).
fn read_with_lock(events: &Path) -> Result<(Vec<u8>, bool), ExportError> {
    let read_error = |source| ExportError::Read {
        path: events.to_owned(),
        source,
    };
    let mut file = File::open(events).map_err(read_error)?;
    let locked = match file.try_lock_shared() {
        Ok(()) => false,
        Err(TryLockError::WouldBlock) => true,
        // A file system without locks: only the log's end can tell a recording session.
        Err(TryLockError::Error(_)) => false,
    };
    let mut bytes = Vec::new();
    file.read_to_end(&mut bytes).map_err(read_error)?;
    Ok((bytes, locked))
}

/// Reads the log's whole lines into a timeline; a last line without its `\n` (a kill cut it
/// short) is left out with a warning, any other line that is not a corpus line stops the
/// export at its place.
fn read_log(
    path: &Path,
    mut bytes: Vec<u8>,
    warnings: &mut Vec<ExportWarning>,
) -> Result<(Vec<u8>, Timeline), ExportError> {
    let whole = bytes.iter().rposition(|&b| b == b'\n').map_or(0, |n| n + 1);
    let damaged = |line, problem| ExportError::DamagedLog {
        path: path.to_owned(),
        line,
        problem,
    };
    if whole == 0 {
        let problem = "it has no whole line, not even its `session.started`".to_owned();
        return Err(damaged(1, problem));
    }
    let mut reader = TimelineReader::default();
    let mut count = 0;
    for (n, line) in bytes[..whole - 1].split(|&b| b == b'\n').enumerate() {
        count = n + 1;
        reader.read_line(line).map_err(|p| damaged(count, p.0))?;
    }
    if whole < bytes.len() {
        let line = count + 1;
        let path = path.to_owned();
        warnings.push(ExportWarning::IncompleteLastLine { path, line });
    }
    bytes.truncate(whole);
    Ok((bytes, reader.finish()))
}

/// The act labels of the EAF's vocabulary: the labels the session used and, when the session's
/// bundle still loads, all of the bundle's; sorted. And the bundle's codebook, when it loads
/// (without it, the annotations' own tiers and codes are the vocabulary).
fn vocabulary(
    manifest: &SessionManifest,
    timeline: &Timeline,
    warnings: &mut Vec<ExportWarning>,
) -> (Vec<String>, Codebook) {
    let mut labels: BTreeSet<String> = timeline.labels.clone();
    let mut codebook = Codebook::default();
    let why_not = match &manifest.bundle {
        None => Some("the session's manifest names no bundle".to_owned()),
        Some(folder) => {
            let report = load_bundle(Path::new(folder));
            match report.bundle {
                Some(bundle) => {
                    labels.extend(bundle.acts.into_iter().map(|a| a.label));
                    codebook = bundle.config.codebook;
                    None
                }
                None => {
                    let first = report.diagnostics.iter().find(|d| d.is_error());
                    let why = first.map_or_else(String::new, |d| {
                        format!(": {}:{}: {}", d.file, d.line, d.message)
                    });
                    Some(format!("its bundle {folder} does not load any more{why}"))
                }
            }
        }
    };
    if let Some(why) = why_not {
        warnings.push(ExportWarning::VocabularyFromSessionOnly(why));
    }
    (labels.into_iter().collect(), codebook)
}

/// Writes `bytes` to `file` whole: beside it first, then renamed over it.
fn write_whole(out_dir: &Path, file: &Path, bytes: &[u8]) -> Result<(), ExportError> {
    let write_error = |path: &Path| {
        let path = path.to_owned();
        move |source| ExportError::Write { path, source }
    };
    std::fs::create_dir_all(out_dir).map_err(write_error(out_dir))?;
    let mut partial = file.as_os_str().to_owned();
    partial.push(".partial");
    let partial = PathBuf::from(partial);
    let written = (|| -> io::Result<()> {
        let mut out = File::create(&partial)?;
        out.write_all(bytes)?;
        out.sync_data()?;
        std::fs::rename(&partial, file)
    })();
    if written.is_err() {
        let _ = std::fs::remove_file(&partial);
    }
    written.map_err(write_error(file))
}
