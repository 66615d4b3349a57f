//! `POST /api/sessions/{name}/annotations` (bearer): a researcher adds, changes or deletes an
//! annotation of a recorded session. The tier and code must be in the live bundle's codebook
//! and the times within the session; the line is appended to the session's
//! `annotations.jsonl` and synced to disk before the answer (`corpus/annotations.rs`), so an
//! annotation the page shows as saved survives a crash. Refusals carry their `ErrorCode`
//! (`docs/PROTOCOL.md`).

use axum::Json;
use axum::extract::{Path as UrlPath, State};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use serde::Deserialize;

use crate::corpus::annotations::{
    ANNOTATIONS_FILE, AnnotationError, AppendError, Draft, Edit, append, validate,
};
use crate::corpus::export::{ExportError, SessionExport};
use crate::http::AppError;
use crate::http::auth::Authorized;
use crate::http::body::RequestBody;
use crate::http::sessions::session_dir;
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
    UrlPath(name): UrlPath<String>,
    body: RequestBody,
) -> Result<Response, AppError> {
    let body: EditBody = body
        .object(EXAMPLE)?
        .ok_or_else(|| AppError::bad_request(format!("expected a body, e.g. {EXAMPLE}")))?;
    let corpus = state.replay.corpus.clone();
    let codebook = state.dispatcher.bundle().config.codebook.clone();
    let saved = tokio::task::spawn_blocking(move || {
        let (_, dir) = session_dir(&corpus, &name)?;
        let edit = body.edit()?;
        let status = match edit {
            Edit::Add(_) => StatusCode::CREATED,
            _ => StatusCode::OK,
        };
        if let Edit::Add(draft) | Edit::Change(_, draft) = &edit {
            // The session's length, as its log says it (a running session's so far).
            let length_us = match SessionExport::open(&dir) {
                Ok(session) => session.timeline().end_us,
                Err(ExportError::Recording(_)) => u64::MAX,
                // The annotations file itself cannot be read: it cannot be appended to either.
                Err(ExportError::Read { path, source }) if path.ends_with(ANNOTATIONS_FILE) => {
                    return Err(unwritable(&dir, &source));
                }
                Err(e) => return Err(AppError::internal(e)),
            };
            validate(&codebook, length_us, draft).map_err(refused)?;
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
