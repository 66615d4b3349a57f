//! A session named in a URL (`/api/sessions/{name}...`): [`SessionName`] takes the name from
//! the path and [`session_dir`] finds its folder. A name no session folder can have (not
//! UTF-8 once percent-decoded, holding a NUL or another control character, a path, longer
//! than a file name may be) is `404 unknown-session` before it comes near the file system:
//! `%00` used to reach it and come back as a 500.

use std::path::{Path, PathBuf};

use axum::extract::{FromRequestParts, Path as UrlPath};
use axum::http::StatusCode;
use axum::http::request::Parts;

use crate::corpus::catalog::{CorpusError, find_session};
use crate::http::AppError;
use crate::wire::ErrorCode;

/// The longest name a session folder can have: a file name's limit on Linux, in bytes.
const MAX_NAME_BYTES: usize = 255;

/// The `{name}` of a `/api/sessions/{name}...` route, checked with [`is_session_name`].
pub struct SessionName(pub String);

impl<S: Send + Sync> FromRequestParts<S> for SessionName {
    type Rejection = AppError;

    async fn from_request_parts(parts: &mut Parts, state: &S) -> Result<Self, AppError> {
        match UrlPath::<String>::from_request_parts(parts, state).await {
            Ok(UrlPath(name)) if is_session_name(&name) => Ok(SessionName(name)),
            Ok(UrlPath(name)) => Err(not_a_session(&name)),
            // Not UTF-8 once decoded (`%FF`): no session is named so.
            Err(_) => Err(AppError::new(
                StatusCode::NOT_FOUND,
                ErrorCode::UnknownSession,
                "the session's name in the address is not UTF-8 text: no session is named so",
            )),
        }
    }
}

/// Whether `name` could be a session folder's name directly in `sessions/`: not empty, not
/// `.` or `..`, no `/` or `\`, no control character (NUL, line breaks), at most 255 bytes.
pub fn is_session_name(name: &str) -> bool {
    !name.is_empty()
        && name.len() <= MAX_NAME_BYTES
        && name != "."
        && name != ".."
        && !name.contains(['/', '\\'])
        && !name.chars().any(char::is_control)
}

/// `404 unknown-session` for a name that cannot be a session's (quoted, so a control
/// character shows as an escape).
fn not_a_session(name: &str) -> AppError {
    let shown: String = name.chars().take(80).collect();
    AppError::new(
        StatusCode::NOT_FOUND,
        ErrorCode::UnknownSession,
        format!("{shown:?} is not the name of a session of the corpus"),
    )
}

/// The folder of session `name` in `corpus`; `404 unknown-session` for anything that is not
/// the name of a session folder directly in `sessions/` (a path, `..`, a link, a NUL).
pub fn session_dir(corpus: &Path, name: &str) -> Result<(String, PathBuf), AppError> {
    if !is_session_name(name) {
        return Err(not_a_session(name));
    }
    find_session(corpus, name).map_err(|e| match e {
        CorpusError::Unreadable { .. } => AppError::internal(e),
        CorpusError::UnknownSession { .. } => AppError::new(
            StatusCode::NOT_FOUND,
            ErrorCode::UnknownSession,
            format!("there is no session {name} in the corpus"),
        ),
        _ => not_a_session(name),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_name_of_a_session_folder_names_a_session() {
        let corpus = tempfile::tempdir().unwrap();
        let sessions = corpus.path().join("sessions");
        std::fs::create_dir_all(sessions.join("2026-11-24T10-15-02Z")).unwrap();
        std::fs::create_dir_all(corpus.path().join("days")).unwrap();
        std::os::unix::fs::symlink(corpus.path().join("days"), sessions.join("linked")).unwrap();
        let (name, dir) = session_dir(corpus.path(), "2026-11-24T10-15-02Z").unwrap();
        assert_eq!(
            (name.as_str(), dir),
            ("2026-11-24T10-15-02Z", sessions.join(&name))
        );
        let long = "x".repeat(256);
        let refused = [
            "..",
            ".",
            "",
            "../days",
            "sessions/2026-11-24T10-15-02Z",
            "a\\b",
            "\0",
            "2026-11-24T10-15-02Z\0",
            "a\nb",
            "\u{7f}",
            long.as_str(),
        ];
        for name in refused
            .into_iter()
            .chain(["linked", "2026-11-24T10-15-03Z", "/etc"])
        {
            let error = session_dir(corpus.path(), name).unwrap_err();
            let text = format!("{error:?}");
            assert!(text.contains("UnknownSession"), "{name:?}: {text}");
        }
        assert!(is_session_name(&"x".repeat(255)));
    }
}
