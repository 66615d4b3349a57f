//! [`AppError`]: every HTTP error answer is JSON `{"error", "code", "suggestion"?}`. Client
//! errors say what was wrong; internal errors get a generic message and are logged once.

use axum::Json;
use axum::http::{HeaderName, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use serde_json::json;

use crate::dispatch::TriggerError;
use crate::wire::ErrorCode;

/// An error answer.
#[derive(Debug)]
pub struct AppError {
    status: StatusCode,
    code: ErrorCode,
    message: String,
    suggestion: Option<String>,
    // Boxed: rare, and it would double the size of every `Result<_, AppError>`.
    header: Option<Box<(HeaderName, HeaderValue)>>,
}

impl AppError {
    /// A client error with this status, code and message.
    pub fn new(status: StatusCode, code: ErrorCode, message: impl Into<String>) -> Self {
        AppError {
            status,
            code,
            message: message.into(),
            suggestion: None,
            header: None,
        }
    }

    /// The same error with one more response header (`WWW-Authenticate`, `Retry-After`).
    pub fn with_header(mut self, name: HeaderName, value: HeaderValue) -> Self {
        self.header = Some(Box::new((name, value)));
        self
    }

    /// 404 `not-found`.
    pub fn not_found(message: impl Into<String>) -> Self {
        Self::new(StatusCode::NOT_FOUND, ErrorCode::NotFound, message)
    }

    /// 400 `bad-request`.
    pub fn bad_request(message: impl Into<String>) -> Self {
        Self::new(StatusCode::BAD_REQUEST, ErrorCode::BadRequest, message)
    }

    /// 400 with a more precise code than `bad-request`.
    pub fn bad_request_with_code(code: ErrorCode, message: impl Into<String>) -> Self {
        Self::new(StatusCode::BAD_REQUEST, code, message)
    }

    /// 503 `corpus-unwritable`: the corpus log cannot be written, so nothing is acknowledged.
    pub fn log_unwritable(message: String) -> Self {
        Self::new(
            StatusCode::SERVICE_UNAVAILABLE,
            crate::events::LogUnwritable::CODE,
            message,
        )
    }

    /// 500, logged here once; the client sees a generic message.
    pub fn internal(error: impl std::fmt::Display) -> Self {
        tracing::error!(%error, "internal error");
        Self::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            ErrorCode::Internal,
            "internal error; see the server log",
        )
    }
}

impl From<TriggerError> for AppError {
    fn from(e: TriggerError) -> Self {
        let status = match e {
            TriggerError::UnknownAct { .. } => StatusCode::NOT_FOUND,
            TriggerError::UnknownContext { .. } | TriggerError::UnknownLanguage { .. } => {
                StatusCode::BAD_REQUEST
            }
            TriggerError::LanguageNotOffered { .. } => StatusCode::FORBIDDEN,
            TriggerError::AlreadySpeaking { .. } => StatusCode::CONFLICT,
        };
        AppError {
            status,
            code: e.code(),
            message: e.to_string(),
            suggestion: e.suggestion().map(str::to_owned),
            header: None,
        }
    }
}

impl IntoResponse for AppError {
    fn into_response(self) -> Response {
        let mut body = json!({ "error": self.message, "code": self.code });
        if let Some(s) = self.suggestion {
            body["suggestion"] = s.into();
        }
        let mut response = (self.status, Json(body)).into_response();
        if let Some(header) = self.header {
            let (name, value) = *header;
            response.headers_mut().insert(name, value);
        }
        response
    }
}
