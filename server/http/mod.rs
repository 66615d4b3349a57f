//! The HTTP side: one route table ([`app`]), handlers grouped by resource.
//!
//! - `api`: the trigger API (`/api/...`, `/healthz`).
//! - `act_view`: `/api/acts`, every act as the console reads it (texts per language).
//! - `presence`: `/healthz?role=kiosk&name=NAME`, whether such a client is connected.
//! - `files`: bundle files under `/pages/` and `/media/`, never outside the bundle.
//! - `act_timers`: pages served with their `data-act-after` delays in milliseconds.
//! - `missing_page`: the friendly 404 page a touchscreen shows for a page that is not there.
//! - `shells`: the kiosk (`/`) and projector (`/projector`) pages, askama templates.
//! - `static_files`: `/static/...`, the shells' scripts and styles, embedded in the binary.
//! - `operator`: the operator console (`/operator`) and its settings (`/api/operator`).
//! - `report`: the content report (`/report`) and its data (`/api/report`).
//! - `sessions`: the replay and annotation page (`/sessions`) and its data (`/api/sessions`);
//!   `sessions_annotate`: annotations saved; `sessions_media`: recordings by media ticket;
//!   `session_name`: a session named in a URL, checked before it reaches the file system.
//! - `auth`: who is asking ([`auth::Peer`]) and whether they may ([`auth::Authorized`]).
//! - `body`: request bodies, JSON objects only, read within a time limit.
//! - `connections`: the accept loop: header and body time limits, connection caps.
//! - `open_files`: the open-files limit raised at start-up for the connection cap.
//! - `framing`: requests with both `Content-Length` and `Transfer-Encoding` found and refused.
//! - `error`: [`AppError`], the one error type at the HTTP edge.

mod act_timers;
mod act_view;
mod api;
pub(crate) mod auth;
mod body;
pub(crate) use body::body_timed_out;
mod connections;
mod error;
mod files;
mod framing;
mod missing_page;
mod open_files;
mod operator;
mod presence;
mod report;
mod session_name;
mod sessions;
mod sessions_annotate;
mod sessions_media;
mod shells;
pub(crate) mod static_files;

use axum::Router;
use axum::extract::DefaultBodyLimit;
use axum::routing::{get, post, put};
use tower_http::trace::TraceLayer;

pub use connections::{ConnectionLimits, ConnectionSlot, serve_connections};
pub use error::AppError;
pub use missing_page::MissingPageReports;
pub use open_files::{OWN_FILES, OpenFiles, make_room};
pub use presence::Absences;
pub use sessions_media::Replay;

use crate::state::AppState;
use crate::ws::ws_upgrade;

/// Largest request body accepted (trigger and context bodies are tiny): read by `body`'s
/// `RequestBody`, which answers a larger one `413 body-too-large` in JSON.
pub const MAX_BODY_BYTES: usize = 64 * 1024;

/// The whole route table.
pub fn app(state: AppState) -> Router {
    Router::new()
        .route("/", get(shells::kiosk))
        .route("/projector", get(shells::projector))
        .route("/preview", get(shells::preview))
        .route("/operator", get(operator::console))
        .route("/report", get(report::report_page))
        .route("/static/{*path}", get(static_files::serve_static))
        .route("/favicon.ico", get(api::no_favicon))
        .route("/healthz", get(api::health))
        .route("/api/acts", get(act_view::list_acts))
        .route("/api/acts/{label}/trigger", post(api::trigger_act))
        .route("/api/stop", post(api::stop_all))
        .route("/api/context", get(api::get_context).put(api::put_context))
        .route("/api/state", get(api::get_state))
        .route("/api/schedule/{at}", get(api::get_schedule))
        .route("/api/operator", get(operator::settings))
        .route("/api/report", get(report::get_report))
        .route("/sessions", get(sessions::sessions_page))
        .route("/api/sessions", get(sessions::list_sessions))
        .route("/api/sessions/{name}", get(sessions::get_session))
        .route(
            "/api/sessions/{name}/annotations",
            post(sessions_annotate::post_annotation),
        )
        .route(
            "/api/sessions/{name}/media-ticket",
            post(sessions_media::media_ticket),
        )
        .route(
            "/session-media/{ticket}/{*file}",
            get(sessions_media::serve_media),
        )
        .route("/pages/{*path}", get(files::serve_page))
        .route("/media/{*path}", get(files::serve_media))
        .route("/ws", get(ws_upgrade))
        .merge(crate::fleet::routes::<AppState>())
        .fallback(api::not_found)
        .method_not_allowed_fallback(api::method_not_allowed)
        .layer(DefaultBodyLimit::max(MAX_BODY_BYTES))
        // After the layer above: a recording chunk is read by its handler, after its token
        // was checked, with its own limits (`recording::MAX_CHUNK_BYTES`, the body time limit).
        .route(
            "/api/recordings/{recording}/chunks/{seq}",
            put(crate::recording::put_chunk),
        )
        .layer(TraceLayer::new_for_http())
        .with_state(state)
}
