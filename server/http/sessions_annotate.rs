//! `POST /api/sessions/{name}/annotations` (bearer): a researcher adds, changes or deletes an
//! annotation of a recorded session. The tier and code must be in the live bundle's codebook
//! and the times within the session (an ended session's up to its end; a running session's
//! up to now on its clock, [`running_length_us`]); the line is appended to the session's
//! `annotations.jsonl` and synced to disk before the answer (`corpus/annotations.rs`), so an
//! annotation the page shows as saved survives a crash. Refusals carry their `ErrorCode`
//! (`docs/PROTOCOL.md`).

use std::time::SystemTime;

use axum::Json;
use axum::extract::State;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use serde::Deserialize;

use crate::corpus::annotations::{
    ANNOTATIONS_FILE, AnnotationError, AppendError, Draft, Edit, SessionSpan, append, validate,
};
use crate::corpus::export::{ExportError, SessionExport};
use crate::corpus::manifest::SessionManifest;
use crate::http::AppError;
use crate::http::auth::Authorized;
use crate::http::body::RequestBody;
use crate::http::session_name::{SessionName, session_dir};
use crate::state::AppState;
use crate::wire::ErrorCode;

/// What the page asks for: `action` `add` (no `id`), `change` (an `id` and the new content)
/// or `delete` (an `id` only).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct EditBody {
    action: Action,
    #[serde(default)]
    id: Option<String>,
    #[serde(default)]
    tier: Option<String>,
    #[serde(default)]
    code: Option<String>,
    #[serde(default)]
    start_us: Option<u64>,
    /// Absent: a point.
    #[serde(default)]
    end_us: Option<u64>,
    #[serde(default)]
    annotator: Option<String>,
}

#[derive(Deserialize, Clone, Copy)]
#[serde(rename_all = "lowercase")]
enum Action {
    Add,
    Change,
    Delete,
}

/// The longest annotator name kept.
const MAX_ANNOTATOR: usize = 80;

impl EditBody {
    fn edit(self) -> Result<Edit, AppError> {
        let missing = |field: &str| {
            AppError::bad_request(format!("the request needs `{field}`, e.g. {EXAMPLE}"))
        };
        let id = self.id;
        if let Action::Delete = self.action {
            return id.map(Edit::Delete).ok_or_else(|| missing("id"));
        }
        let start_us = self.start_us.ok_or_else(|| missing("start_us"))?;
        let annotator = (self
            .annotator
            .map(|a| a.trim().chars().take(MAX_ANNOTATOR).collect()))
        .filter(|a: &String| !a.is_empty());
        let draft = Draft {
            tier: self.tier.ok_or_else(|| missing("tier"))?,
            code: self.code.ok_or_else(|| missing("code"))?,
            start_us,
            end_us: self.end_us.unwrap_or(start_us),
            annotator,
        };
        match (self.action, id) {
            (Action::Add, None) => Ok(Edit::Add(draft)),
            (Action::Add, Some(_)) => Err(AppError::bad_request(
                "an `add` takes no `id`: Docent gives the new annotation its id",
            )),
            (_, Some(id)) => Ok(Edit::Change(id, draft)),
            (_, None) => Err(missing("id")),
        }
    }
}

const EXAMPLE: &str = r#"{"action": "add", "tier": "situation", "code": "question", "start_us": 5000000, "end_us": 7500000}"#;

/// The answer to a refused annotation.
fn refused(e: AnnotationError) -> AppError {
    let (status, code) = match &e {
        AnnotationError::UnknownTier { .. } => (StatusCode::BAD_REQUEST, ErrorCode::UnknownTier),
        AnnotationError::UnknownCode { .. } => (StatusCode::BAD_REQUEST, ErrorCode::UnknownCode),
        AnnotationError::BadTime(_) => (StatusCode::BAD_REQUEST, ErrorCode::BadTime),
        AnnotationError::UnknownAnnotation(_) => {
            (StatusCode::NOT_FOUND, ErrorCode::UnknownAnnotation)
        }
    };
    AppError::new(status, code, e.to_string())
}

/// How long the running session `manifest` describes has lasted, on its clock: the hub's
/// monotonic clock now less the session's start on it. A start the hub's clock has not
/// reached yet was stamped by another process (the hub's clock starts with the server), so
/// the wall clock since the start's `time` is taken instead (0 when that cannot be read).
pub fn running_length_us(manifest: &SessionManifest, hub_now_us: u64, now: SystemTime) -> u64 {
    let start = &manifest.started;
    if start.mono_us <= hub_now_us {
        return hub_now_us - start.mono_us;
    }
    let started = humantime::parse_rfc3339_weak(&start.time).ok();
    let elapsed = started.and_then(|t| now.duration_since(t).ok());
    elapsed.map_or(0, |d| u64::try_from(d.as_micros()).unwrap_or(u64::MAX))
}

/// `503 annotations-unwritable`, logged once.
fn unwritable(dir: &std::path::Path, e: &std::io::Error) -> AppError {
    tracing::error!(error = %e, dir = %dir.display(), "annotation not saved");
    AppError::new(
        StatusCode::SERVICE_UNAVAILABLE,
        ErrorCode::AnnotationsUnwritable,
        format!("the annotation was not saved: {ANNOTATIONS_FILE} cannot be written ({e})"),
    )
}

/// `POST /api/sessions/{name}/annotations`: 201 with the annotation added, 200 with the
/// annotation changed or the line that deleted it.
pub async fn post_annotation(
    _: Authorized,
    State(state): State<AppState>,
    SessionName(name): SessionName,
    body: RequestBody,
) -> Result<Response, AppError> {
    let body: EditBody = body
        .object(EXAMPLE)?
        .ok_or_else(|| AppError::bad_request(format!("expected a body, e.g. {EXAMPLE}")))?;
    let corpus = state.replay.corpus.clone();
    let codebook = state.dispatcher.bundle().config.codebook.clone();
    let hub = state.hub.clone();
    let saved = tokio::task::spawn_blocking(move || {
        let (_, dir) = session_dir(&corpus, &name)?;
        let edit = body.edit()?;
        let status = match edit {
            Edit::Add(_) => StatusCode::CREATED,
            _ => StatusCode::OK,
        };
        if let Edit::Add(draft) | Edit::Change(_, draft) = &edit {
            // The session's span: an ended one's as its log says it, a running one's so far.
            let span = match SessionExport::open(&dir) {
                Ok(session) => SessionSpan::Ended {
                    end_us: session.timeline().end_us,
                },
                Err(ExportError::Recording(_)) => {
                    let manifest = SessionManifest::read_from(&dir).map_err(|e| {
                        AppError::new(
                            StatusCode::CONFLICT,
                            ErrorCode::SessionRecording,
                            format!(
                                "the session has only just started: its manifest cannot be \
                                 read yet ({e}); annotate it again in a moment"
                            ),
                        )
                    })?;
                    let now_us = running_length_us(&manifest, hub.mono_us(), SystemTime::now());
                    SessionSpan::Running { now_us }
                }
                // The annotations file itself cannot be read: it cannot be appended to either.
                Err(ExportError::Read { path, source }) if path.ends_with(ANNOTATIONS_FILE) => {
                    return Err(unwritable(&dir, &source));
                }
                Err(e) => return Err(AppError::internal(e)),
            };
            validate(&codebook, span, draft).map_err(refused)?;
        }
        let time = humantime::format_rfc3339_millis(std::time::SystemTime::now()).to_string();
        match append(&dir, edit, time) {
            Ok(line) => Ok((status, line)),
            Err(AppendError::Refused(e)) => Err(refused(e)),
            Err(AppendError::Io(e)) => Err(unwritable(&dir, &e)),
        }
    })
    .await
    .unwrap_or_else(|e| Err(AppError::internal(e)))?;
    let (status, line) = saved;
    Ok((status, Json(line)).into_response())
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use super::*;
    use crate::corpus::manifest::SessionMark;

    fn started(mono_us: u64, time: &str) -> SessionManifest {
        let mark = SessionMark {
            seq: 1,
            time: time.to_owned(),
            mono_us,
            source: "operator".to_owned(),
            reason: None,
        };
        SessionManifest {
            format: 1,
            session: "s".to_owned(),
            number: 1,
            docent: "0".to_owned(),
            bundle: None,
            bundle_hash: None,
            started: mark,
            ended: None,
            group: None,
            context: None,
            consent: "recorded".to_owned(),
            media: Vec::new(),
        }
    }

    #[test]
    fn a_running_session_lasts_until_now_on_the_hubs_clock_else_the_wall_clocks() {
        let start = humantime::parse_rfc3339("2026-11-24T10:00:00Z").unwrap();
        let now = start + Duration::from_secs(90);
        let ours = started(5_000_000, "2026-11-24T10:00:00Z");
        assert_eq!(running_length_us(&ours, 7_500_000, now), 2_500_000);
        // Stamped on a clock ahead of this hub's: the wall clock says how long.
        let other = started(9_000_000_000, "2026-11-24T10:00:00.000Z");
        assert_eq!(running_length_us(&other, 7_500_000, now), 90_000_000);
        let unreadable = started(9_000_000_000, "yesterday");
        assert_eq!(running_length_us(&unreadable, 7_500_000, now), 0);
    }
}
