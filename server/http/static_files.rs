//! `/static/...`: the shells' scripts and styles, embedded in the binary so a deployed
//! `docent` needs no checkout beside it. A fixed table of names; anything else is a 404.

use axum::extract::Path;
use axum::extract::rejection::PathRejection;
use axum::http::header;
use axum::response::{IntoResponse, Response};

use crate::http::AppError;

const JS: &str = "text/javascript; charset=utf-8";
const CSS: &str = "text/css; charset=utf-8";

/// Every file served under `/static/`: name, content type, content.
const FILES: &[(&str, &str, &str)] = &[
    ("kiosk.js", JS, include_str!("../../static/kiosk.js")),
    ("socket.js", JS, include_str!("../../static/socket.js")),
    ("speech.js", JS, include_str!("../../static/speech.js")),
    (
        "speech-state.js",
        JS,
        include_str!("../../static/speech-state.js"),
    ),
    (
        "camera-kiosk.js",
        JS,
        include_str!("../../static/camera-kiosk.js"),
    ),
    (
        "operator/camera.js",
        JS,
        include_str!("../../static/operator/camera.js"),
    ),
    ("preview.js", JS, include_str!("../../static/preview.js")),
    ("kiosk.css", CSS, include_str!("../../static/kiosk.css")),
    ("preview.css", CSS, include_str!("../../static/preview.css")),
    (
        "docent-page.js",
        JS,
        include_str!("../../static/docent-page.js"),
    ),
    (
        "projector.js",
        JS,
        include_str!("../../static/projector.js"),
    ),
    (
        "projector.css",
        CSS,
        include_str!("../../static/projector.css"),
    ),
    // The content report (static/report/; it signs in with operator/signin.js).
    (
        "report/main.js",
        JS,
        include_str!("../../static/report/main.js"),
    ),
    (
        "report/render.js",
        JS,
        include_str!("../../static/report/render.js"),
    ),
    ("report.css", CSS, include_str!("../../static/report.css")),
    // The operator console (static/operator/, one module per job).
    (
        "operator/main.js",
        JS,
        include_str!("../../static/operator/main.js"),
    ),
    (
        "operator/access.js",
        JS,
        include_str!("../../static/operator/access.js"),
    ),
    (
        "operator/acts.js",
        JS,
        include_str!("../../static/operator/acts.js"),
    ),
    (
        "operator/actlist.js",
        JS,
        include_str!("../../static/operator/actlist.js"),
    ),
    (
        "operator/api.js",
        JS,
        include_str!("../../static/operator/api.js"),
    ),
    (
        "operator/camerapanel.js",
        JS,
        include_str!("../../static/operator/camerapanel.js"),
    ),
    (
        "operator/clients.js",
        JS,
        include_str!("../../static/operator/clients.js"),
    ),
    (
        "operator/connection.js",
        JS,
        include_str!("../../static/operator/connection.js"),
    ),
    (
        "operator/context.js",
        JS,
        include_str!("../../static/operator/context.js"),
    ),
    (
        "operator/dom.js",
        JS,
        include_str!("../../static/operator/dom.js"),
    ),
    (
        "operator/events.js",
        JS,
        include_str!("../../static/operator/events.js"),
    ),
    (
        "operator/history.js",
        JS,
        include_str!("../../static/operator/history.js"),
    ),
    (
        "operator/keys.js",
        JS,
        include_str!("../../static/operator/keys.js"),
    ),
    (
        "operator/live.js",
        JS,
        include_str!("../../static/operator/live.js"),
    ),
    (
        "operator/map.js",
        JS,
        include_str!("../../static/operator/map.js"),
    ),
    (
        "operator/marks.js",
        JS,
        include_str!("../../static/operator/marks.js"),
    ),
    (
        "operator/preview.js",
        JS,
        include_str!("../../static/operator/preview.js"),
    ),
    (
        "operator/proposals.js",
        JS,
        include_str!("../../static/operator/proposals.js"),
    ),
    (
        "operator/reloadbanner.js",
        JS,
        include_str!("../../static/operator/reloadbanner.js"),
    ),
    (
        "operator/search.js",
        JS,
        include_str!("../../static/operator/search.js"),
    ),
    (
        "operator/signin.js",
        JS,
        include_str!("../../static/operator/signin.js"),
    ),
    (
        "operator/stop.js",
        JS,
        include_str!("../../static/operator/stop.js"),
    ),
    (
        "operator/store.js",
        JS,
        include_str!("../../static/operator/store.js"),
    ),
    (
        "operator.css",
        CSS,
        include_str!("../../static/operator.css"),
    ),
];

/// The content type and content of a static file, if there is one by that name.
pub fn lookup(name: &str) -> Option<(&'static str, &'static str)> {
    FILES
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|(_, kind, body)| (*kind, *body))
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
    fn every_file_has_a_header_comment_and_a_known_type() {
        for (name, kind, body) in FILES {
            assert!(body.starts_with("/*") || body.starts_with("//"), "{name}");
            let ext = name.rsplit('.').next().unwrap_or_default();
            assert_eq!(*kind, if ext == "js" { JS } else { CSS }, "{name}");
        }
        assert!(lookup("kiosk.js").is_some());
        assert!(lookup("../Cargo.toml").is_none());
    }
}
