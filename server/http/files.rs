//! `/pages/...` and `/media/...`: files of the bundle being served. The path is checked by
//! [`resolve_in_bundle`] (no `..`, no absolute paths, exact case, no symlink leading out),
//! then served by tower-http's `ServeFile` (content type, ranges for video seeking).

use axum::extract::rejection::PathRejection;
use axum::extract::{Path, Request, State};
use axum::response::{IntoResponse, Response};
use tower::ServiceExt;
use tower_http::services::ServeFile;

use crate::content::{BundleArea, PathError, resolve_in_bundle};
use crate::http::AppError;
use crate::state::AppState;

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
        Err(e) => return AppError::not_found(format!("no such file: {e}")).into_response(),
    };
    let root = state.dispatcher.bundle().root.clone();
    // Resolving reads directories: keep it off the threads that carry triggers.
    let checked = {
        let rel = rel.clone();
        tokio::task::spawn_blocking(move || resolve_in_bundle(&root, area, &rel)).await
    };
    let Ok(checked) = checked else {
        return AppError::internal("path check panicked").into_response();
    };
    let file = match checked {
        Ok(file) => file,
        // Every refusal looks like "not found": a request must not learn what exists outside.
        Err(PathError::Outside | PathError::NotFound | PathError::NotAFile) => {
            return AppError::not_found(format!("no such file: {rel}")).into_response();
        }
        Err(PathError::Miscased { actual }) => {
            let message = format!("no such file: {rel} (the file is spelled {actual})");
            return AppError::not_found(message).into_response();
        }
    };
    match ServeFile::new(file).oneshot(req).await {
        Ok(response) => response.into_response(),
        Err(e) => AppError::internal(e).into_response(),
    }
}
