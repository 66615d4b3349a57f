//! `PUT /api/recordings/{recording}/chunks/{seq}`: a kiosk uploads chunk `seq` (from 0) of a
//! recording, with the recording's own upload token as its Bearer credential (it opens no
//! other door). The chunk is stored only when it is the next one and answered 200 `{acked,
//! next}` once on disk; a chunk stored before is answered the same without being appended
//! again; a chunk after a gap is refused 409 with the `next` one the server expects; a
//! recording that is closed (stopped, consent declined or withdrawn) or unknown is 410.
//!
//! The token is checked from the headers before a byte of the body is read, so that nobody
//! without it can make the server hold a body (or wait for one); the body is then read as it
//! arrives, at most [`MAX_CHUNK_BYTES`] (`413 body-too-large`, as soon as `Content-Length`
//! or the bytes so far say so) and within the connection's body time limit (`408
//! body-timeout`).

use std::time::Duration;

use axum::Json;
use axum::body::{Body, Bytes};
use axum::extract::{Path, Request, State};
use axum::http::{HeaderMap, StatusCode, header};
use axum::response::{IntoResponse, Response};
use futures_util::StreamExt;
use serde_json::json;

use super::Appending;
use super::chunks::Appended;
use crate::events::FailureCode;
use crate::http::auth::bearer;
use crate::http::{AppError, ConnectionLimits};
use crate::state::AppState;
use crate::wire::ErrorCode;

/// The largest chunk accepted: a second of 1080p VP8 with Opus is well below it. The
/// `record` frame tells the kiosk, which splits a larger piece of its recording into
/// consecutive chunks (`static/recorder.js`).
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
    request: Request,
) -> Result<Response, AppError> {
    // Read here, so that a bad number is a JSON `bad-request` like every other error.
    let (Ok(id), Ok(seq)) = (id.parse::<u64>(), seq.parse::<u64>()) else {
        return Err(AppError::bad_request(
            "the recording and the chunk are numbers: /api/recordings/RECORDING/chunks/SEQ",
        ));
    };
    let recordings = &state.recordings;
    let token = bearer(request.headers()).unwrap_or_default();
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
    // While the log cannot be written the recording waits: the kiosk keeps its chunks and
    // sends them again (a 5xx), and the operators were told why (`corpus.unwritable`).
    if let Some(failure) = state.hub.log_failure() {
        return Err(paused(seq, &failure.to_string()));
    }
    let (head, body) = request.into_parts();
    let limit = (head.extensions.get::<ConnectionLimits>())
        .map_or(ConnectionLimits::default().body_timeout, |l| l.body_timeout);
    let body = read_chunk(&head.headers, body, limit).await?;
    let all = std::sync::Arc::clone(recordings);
    let (session, client) = (recording.session, recording.client);
    let turn = recordings
        .turn_to_write()
        .await
        .map_err(AppError::internal)?;
    let stored = tokio::task::spawn_blocking(move || all.append(&recording, seq, &body))
        .await
        .map_err(AppError::internal)?;
    drop(turn);
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
        // A disk that is full or read-only now may not be later: the kiosk tries again, while
        // the log's own failure tells the operator. With the log still written, nobody else
        // would tell: the recording fails with the reason instead (below).
        Appending::Done(Err(e))
            if matches!(
                e.kind(),
                std::io::ErrorKind::StorageFull | std::io::ErrorKind::ReadOnlyFilesystem
            ) && state.hub.log_failure().is_some() =>
        {
            Err(paused(seq, &e.to_string()))
        }
        Appending::Done(Err(e)) => {
            let message = format!("the server could not store chunk {seq} of recording {id}: {e}");
            recordings.failed(client, Some(id), FailureCode::DiskError, &message);
            Err(AppError::internal(message))
        }
    }
}

/// The chunk's bytes, read as they arrive: refused as soon as `Content-Length` or the bytes
/// so far are over [`MAX_CHUNK_BYTES`], or when the whole body has not come within `limit`.
async fn read_chunk(headers: &HeaderMap, body: Body, limit: Duration) -> Result<Bytes, AppError> {
    let announced = (headers.get(header::CONTENT_LENGTH))
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.parse::<u64>().ok());
    if announced.is_some_and(|n| n > MAX_CHUNK_BYTES as u64) {
        return Err(too_large());
    }
    let capacity = announced.map_or(0, |n| usize::try_from(n).unwrap_or(0));
    let read = async move {
        let mut bytes = Vec::with_capacity(capacity);
        let mut stream = body.into_data_stream();
        while let Some(piece) = stream.next().await {
            let piece =
                piece.map_err(|e| AppError::bad_request(format!("body unreadable: {e}")))?;
            if bytes.len() + piece.len() > MAX_CHUNK_BYTES {
                return Err(too_large());
            }
            bytes.extend_from_slice(&piece);
        }
        Ok(Bytes::from(bytes))
    };
    match tokio::time::timeout(limit, read).await {
        Ok(read) => read,
        Err(_) => Err(crate::http::body_timed_out(limit)),
    }
}

/// 413 `body-too-large`, saying the limit in words so the kiosk's author knows what to send.
fn too_large() -> AppError {
    let message = format!(
        "a recording chunk is at most {} MiB ({MAX_CHUNK_BYTES} bytes); split a larger one \
         into consecutive chunks",
        MAX_CHUNK_BYTES / (1024 * 1024)
    );
    AppError::new(
        StatusCode::PAYLOAD_TOO_LARGE,
        ErrorCode::BodyTooLarge,
        message,
    )
}

/// 503 `corpus-unwritable`: chunk `seq` is not stored because of `why`; the kiosk keeps it
/// and the ones after it, and sends it again (`static/recorder.js` pauses).
fn paused(seq: u64, why: &str) -> AppError {
    AppError::log_unwritable(format!(
        "chunk {seq} not stored: {why}. The recording pauses: send it again once the corpus \
         can be written."
    ))
}

/// 410 `recording-gone`: the kiosk stops uploading this recording.
fn gone(id: u64) -> Response {
    let message = format!(
        "recording {id} takes no more chunks: it was stopped, its visitors declined or \
         withdrew consent, or the server restarted"
    );
    AppError::new(StatusCode::GONE, ErrorCode::RecordingGone, message).into_response()
}
