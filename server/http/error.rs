//! [`AppError`]: every HTTP error answer is JSON `{"error", "code", "suggestion"?}`. Client
//! errors say what was wrong; internal errors get a generic message and are logged once.

use axum::Json;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use serde_json::json;

use crate::dispatch::TriggerError;

/// An error answer.
#[derive(Debug)]
pub struct AppError {
    status: StatusCode,
    code: &'static str,
    message: String,
    suggestion: Option<String>,
}

impl AppError {
    /// A client error with this status, code and message.
    pub fn new(status: StatusCode, code: &'static str, message: impl Into<String>) -> Self {
        AppError {
            status,
            code,
            message: message.into(),
            suggestion: None,
        }
    }

    /// 404 `not-found`.
    pub fn not_found(message: impl Into<String>) -> Self {
        Self::new(StatusCode::NOT_FOUND, "not-found", message)
    }

    /// 400 `bad-request`.
    pub fn bad_request(message: impl Into<String>) -> Self {
        Self::new(StatusCode::BAD_REQUEST, "bad-request", message)
    }

    /// 500, logged here once; the client sees a generic message.
    pub fn internal(error: impl std::fmt::Display) -> Self {
        tracing::error!(%error, "internal error");
        Self::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            "internal",
            "internal error; see the server log",
        )
    }
}

impl From<TriggerError> for AppError {
    fn from(e: TriggerError) -> Self {
        let status = match e {
            TriggerError::UnknownAct { .. } => StatusCode::NOT_FOUND,
            TriggerError::UnknownContext { .. } => StatusCode::BAD_REQUEST,
        };
        AppError {
            status,
            code: e.code(),
            message: e.to_string(),
            suggestion: e.suggestion().map(str::to_owned),
        }
    }
}

impl IntoResponse for AppError {
    fn into_response(self) -> Response {
        let mut body = json!({ "error": self.message, "code": self.code });
        if let Some(s) = self.suggestion {
            body["suggestion"] = s.into();
        }
        (self.status, Json(body)).into_response()
    }
}
