//! The MCAP export's metadata records, which Foxglove lists by name with their keys and
//! values (strings only): `docent.session`, the session's manifest, and one `docent.media`
//! per recorded media file, linked by its path (never embedded: see `docs/CORPUS.md`, "MCAP").

use std::collections::BTreeMap;
use std::path::{Component, Path};

use serde_json::Value;

/// The manifest's field listing the media files; written as `docent.media` records, not in
/// `docent.session`.
const MEDIA: &str = "media";

/// The session's manifest as `key → value` strings: nested objects flattened with dotted
/// keys (`started.time`), a `null` left out, numbers and booleans as JSON writes them; plus
/// `session_clock_zero_ns`, the session clock's zero on the MCAP's clock.
pub fn session(manifest: &Value, zero_ns: u64) -> BTreeMap<String, String> {
    let mut fields = BTreeMap::new();
    if let Some(object) = manifest.as_object() {
        for (key, value) in object.iter().filter(|(k, _)| *k != MEDIA) {
            flatten(key, value, &mut fields);
        }
    }
    fields.insert("session_clock_zero_ns".to_owned(), zero_ns.to_string());
    fields
}

/// A media file the manifest lists, as its `docent.media` record.
pub struct MediaRecord {
    /// The record's fields.
    pub fields: BTreeMap<String, String>,
    /// Its `file` when that is not a file inside the session's folder (missing, outside it, or
    /// not named): the researcher is told.
    pub not_found: Option<String>,
}

/// The manifest's `media` list (missing: none), each entry as it is (flattened like the
/// manifest) plus `start_ns`, where its first sample lies on the MCAP's clock.
pub fn media(manifest: &Value, zero_ns: u64, session_dir: &Path) -> Vec<MediaRecord> {
    let entries = manifest.get(MEDIA).and_then(Value::as_array);
    let mut records = Vec::new();
    for entry in entries.into_iter().flatten() {
        let mut fields = BTreeMap::new();
        flatten_into(entry, "", &mut fields);
        if let Some(start_us) = entry.get("start_us").and_then(Value::as_u64) {
            let start_ns = zero_ns + start_us * 1000;
            fields.insert("start_ns".to_owned(), start_ns.to_string());
        }
        let file = entry.get("file").and_then(Value::as_str);
        let found = file.is_some_and(|f| inside(Path::new(f)) && session_dir.join(f).is_file());
        let not_found =
            (!found).then(|| file.map_or_else(|| "(no file named)".to_owned(), str::to_owned));
        records.push(MediaRecord { fields, not_found });
    }
    records
}

/// Whether `file` names a place inside the folder it is relative to.
fn inside(file: &Path) -> bool {
    (file.components()).all(|c| matches!(c, Component::Normal(_) | Component::CurDir))
}

fn flatten(key: &str, value: &Value, into: &mut BTreeMap<String, String>) {
    match value {
        Value::Null => {}
        Value::String(s) => drop(into.insert(key.to_owned(), s.clone())),
        Value::Object(_) => flatten_into(value, &format!("{key}."), into),
        other => drop(into.insert(key.to_owned(), other.to_string())),
    }
}

fn flatten_into(object: &Value, prefix: &str, into: &mut BTreeMap<String, String>) {
    if let Some(object) = object.as_object() {
        for (key, value) in object {
            flatten(&format!("{prefix}{key}"), value, into);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn the_manifest_is_flattened_and_media_are_placed_on_the_clock() {
        let manifest = json!({
            "format": 1, "session": "S", "group": null,
            "started": {"seq": 3, "time": "2026-11-24T10:00:00.000Z"},
            "media": [{"file": "media/audio-1.webm", "track": "audio", "start_us": 1500}]
        });
        let fields = session(&manifest, 7_000);
        let want = [
            ("format", "1"),
            ("session", "S"),
            ("session_clock_zero_ns", "7000"),
            ("started.seq", "3"),
            ("started.time", "2026-11-24T10:00:00.000Z"),
        ];
        let want: BTreeMap<String, String> = want
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        assert_eq!(fields, want);
        let dir = tempfile::tempdir().unwrap();
        let records = media(&manifest, 7_000, dir.path());
        assert_eq!(records.len(), 1);
        assert_eq!(records[0].fields["start_ns"], "1507000");
        assert_eq!(records[0].fields["track"], "audio");
        assert_eq!(records[0].not_found.as_deref(), Some("media/audio-1.webm"));
        let outside = json!({"media": [{"file": "../other/events.jsonl"}]});
        let records = media(&outside, 0, dir.path());
        assert_eq!(
            records[0].not_found.as_deref(),
            Some("../other/events.jsonl")
        );
    }
}
