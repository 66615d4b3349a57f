//! The MCAP export's own cases, one fixture each: media files the manifest lists (as the
//! recorder writes them: `media` in `session.json`), linked by metadata, a missing one told;
//! a `pose` line without its numbers and a manifest without a clock, refused word for word.

use std::path::{Path, PathBuf};

use docent::corpus::export::{ExportError, ExportFormat, ExportWarning, export_session};
use docent::corpus::layout::{SESSION_EVENTS, SESSION_MANIFEST, SESSIONS_DIR};
use serde_json::{Value, json};

use crate::corpus_export::generated;
use crate::corpus_export::mcap::{read_mcap, zero_ns};

/// A generated session of `seconds` in a temporary corpus.
fn generated_session(seconds: u64) -> (tempfile::TempDir, PathBuf) {
    let corpus = tempfile::tempdir().unwrap();
    let session = corpus.path().join(SESSIONS_DIR).join(generated::NAME);
    generated::write_session(&session, seconds, None).unwrap();
    (corpus, session)
}

fn manifest(session: &Path) -> Value {
    serde_json::from_slice(&std::fs::read(session.join(SESSION_MANIFEST)).unwrap()).unwrap()
}

fn write_manifest(session: &Path, manifest: &Value) {
    let text = serde_json::to_vec_pretty(manifest).unwrap();
    std::fs::write(session.join(SESSION_MANIFEST), text).unwrap();
}

#[test]
fn media_the_manifest_lists_are_linked_on_the_session_clock_and_a_missing_one_is_told() {
    let (_corpus, session) = generated_session(60);
    let mut with_media = manifest(&session);
    with_media["media"] = json!([
        {"file": "media/audio-1.webm", "track": "audio", "mime": "audio/webm;codecs=opus",
         "start_us": 1_234_567, "recording": 1},
        {"file": "media/video-1.webm", "track": "video", "mime": "video/webm",
         "start_us": 30_000_000, "recording": 2}
    ]);
    write_manifest(&session, &with_media);
    std::fs::create_dir_all(session.join("media")).unwrap();
    std::fs::write(session.join("media/audio-1.webm"), b"\x1a\x45\xdf\xa3").unwrap();

    let out = tempfile::tempdir().unwrap();
    let exported = export_session(&session, ExportFormat::Mcap, out.path()).unwrap();
    let missing = ExportWarning::MediaNotInSession {
        file: "media/video-1.webm".to_owned(),
    };
    assert_eq!(exported.warnings.last(), Some(&missing));
    assert_eq!(
        missing.to_string(),
        "session.json lists the media file \"media/video-1.webm\", which is not a file in the \
         session's folder (deleted, moved, or a path outside it): the MCAP's `docent.media` \
         names it all the same, but a player will not find it there, and the EAF has no WAV \
         copy of it"
    );

    let read = read_mcap(&exported.files[0]);
    let zero = zero_ns(&with_media);
    let media = &read["metadata"]["docent.media"];
    let start = |us: u64| (zero + us * 1000).to_string();
    assert_eq!(
        media,
        &json!([
            {"file": "media/audio-1.webm", "track": "audio", "mime": "audio/webm;codecs=opus",
             "start_us": "1234567", "recording": "1", "start_ns": start(1_234_567)},
            {"file": "media/video-1.webm", "track": "video", "mime": "video/webm",
             "start_us": "30000000", "recording": "2", "start_ns": start(30_000_000)}
        ])
    );
    let session_record = &read["metadata"]["docent.session"][0];
    assert!(
        session_record.get("media").is_none() && session_record.get("media.0").is_none(),
        "the media are their own records: {session_record}"
    );
    assert_eq!(read["attachments"], json!([]));
}

#[test]
fn a_pose_without_its_numbers_is_a_damaged_line() {
    let (_corpus, session) = generated_session(10);
    let events = session.join(SESSION_EVENTS);
    let text = std::fs::read_to_string(&events).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let n = lines
        .iter()
        .position(|l| l.contains(r#""type":"pose""#))
        .unwrap();
    let mut pose: Value = serde_json::from_str(&lines[n]).unwrap();
    pose.as_object_mut().unwrap().remove("heading");
    lines[n] = pose.to_string();
    std::fs::write(&events, lines.join("\n") + "\n").unwrap();

    let out = tempfile::tempdir().unwrap();
    let error = export_session(&session, ExportFormat::Mcap, out.path()).unwrap_err();
    assert!(matches!(error, ExportError::DamagedLog { .. }), "{error:?}");
    assert_eq!(
        error.to_string(),
        format!(
            "{}:{}: the session's log is damaged: a `pose` without its numbers `x`, `y` and \
             `heading`. Nothing was exported; repair or remove that line (keep a copy of the \
             original) and export again",
            events.display(),
            n + 1
        )
    );
    assert_eq!(std::fs::read_dir(out.path()).unwrap().count(), 0);
}

#[test]
fn a_manifest_without_a_clock_is_refused() {
    let (_corpus, session) = generated_session(10);
    let mut no_clock = manifest(&session);
    no_clock["started"]["time"] = json!("yesterday");
    write_manifest(&session, &no_clock);
    let out = tempfile::tempdir().unwrap();
    let error = export_session(&session, ExportFormat::Mcap, out.path()).unwrap_err();
    assert_eq!(
        error.to_string(),
        format!(
            "{}: the session's manifest is missing or damaged (its `started.time` \"yesterday\" \
             is not an RFC 3339 time, which the MCAP's clock starts from: timestamp format is \
             invalid); nothing was exported",
            session.join(SESSION_MANIFEST).display()
        )
    );
}
