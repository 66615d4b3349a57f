//! Researchers' annotations of a session, `sessions/NAME/annotations.jsonl`, beside its log
//! and never in it: one JSON object per line, append-only, the latest line for an `id` wins
//! and `"deleted": true` removes it. Every append is synced to disk before it is
//! acknowledged, and appends to one file are serialised here, so ids never repeat. A last
//! line cut short by a crash is reported and left out, never fatal; the next append starts on
//! a line of its own. Read by the `/sessions` page (`http/sessions*.rs`) and the exports.
//! Format: `docs/CORPUS.md`, "Replay and annotation".

use std::collections::BTreeMap;
use std::fs::OpenOptions;
use std::io::{self, Read, Write};
use std::path::Path;
use std::sync::Mutex;

use serde::{Deserialize, Serialize};

use crate::lock;
use docent_content::config::Codebook;

/// The annotations file in a session's folder.
pub const ANNOTATIONS_FILE: &str = "annotations.jsonl";

/// One line of `annotations.jsonl`: an annotation as it is from then on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Annotation {
    /// Stable within the session: `a1`, `a2`, ...
    pub id: String,
    /// The codebook tier.
    #[serde(default)]
    pub tier: String,
    /// The code, one of the tier's.
    #[serde(default)]
    pub code: String,
    /// Start on the session clock (µs after `session.started`).
    #[serde(default)]
    pub start_us: u64,
    /// End on the session clock; equal to `start_us` for a point.
    #[serde(default)]
    pub end_us: u64,
    /// Who annotated (the name the page was signed in with), if given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub annotator: Option<String>,
    /// When this line was written (RFC 3339, UTC).
    #[serde(default)]
    pub time: String,
    /// This line removes the annotation.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub deleted: bool,
}

impl Annotation {
    /// Whether it marks an instant rather than a stretch.
    pub fn is_point(&self) -> bool {
        self.start_us == self.end_us
    }
}

/// A session's annotations as they stand.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Annotations {
    /// The live annotations (not deleted), by start, then tier, then id.
    pub annotations: Vec<Annotation>,
    /// Lines that could not be read: (line number, why). Left out, never fatal.
    pub problems: Vec<(usize, String)>,
}

/// Why an annotation is refused.
#[derive(Debug, PartialEq, Eq, thiserror::Error)]
pub enum AnnotationError {
    /// The tier is not in the codebook.
    #[error("there is no tier `{tier}` in the codebook (tiers: {known})")]
    UnknownTier {
        /// As asked.
        tier: String,
        /// The codebook's tiers.
        known: String,
    },
    /// The code is not one of its tier's.
    #[error("`{code}` is not a code of tier `{tier}` (codes: {known})")]
    UnknownCode {
        /// As asked.
        code: String,
        /// Its tier.
        tier: String,
        /// The tier's codes.
        known: String,
    },
    /// The times are backwards or outside the session.
    #[error("{0}")]
    BadTime(String),
    /// A change or removal of an annotation the session does not have.
    #[error("the session has no annotation `{0}` (it may have been deleted)")]
    UnknownAnnotation(String),
}

/// Serialises appends (and the id they allocate) within this process.
static APPENDS: Mutex<()> = Mutex::new(());

/// Reads the annotations of the session in `dir` (none when it has no file yet).
pub fn read_annotations(dir: &Path) -> io::Result<Annotations> {
    let mut bytes = Vec::new();
    match std::fs::File::open(dir.join(ANNOTATIONS_FILE)) {
        Ok(mut file) => file.read_to_end(&mut bytes)?,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(Annotations::default()),
        Err(e) => return Err(e),
    };
    Ok(parse(&bytes))
}

/// The annotations `bytes` (an `annotations.jsonl`) hold.
pub fn parse(bytes: &[u8]) -> Annotations {
    let mut latest: BTreeMap<String, Annotation> = BTreeMap::new();
    let mut problems = Vec::new();
    let lines: Vec<&[u8]> = bytes.split(|&b| b == b'\n').collect();
    let count = lines.len();
    for (n, line) in lines.into_iter().enumerate() {
        let last = n + 1 == count;
        if line.iter().all(u8::is_ascii_whitespace) {
            continue;
        }
        match serde_json::from_slice::<Annotation>(line) {
            Ok(a) if a.id.is_empty() => problems.push((n + 1, "the line has no `id`".into())),
            Ok(a) => {
                latest.insert(a.id.clone(), a);
            }
            Err(_) if last => problems.push((
                n + 1,
                "the last line is incomplete (cut short by a crash while it was written; it \
                 was never acknowledged)"
                    .into(),
            )),
            Err(e) => problems.push((n + 1, format!("not an annotation: {e}"))),
        }
    }
    let mut annotations: Vec<Annotation> = latest.into_values().filter(|a| !a.deleted).collect();
    annotations.sort_by(|a, b| {
        (a.start_us, &a.tier, id_number(&a.id)).cmp(&(b.start_us, &b.tier, id_number(&b.id)))
    });
    Annotations {
        annotations,
        problems,
    }
}

/// `a12` → 12, for ordering and for the next id.
fn id_number(id: &str) -> u64 {
    id.strip_prefix('a')
        .and_then(|n| n.parse().ok())
        .unwrap_or(0)
}

/// What a researcher asks for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Edit {
    /// A new annotation.
    Add(Draft),
    /// An annotation changed.
    Change(String, Draft),
    /// An annotation removed.
    Delete(String),
}

/// An annotation's content as asked.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Draft {
    /// The tier.
    pub tier: String,
    /// The code.
    pub code: String,
    /// Start, µs on the session clock.
    pub start_us: u64,
    /// End (the start for a point).
    pub end_us: u64,
    /// Who.
    pub annotator: Option<String>,
}

/// How far a session goes on its clock: what an annotation must lie within. Without it an
/// annotation could end anywhere, and every exported tier would stretch to it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SessionSpan {
    /// A session over (ended, or cut off by a crash): up to its last line.
    Ended {
        /// Its end, µs on its clock.
        end_us: u64,
    },
    /// A session being recorded: up to now.
    Running {
        /// Now, µs on its clock.
        now_us: u64,
    },
}

/// Checks `draft` against the codebook and the session's span.
pub fn validate(
    codebook: &Codebook,
    span: SessionSpan,
    draft: &Draft,
) -> Result<(), AnnotationError> {
    let names = |items: Vec<&str>| items.join(", ");
    let Some(tier) = codebook.tier(&draft.tier) else {
        let known = names(codebook.tiers.iter().map(|t| t.name.as_str()).collect());
        let tier = draft.tier.clone();
        return Err(AnnotationError::UnknownTier { tier, known });
    };
    if !tier.has(&draft.code) {
        let known = names(tier.codes.iter().map(|c| c.code.as_str()).collect());
        let (code, tier) = (draft.code.clone(), draft.tier.clone());
        return Err(AnnotationError::UnknownCode { code, tier, known });
    }
    if draft.end_us < draft.start_us {
        return Err(AnnotationError::BadTime(format!(
            "the annotation ends ({} µs) before it starts ({} µs)",
            draft.end_us, draft.start_us
        )));
    }
    let (limit, what) = match span {
        SessionSpan::Ended { end_us } => (end_us, "after the session's end at"),
        SessionSpan::Running { now_us } => (now_us, "after now: the session is still running, at"),
    };
    if draft.end_us > limit {
        return Err(AnnotationError::BadTime(format!(
            "the annotation ends at {} µs, {what} {limit} µs",
            draft.end_us
        )));
    }
    Ok(())
}

/// Applies `edit` (already validated) to the session in `dir`: appends its line, synced, and
/// returns it. `time` is the line's RFC 3339 time.
pub fn append(dir: &Path, edit: Edit, time: String) -> Result<Annotation, AppendError> {
    let _serial = lock(&APPENDS);
    let current = read_annotations(dir).map_err(AppendError::Io)?;
    let find = |id: &str| {
        (current.annotations.iter().find(|a| a.id == id).cloned())
            .ok_or_else(|| AppendError::Refused(AnnotationError::UnknownAnnotation(id.to_owned())))
    };
    let from = |id: String, d: Draft| Annotation {
        id,
        tier: d.tier,
        code: d.code,
        start_us: d.start_us,
        end_us: d.end_us,
        annotator: d.annotator,
        time: time.clone(),
        deleted: false,
    };
    let line = match edit {
        Edit::Add(draft) => {
            // Ids of deleted annotations are never given again: count every line's id.
            let next = max_id(dir).map_err(AppendError::Io)? + 1;
            from(format!("a{next}"), draft)
        }
        Edit::Change(id, draft) => {
            find(&id)?;
            from(id, draft)
        }
        Edit::Delete(id) => Annotation {
            deleted: true,
            time: time.clone(),
            ..find(&id)?
        },
    };
    write_line(dir, &line).map_err(AppendError::Io)?;
    Ok(line)
}

/// Why an append did not happen.
#[derive(Debug, thiserror::Error)]
pub enum AppendError {
    /// The edit names no annotation.
    #[error(transparent)]
    Refused(AnnotationError),
    /// The file could not be read or written: nothing was acknowledged.
    #[error("cannot write {ANNOTATIONS_FILE}: {0}")]
    Io(io::Error),
}

/// The highest id number any line of the file has used (deleted or not).
fn max_id(dir: &Path) -> io::Result<u64> {
    let text = match std::fs::read(dir.join(ANNOTATIONS_FILE)) {
        Ok(text) => text,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(0),
        Err(e) => return Err(e),
    };
    #[derive(Deserialize)]
    struct Id {
        id: String,
    }
    Ok((text.split(|&b| b == b'\n'))
        .filter_map(|l| serde_json::from_slice::<Id>(l).ok())
        .map(|l| id_number(&l.id))
        .max()
        .unwrap_or(0))
}

/// Appends `line`, on a line of its own, and syncs it (and a new file's folder entry).
fn write_line(dir: &Path, line: &Annotation) -> io::Result<()> {
    let path = dir.join(ANNOTATIONS_FILE);
    let created = !path.exists();
    let mut file = OpenOptions::new().append(true).create(true).open(&path)?;
    let mut bytes = Vec::with_capacity(256);
    // A torn last line (a crash mid-write) must not swallow this one.
    let length = file.metadata()?.len();
    if length > 0 {
        let mut last = [0u8];
        let mut reader = std::fs::File::open(&path)?;
        std::io::Seek::seek(&mut reader, io::SeekFrom::Start(length - 1))?;
        reader.read_exact(&mut last)?;
        if last[0] != b'\n' {
            bytes.push(b'\n');
        }
    }
    serde_json::to_writer(&mut bytes, line).map_err(io::Error::other)?;
    bytes.push(b'\n');
    file.write_all(&bytes)?;
    file.sync_data()?;
    if created {
        std::fs::File::open(dir)?.sync_all()?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn codebook() -> Codebook {
        Codebook::from_situations(&["question".to_owned(), "laughter".to_owned()])
    }

    fn draft(code: &str, start_us: u64, end_us: u64) -> Draft {
        Draft {
            tier: "situation".into(),
            code: code.into(),
            start_us,
            end_us,
            annotator: Some("ana".into()),
        }
    }

    #[test]
    fn the_latest_line_wins_deleted_ones_go_and_a_torn_last_line_is_reported() {
        let text = b"{\"id\":\"a1\",\"tier\":\"situation\",\"code\":\"question\",\"start_us\":5,\"end_us\":7,\"time\":\"t\"}\n\
{\"id\":\"a2\",\"tier\":\"situation\",\"code\":\"laughter\",\"start_us\":1,\"end_us\":1,\"time\":\"t\"}\n\
{\"id\":\"a1\",\"tier\":\"situation\",\"code\":\"laughter\",\"start_us\":5,\"end_us\":9,\"time\":\"t\"}\n\
{\"id\":\"a2\",\"deleted\":true}\n\
{\"id\":\"a3\",\"tier\":\"situ";
        let read = parse(text);
        let ids: Vec<(&str, &str, u64)> = (read.annotations.iter())
            .map(|a| (a.id.as_str(), a.code.as_str(), a.end_us))
            .collect();
        assert_eq!(ids, [("a1", "laughter", 9)]);
        assert_eq!(read.problems.len(), 1);
        assert_eq!(read.problems[0].0, 5);
        assert!(
            read.problems[0].1.contains("incomplete"),
            "{:?}",
            read.problems
        );
    }

    #[test]
    fn appends_are_synced_lines_and_ids_are_never_reused() {
        let dir = tempfile::tempdir().unwrap();
        let a1 = append(dir.path(), Edit::Add(draft("question", 1, 2)), "t1".into()).unwrap();
        assert_eq!(a1.id, "a1");
        append(dir.path(), Edit::Delete("a1".into()), "t2".into()).unwrap();
        // A crash left half a line: the next append starts a line of its own.
        let path = dir.path().join(ANNOTATIONS_FILE);
        let mut file = OpenOptions::new().append(true).open(&path).unwrap();
        file.write_all(b"{\"id\":\"a9").unwrap();
        let a2 = append(dir.path(), Edit::Add(draft("laughter", 3, 3)), "t3".into()).unwrap();
        assert_eq!(a2.id, "a2", "a1 deleted stays used");
        let read = read_annotations(dir.path()).unwrap();
        assert_eq!(read.annotations, [a2]);
        assert_eq!(read.problems.len(), 1, "{:?}", read.problems);
        let missing = append(dir.path(), Edit::Delete("a1".into()), "t4".into()).unwrap_err();
        assert!(matches!(
            missing,
            AppendError::Refused(AnnotationError::UnknownAnnotation(_))
        ));
    }

    #[test]
    fn tiers_codes_and_times_are_checked() {
        let book = codebook();
        let ten = SessionSpan::Ended { end_us: 10 };
        assert!(validate(&book, ten, &draft("question", 2, 10)).is_ok());
        let bad_tier = Draft {
            tier: "mood".into(),
            ..draft("question", 1, 2)
        };
        assert!(matches!(
            validate(&book, ten, &bad_tier),
            Err(AnnotationError::UnknownTier { .. })
        ));
        assert!(matches!(
            validate(&book, ten, &draft("yawn", 1, 2)),
            Err(AnnotationError::UnknownCode { .. })
        ));
        for (start, end) in [(5, 4), (9, 11)] {
            assert!(matches!(
                validate(&book, ten, &draft("question", start, end)),
                Err(AnnotationError::BadTime(_))
            ));
        }
        let running = SessionSpan::Running { now_us: 10 };
        assert!(validate(&book, running, &draft("question", 10, 10)).is_ok());
        let e = validate(
            &book,
            running,
            &draft("question", 0, 10_000_000_000_000_000),
        );
        assert_eq!(
            e.map_err(|e| e.to_string()),
            Err(
                "the annotation ends at 10000000000000000 µs, after now: the session is still \
                 running, at 10 µs"
                    .to_owned()
            )
        );
    }
}
