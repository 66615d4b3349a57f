//! `/pages/...` and `/media/...`: files of the bundle being served. The path is checked by
//! [`resolve_in_bundle`] (no `..`, no absolute paths, exact case, no symlink leading out),
//! then served by tower-http's `ServeFile` (content type, ranges for video seeking). A media
//! file Chromium cannot show is served as converted ([`crate::media`]): the same address, the
//! converted content and its type; until it is ready, a 503 saying how far it is. HTML pages
//! under `/pages/` are the exception: the server adds the page script (`docent-page.js`, the
//! `data-act` taps and the `docent` JS API) to them, so authors include nothing themselves.
//! It goes first in `<head>` as a classic script, so `docent` exists before any script of the
//! page runs. A page that is not there answers a browser with a friendly page
//! ([`missing_page`](super::missing_page)), never with JSON. A file under a language folder
//! (`/pages/de/tour.html`) that is not there is served from the default language's `pages/`.

use axum::extract::rejection::PathRejection;
use axum::extract::{Path, Request, State};
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use tower::ServiceExt;
use tower_http::services::ServeFile;

use crate::content::{BundleArea, PathError, is_litter, resolve_in_bundle};
use crate::http::act_timers::with_act_timers;
use crate::http::{AppError, missing_page};
use crate::media::Served;
use crate::state::AppState;
use crate::wire::ErrorCode;

/// `GET /pages/{path}`: a touchscreen page or its assets.
pub async fn serve_page(
    state: State<AppState>,
    path: Result<Path<String>, PathRejection>,
    req: Request,
) -> Response {
    serve(state, BundleArea::Pages, path, req).await
}

/// `GET /media/{path}`: an image, video or sound.
pub async fn serve_media(
    state: State<AppState>,
    path: Result<Path<String>, PathRejection>,
    req: Request,
) -> Response {
    serve(state, BundleArea::Media, path, req).await
}

async fn serve(
    State(state): State<AppState>,
    area: BundleArea,
    path: Result<Path<String>, PathRejection>,
    req: Request,
) -> Response {
    let Path(rel) = match path {
        Ok(path) => path,
        Err(e) => {
            let rel = req.uri().path().trim_start_matches("/pages/").to_owned();
            let error = AppError::not_found(format!("no such file: {e}"));
            return not_found(&state, area, &rel, req.headers(), error).await;
        }
    };
    // What computers and editors leave in copied folders is not content: never served.
    if rel.split('/').any(is_litter) {
        let error = AppError::not_found(format!("no such file: {rel}"));
        return not_found(&state, area, &rel, req.headers(), error).await;
    }
    let bundle = state.dispatcher.bundle();
    let root = bundle.root.clone();
    // `pages/de/tour.html` missing: the default language's `pages/tour.html` (a page or an
    // asset a translated page links to), through the same gate (docs/AUTHORING.md).
    let fallback = (area == BundleArea::Pages)
        .then(|| {
            bundle
                .config
                .languages
                .page_fallback(&rel)
                .map(str::to_owned)
        })
        .flatten();
    drop(bundle);
    // Resolving reads directories: keep it off the threads that carry triggers.
    let checked = {
        let rel = rel.clone();
        tokio::task::spawn_blocking(move || {
            let found = resolve_in_bundle(&root, area, &rel);
            match (&found, fallback) {
                (Err(PathError::NotFound), Some(fallback)) => {
                    resolve_in_bundle(&root, area, &fallback)
                }
                _ => found,
            }
        })
        .await
    };
    let Ok(checked) = checked else {
        return AppError::internal("path check panicked").into_response();
    };
    let file = match checked {
        Ok(file) => file,
        // Every refusal looks like "not found": a request must not learn what exists outside.
        Err(PathError::Outside | PathError::NotFound | PathError::NotAFile) => {
            let error = AppError::not_found(format!("no such file: {rel}"));
            return not_found(&state, area, &rel, req.headers(), error).await;
        }
        Err(PathError::Miscased { actual }) => {
            let message = format!("no such file: {rel} (the file is spelled {actual})");
            let error = AppError::not_found(message);
            return not_found(&state, area, &rel, req.headers(), error).await;
        }
    };
    // A file Chromium cannot show is served converted, under its own name.
    let file = match state.media.lookup(&file) {
        Served::Original => file,
        Served::Converted(converted) => converted,
        Served::NotYet(reason) => {
            return AppError::new(
                StatusCode::SERVICE_UNAVAILABLE,
                ErrorCode::MediaConverting,
                reason,
            )
            .with_header(header::RETRY_AFTER, HeaderValue::from_static("5"))
            .into_response();
        }
        Served::Failed(reason) => {
            let code = ErrorCode::MediaUnconvertible;
            return AppError::new(StatusCode::UNPROCESSABLE_ENTITY, code, reason).into_response();
        }
    };
    if area == BundleArea::Pages && is_html(&file) {
        match serve_html(&file).await {
            Ok(Some(response)) => return response,
            Ok(None) => {} // Too large to rewrite: served as it is.
            Err(e) => return AppError::internal(e).into_response(),
        }
    }
    match ServeFile::new(file).oneshot(req).await {
        Ok(response) => response.into_response(),
        Err(e) => AppError::internal(e).into_response(),
    }
}

/// A missing file: the friendly page for a browser asking for a page, else the JSON `error`.
async fn not_found(
    state: &AppState,
    area: BundleArea,
    rel: &str,
    headers: &HeaderMap,
    error: AppError,
) -> Response {
    if area == BundleArea::Pages && missing_page::wants_page(headers, rel) {
        return missing_page::answer(state, rel, headers).await;
    }
    error.into_response()
}

/// The tag added to every HTML page under `/pages/`: a classic script, not a module, so that
/// it runs where it stands (first in `<head>`), before the page's own scripts.
const PAGE_SCRIPT: &[u8] = b"<script src=\"/static/docent-page.js\"></script>";

/// HTML pages larger than this are served untouched (no page script) rather than read whole.
const MAX_REWRITTEN_BYTES: u64 = 16 * 1024 * 1024;

fn is_html(file: &std::path::Path) -> bool {
    file.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("html") || e.eq_ignore_ascii_case("htm"))
}

/// The page with the page script added, or `None` when it is too large to rewrite.
async fn serve_html(file: &std::path::Path) -> std::io::Result<Option<Response>> {
    if tokio::fs::metadata(file).await?.len() > MAX_REWRITTEN_BYTES {
        return Ok(None);
    }
    let page = tokio::fs::read(file).await?;
    let headers = [
        // No charset: the page's own `<meta charset>` decides, as it would from ServeFile.
        (header::CONTENT_TYPE, "text/html"),
        (header::CACHE_CONTROL, "no-cache"),
    ];
    let page = with_page_script(&with_act_timers(page));
    Ok(Some((headers, page).into_response()))
}

/// Inserts [`PAGE_SCRIPT`] right after the `<head>` tag, else after the doctype, else first.
pub(crate) fn with_page_script(page: &[u8]) -> Vec<u8> {
    let at = tag_end(page, b"<head")
        .or_else(|| tag_end(page, b"<!doctype"))
        .unwrap_or(0);
    let mut out = Vec::with_capacity(page.len() + PAGE_SCRIPT.len());
    out.extend_from_slice(&page[..at]);
    out.extend_from_slice(PAGE_SCRIPT);
    out.extend_from_slice(&page[at..]);
    out
}

/// The index just past the `>` of the first tag named `name` (ASCII case-insensitive),
/// not matching longer names (`<head` is not `<header`).
fn tag_end(page: &[u8], name: &[u8]) -> Option<usize> {
    let mut from = 0;
    while let Some(found) = page
        .get(from..)?
        .windows(name.len())
        .position(|w| w.eq_ignore_ascii_case(name))
    {
        let after = from + found + name.len();
        match page.get(after) {
            Some(b'>' | b' ' | b'\t' | b'\n' | b'\r' | b'/') => {
                let close = page.get(after..)?.iter().position(|b| *b == b'>')?;
                return Some(after + close + 1);
            }
            _ => from = after,
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inject(page: &str) -> String {
        String::from_utf8(with_page_script(page.as_bytes())).expect("utf-8")
    }

    #[test]
    fn the_page_script_goes_right_after_head_or_the_doctype_or_first() {
        let tag = std::str::from_utf8(PAGE_SCRIPT).expect("utf-8");
        assert_eq!(
            inject("<!DOCTYPE html><header></header><HEAD lang=x><title>t</title>"),
            format!("<!DOCTYPE html><header></header><HEAD lang=x>{tag}<title>t</title>")
        );
        assert_eq!(
            inject("<!doctype html>\n<title>home</title>"),
            format!("<!doctype html>{tag}\n<title>home</title>")
        );
        assert_eq!(inject("<p>hi</p>"), format!("{tag}<p>hi</p>"));
        assert_eq!(inject(""), tag);
        assert_eq!(inject("<head"), format!("{tag}<head"));
    }
}
