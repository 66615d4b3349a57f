//! `PUT /api/recordings/{recording}/chunks/{seq}`: a kiosk uploads chunk `seq` (from 0) of a
//! recording, with the recording's own upload token as its Bearer credential (it opens no
//! other door). The chunk is stored only when it is the next one and answered 200 `{acked,
//! next}` once on disk; a chunk stored before is answered the same without being appended
//! again; a chunk after a gap is refused 409 with the `next` one the server expects; a
//! recording that is closed (stopped, consent declined or withdrawn) or unknown is 410.

use axum::Json;
use axum::body::Bytes;
use axum::extract::{Path, State};
use axum::http::{HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use serde_json::json;

use super::Appending;
use super::chunks::Appended;
use crate::events::FailureCode;
use crate::http::AppError;
use crate::http::auth::bearer;
use crate::state::AppState;
use crate::wire::ErrorCode;

/// The largest chunk accepted: a second of 1080p VP8 with Opus is well below it.
pub const MAX_CHUNK_BYTES: usize = 8 * 1024 * 1024;

/// Why an upload is refused before its bytes are looked at.
#[derive(Debug)]
pub(super) enum Refusal {
    /// No open recording has this id.
    Gone,
    /// The token is not this recording's.
    Unauthorized,
}

/// The address chunk `seq` of `recording` is uploaded to, without the number.
pub(super) fn chunk_path(recording: u64) -> String {
    format!("/api/recordings/{recording}/chunks/")
}

/// `PUT /api/recordings/{recording}/chunks/{seq}`.
pub async fn put_chunk(
    State(state): State<AppState>,
    Path((id, seq)): Path<(String, String)>,
    headers: HeaderMap,
    body: Bytes,
) -> Result<Response, AppError> {
    // Read here, so that a bad number is a JSON `bad-request` like every other error.
    let (Ok(id), Ok(seq)) = (id.parse::<u64>(), seq.parse::<u64>()) else {
        return Err(AppError::bad_request(
            "the recording and the chunk are numbers: /api/recordings/RECORDING/chunks/SEQ",
        ));
    };
    let recordings = &state.recordings;
    let token = bearer(&headers).unwrap_or_default();
    let recording = match recordings.authorised(id, token) {
        Ok(recording) => recording,
        Err(Refusal::Gone) => return Ok(gone(id)),
        Err(Refusal::Unauthorized) => {
            return Err(AppError::new(
                StatusCode::UNAUTHORIZED,
                ErrorCode::Unauthorized,
                "this upload needs the token of its recording, from its `record` frame",
            ));
        }
    };
    let all = std::sync::Arc::clone(recordings);
    let (session, client) = (recording.session, recording.client);
    let stored = tokio::task::spawn_blocking(move || all.append(&recording, seq, &body))
        .await
        .map_err(AppError::internal)?;
    match stored {
        Appending::Closed => Ok(gone(id)),
        Appending::OverLimit(over) => {
            recordings.over_limit(client, id, &over);
            Err(AppError::new(
                StatusCode::INSUFFICIENT_STORAGE,
                ErrorCode::RecordingLimit,
                over.message,
            ))
        }
        // Consent refused while it was written: the refusal removed it with the rest, and
        // no acknowledgement may follow the refusal's.
        Appending::Done(Ok(Appended::Stored { .. })) if !recordings.may_keep(session) => {
            Ok(gone(id))
        }
        Appending::Done(Ok(Appended::Stored { acked, next, .. })) => {
            Ok(Json(json!({ "acked": acked, "next": next })).into_response())
        }
        Appending::Done(Ok(Appended::Gap { next })) => Ok((
            StatusCode::CONFLICT,
            Json(json!({
                "error": format!("chunk {seq} comes after a gap: send chunk {next} first"),
                "code": ErrorCode::ChunkOutOfOrder,
                "next": next,
            })),
        )
            .into_response()),
        Appending::Done(Err(e)) => {
            let message = format!("the server could not store chunk {seq} of recording {id}: {e}");
            recordings.failed(client, Some(id), FailureCode::DiskError, &message);
            Err(AppError::internal(message))
        }
    }
}

/// 410 `recording-gone`: the kiosk stops uploading this recording.
fn gone(id: u64) -> Response {
    let message = format!(
        "recording {id} takes no more chunks: it was stopped, its visitors declined or \
         withdrew consent, or the server restarted"
    );
    AppError::new(StatusCode::GONE, ErrorCode::RecordingGone, message).into_response()
}
