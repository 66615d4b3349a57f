//! `/static/...`: the shells' scripts and styles, the files of the repository's `static/`
//! folder embedded in the binary by `rust-embed` (also in debug builds, so a deployed
//! `docent` needs no checkout beside it). Any other name is a 404.

use std::borrow::Cow;

use axum::extract::Path;
use axum::extract::rejection::PathRejection;
use axum::http::header;
use axum::response::{IntoResponse, Response};
use rust_embed::RustEmbed;

use crate::http::AppError;

const JS: &str = "text/javascript; charset=utf-8";
const CSS: &str = "text/css; charset=utf-8";

/// Every file under `static/`, by its path there (`operator/main.js`).
#[derive(RustEmbed)]
#[folder = "static/"]
struct StaticFiles;

/// The content type and content of a static file, if there is one by that name (only
/// scripts and style sheets are served).
pub fn lookup(name: &str) -> Option<(&'static str, &'static str)> {
    let kind = match name.rsplit_once('.')?.1 {
        "js" => JS,
        "css" => CSS,
        _ => return None,
    };
    // Embedded files are borrowed from the binary; the `debug-embed` feature makes that so in
    // debug builds as well.
    let Cow::Borrowed(bytes) = StaticFiles::get(name)?.data else {
        return None;
    };
    Some((kind, std::str::from_utf8(bytes).ok()?))
}

/// `GET /static/{name}`
pub async fn serve_static(path: Result<Path<String>, PathRejection>) -> Response {
    let name = match path {
        Ok(Path(name)) => name,
        Err(e) => return AppError::not_found(format!("no such file: {e}")).into_response(),
    };
    match lookup(&name) {
        // `no-cache`: browsers revalidate, so a new server version is picked up at once.
        Some((kind, body)) => (
            [
                (header::CONTENT_TYPE, kind),
                (header::CACHE_CONTROL, "no-cache"),
            ],
            body,
        )
            .into_response(),
        None => AppError::not_found(format!("no such static file: {name}")).into_response(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_file_is_served_with_a_header_comment_and_its_type() {
        let names: Vec<_> = StaticFiles::iter().collect();
        assert!(names.len() >= 30, "{names:?}");
        for name in names {
            let (kind, body) = lookup(&name).unwrap_or_else(|| panic!("{name} is not served"));
            assert!(body.starts_with("/*") || body.starts_with("//"), "{name}");
            assert_eq!(kind == JS, name.ends_with(".js"), "{name}");
        }
        assert!(lookup("kiosk.js").is_some());
        assert!(lookup("operator/main.js").is_some());
        assert!(lookup("../Cargo.toml").is_none());
        assert!(lookup("../server/lib.rs").is_none());
        assert!(lookup("nothing.js").is_none());
    }
}
