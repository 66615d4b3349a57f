//! Request bodies: a JSON object or nothing, read within the connection's body time limit.
//! A JSON array (or number, or string) is refused rather than mapped onto fields by position,
//! which serde would otherwise do for a struct (`["TextChild", true, "ref"]` would trigger).

use std::time::Duration;

use axum::body::Bytes;
use axum::extract::{FromRequest, Request};
use axum::http::{StatusCode, header};
use serde::de::DeserializeOwned;

use crate::http::connections::ConnectionLimits;
use crate::http::{AppError, MAX_BODY_BYTES};
use crate::wire::ErrorCode;

/// A request body read in whole, within the time limit (`408 body-timeout` otherwise) and
/// the size limit, [`MAX_BODY_BYTES`] (`413 body-too-large`: at once when `Content-Length`
/// says so, otherwise once the bytes pass it).
pub struct RequestBody(pub Bytes);

impl<S: Send + Sync> FromRequest<S> for RequestBody {
    type Rejection = AppError;

    async fn from_request(request: Request, state: &S) -> Result<Self, AppError> {
        let said = (request.headers().get(header::CONTENT_LENGTH))
            .and_then(|v| v.to_str().ok())
            .and_then(|v| v.parse::<u64>().ok());
        if said.is_some_and(|n| n > MAX_BODY_BYTES as u64) {
            return Err(too_large());
        }
        let limit = (request.extensions().get::<ConnectionLimits>())
            .map_or(ConnectionLimits::default().body_timeout, |l| l.body_timeout);
        match tokio::time::timeout(limit, Bytes::from_request(request, state)).await {
            Ok(Ok(bytes)) => Ok(RequestBody(bytes)),
            Ok(Err(rejection)) if rejection.status() == StatusCode::PAYLOAD_TOO_LARGE => {
                Err(too_large())
            }
            Ok(Err(rejection)) => Err(AppError::bad_request(rejection.body_text())),
            Err(_) => Err(body_timed_out(limit)),
        }
    }
}

/// `413 body-too-large`, with the limit in words.
fn too_large() -> AppError {
    let message = format!(
        "a request body is at most {} KiB ({MAX_BODY_BYTES} bytes)",
        MAX_BODY_BYTES / 1024
    );
    AppError::new(
        StatusCode::PAYLOAD_TOO_LARGE,
        ErrorCode::BodyTooLarge,
        message,
    )
}

/// `408 body-timeout`: the body did not arrive within `limit` of its headers.
pub(crate) fn body_timed_out(limit: Duration) -> AppError {
    let message = format!(
        "the request body did not arrive within {} s of its headers",
        limit.as_secs_f64()
    );
    AppError::new(StatusCode::REQUEST_TIMEOUT, ErrorCode::BodyTimeout, message)
}

impl RequestBody {
    /// The body as a `T` when it is a JSON object, `None` when empty (or only white space);
    /// `400 body-not-object` for any other JSON value, `400 bad-request` for one that is not
    /// JSON or does not fit `T`. `example` shows a right body in the message.
    pub fn object<T: DeserializeOwned>(&self, example: &str) -> Result<Option<T>, AppError> {
        let first = self.0.iter().find(|b| !b.is_ascii_whitespace());
        match first {
            None => Ok(None),
            Some(b'{') => serde_json::from_slice(&self.0).map(Some).map_err(|e| {
                AppError::bad_request(format!(
                    "the request body is not right: {e}; expected e.g. {example}"
                ))
            }),
            Some(_) => {
                let found = match serde_json::from_slice::<serde_json::Value>(&self.0) {
                    Ok(serde_json::Value::Array(_)) => "an array",
                    Ok(serde_json::Value::String(_)) => "a string",
                    Ok(serde_json::Value::Number(_)) => "a number",
                    Ok(serde_json::Value::Bool(_)) => "true or false",
                    Ok(_) => "null",
                    Err(_) => "not JSON",
                };
                Err(AppError::new(
                    StatusCode::BAD_REQUEST,
                    ErrorCode::BodyNotObject,
                    format!(
                        "the request body must be a JSON object with named fields, e.g. \
                         {example}, but it is {found}"
                    ),
                ))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Deserialize, Debug, PartialEq)]
    struct Context {
        context: String,
    }

    fn body(text: &str) -> RequestBody {
        RequestBody(Bytes::from(text.to_owned()))
    }

    #[test]
    fn only_objects_are_read_and_anything_else_is_named() {
        let example = r#"{"context": "TextGroup"}"#;
        let read = body(r#" {"context": "TextChild"}"#).object::<Context>(example);
        assert_eq!(
            read.unwrap(),
            Some(Context {
                context: "TextChild".into()
            })
        );
        assert_eq!(body(" \n").object::<Context>(example).unwrap(), None);
        for (text, found) in [
            (r#"["TextChild"]"#, "an array"),
            (r#""TextChild""#, "a string"),
            ("42", "a number"),
            ("null", "null"),
            ("nonsense", "not JSON"),
        ] {
            let error = body(text).object::<Context>(example).unwrap_err();
            let text = format!("{error:?}");
            assert!(text.contains("BodyNotObject"), "{text}");
            assert!(text.contains(found), "{text}");
        }
    }
}
