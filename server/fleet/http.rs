//! The fleet view over HTTP, the same on any Docent started with `--mqtt` and on
//! `docent fleet`: the page `GET /fleet` (open, like `/operator`: it holds nothing until its
//! operator signs in), and behind the operator credential (`Authorization: Bearer`, never in
//! an address) `GET /api/fleet` (the link and the robots), `GET /api/fleet/updates` (a
//! `text/event-stream` of changes, read by the page with `fetch` so the credential stays in a
//! header) and `POST /api/fleet/robots/{robot}/stop`. Refused credentials count in the same
//! `Attempts` and are logged as the rest of the HTTP API's are.

use std::convert::Infallible;
use std::net::SocketAddr;
use std::sync::Arc;

use askama::Template;
use axum::extract::{ConnectInfo, FromRef, FromRequestParts, Path, State};
use axum::http::StatusCode;
use axum::http::request::Parts;
use axum::response::sse::{Event as Sse, KeepAlive};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use futures_util::Stream;
use serde_json::{Value, json};
use tokio::sync::broadcast::error::RecvError;
use tokio_util::sync::CancellationToken;

use super::view::{FleetView, StopFailed};
use crate::access::{Access, Needed};
use crate::events::Hub;
use crate::http::AppError;
use crate::http::auth::{bearer, log_refusal, refusal_error, same_origin};
use crate::state::AppState;
use crate::wire::ErrorCode;

/// What the fleet routes need, from a Docent's state or `docent fleet`'s.
#[derive(Clone)]
pub struct FleetHttp {
    /// The fleet, when this server follows one.
    pub view: Option<Arc<FleetView>>,
    /// Credentials and the failed-attempt memory.
    pub access: Arc<Access>,
    /// The event hub refusals are logged to (a Docent's), if any.
    pub hub: Option<Hub>,
    /// Ends the live streams at shutdown.
    pub shutdown: CancellationToken,
}

impl FromRef<AppState> for FleetHttp {
    fn from_ref(state: &AppState) -> Self {
        FleetHttp {
            view: state.fleet.view(),
            access: Arc::clone(&state.access),
            hub: Some(state.hub.clone()),
            shutdown: state.life.shutdown.clone(),
        }
    }
}

/// The fleet view's routes, for a router whose state gives a [`FleetHttp`].
pub fn routes<S>() -> Router<S>
where
    S: Clone + Send + Sync + 'static,
    FleetHttp: FromRef<S>,
{
    Router::new()
        .route("/fleet", get(page))
        .route("/api/fleet", get(fleet))
        .route("/api/fleet/updates", get(updates))
        .route("/api/fleet/robots/{robot}/stop", post(stop))
}

/// `pages/fleet/fleet.html`: the fleet view.
#[derive(Template)]
#[template(path = "fleet/fleet.html")]
pub struct FleetPage {
    /// False on an `--open` server: the page connects without asking.
    pub needs_credential: bool,
}

async fn page(State(http): State<FleetHttp>) -> Response {
    let page = FleetPage {
        needs_credential: !http.access.is_open(),
    };
    match page.render() {
        Ok(html) => axum::response::Html(html).into_response(),
        Err(e) => {
            tracing::error!("the fleet page did not render: {e}");
            AppError::new(
                StatusCode::INTERNAL_SERVER_ERROR,
                ErrorCode::Internal,
                "the page did not render",
            )
            .into_response()
        }
    }
}

/// Proof that the request carries the operator credential.
pub struct FleetOperator;

impl<S> FromRequestParts<S> for FleetOperator
where
    S: Send + Sync,
    FleetHttp: FromRef<S>,
{
    type Rejection = AppError;

    async fn from_request_parts(parts: &mut Parts, state: &S) -> Result<Self, AppError> {
        same_origin(&parts.headers)?;
        let http = FleetHttp::from_ref(state);
        let direct =
            (parts.extensions.get::<ConnectInfo<SocketAddr>>()).map(|ConnectInfo(a)| a.ip());
        let forwarded: Vec<Option<&str>> = (parts.headers.get_all("x-forwarded-for").iter())
            .map(|v| v.to_str().ok())
            .collect();
        let client = http.access.proxies().client(direct, &forwarded);
        match http
            .access
            .check(client, Needed::Operator, bearer(&parts.headers))
        {
            Ok(()) => Ok(FleetOperator),
            Err(refusal) => {
                let log = (&*http.access, http.hub.as_ref());
                log_refusal(log, parts, client.ip, refusal);
                Err(refusal_error(refusal, Needed::Operator))
            }
        }
    }
}

fn view_of(http: &FleetHttp) -> Result<&Arc<FleetView>, AppError> {
    http.view.as_ref().ok_or_else(|| {
        AppError::new(
            StatusCode::NOT_FOUND,
            ErrorCode::NotFound,
            "this Docent follows no fleet: start it with --mqtt URL --robot-id ID, or an mqtt: \
             section in docent.yaml (docs/FLEET.md)",
        )
    })
}

async fn fleet(_: FleetOperator, State(http): State<FleetHttp>) -> Result<Json<Value>, AppError> {
    Ok(Json(view_of(&http)?.snapshot()))
}

async fn updates(_: FleetOperator, State(http): State<FleetHttp>) -> Result<Response, AppError> {
    let view = Arc::clone(view_of(&http)?);
    let stream = update_stream(view, http.shutdown.clone());
    Ok(axum::response::Sse::new(stream)
        .keep_alive(KeepAlive::default())
        .into_response())
}

/// A snapshot, then each change; a fresh snapshot after falling behind; ends at shutdown.
fn update_stream(
    view: Arc<FleetView>,
    shutdown: CancellationToken,
) -> impl Stream<Item = Result<Sse, Infallible>> {
    let (snapshot, updates) = view.watch();
    let first = Sse::default().event("snapshot").data(snapshot.to_string());
    futures_util::stream::unfold(
        (Some(first), updates, view, shutdown),
        |(first, mut updates, view, shutdown)| async move {
            if let Some(first) = first {
                return Some((Ok(first), (None, updates, view, shutdown)));
            }
            let next = tokio::select! {
                () = shutdown.cancelled() => return None,
                next = updates.recv() => next,
            };
            let event = match next {
                Ok(update) => Sse::default().event("update").data(update),
                Err(RecvError::Lagged(_)) => Sse::default()
                    .event("snapshot")
                    .data(view.snapshot().to_string()),
                Err(RecvError::Closed) => return None,
            };
            Some((Ok(event), (None, updates, view, shutdown)))
        },
    )
}

async fn stop(
    _: FleetOperator,
    State(http): State<FleetHttp>,
    Path(robot): Path<String>,
) -> Result<Json<Value>, AppError> {
    let view = view_of(&http)?;
    match view.stop(&robot).await {
        Ok(answer) => Ok(Json(json!({ "robot": robot, "answer": answer }))),
        Err(failed) => {
            let (status, code) = match &failed {
                StopFailed::Unknown(_) => (StatusCode::NOT_FOUND, ErrorCode::NotFound),
                StopFailed::Refused { .. } => (StatusCode::BAD_GATEWAY, ErrorCode::RobotRefused),
                StopFailed::LinkDown(_) => (StatusCode::SERVICE_UNAVAILABLE, ErrorCode::BrokerDown),
                StopFailed::NoAnswer(_) | StopFailed::Unbound { .. } => {
                    (StatusCode::GATEWAY_TIMEOUT, ErrorCode::RobotSilent)
                }
                StopFailed::NoCredential => (StatusCode::CONFLICT, ErrorCode::NoCredential),
            };
            tracing::warn!(robot, "a fleet stop failed: {failed}");
            Err(AppError::new(status, code, failed.to_string()))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fleet_page_carries_its_contract_and_no_robot() {
        let page = FleetPage {
            needs_credential: true,
        }
        .render()
        .expect("renders");
        assert!(page.starts_with("<!doctype html>"), "{page}");
        assert!(page.contains(r#"data-credential="required""#), "{page}");
        assert!(page.contains(r#"src="/static/fleet/main.js""#), "{page}");
        assert!(page.contains(r#"<dialog id="signin""#), "{page}");
        assert!(page.contains(r#"<label for="signin-token">"#), "{page}");
        assert!(page.contains(r#"id="robots""#) && page.contains(r#"id="link""#));
        let open = FleetPage {
            needs_credential: false,
        }
        .render()
        .expect("renders");
        assert!(open.contains(r#"data-credential="open""#));
    }
}
