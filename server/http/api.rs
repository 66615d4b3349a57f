//! The trigger API: acts, triggers, stop, context, state and health. Routes reach devices only
//! through the dispatcher.

use crate::content::schedule::WallClock;
use axum::Json;
use axum::extract::rejection::{PathRejection, QueryRejection};
use axum::extract::{Path, Query, State};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use serde::Deserialize;
use serde_json::{Value, json};

use crate::dispatch::TriggerRequest;
use crate::events::Source;
use crate::http::AppError;
use crate::http::auth::Authorized;
use crate::http::body::RequestBody;
use crate::http::presence;
use crate::state::AppState;
use crate::wire::ErrorCode;
use crate::ws::protocol::{LimitsView, PROTOCOL_VERSION, TriggerOptions};

/// `GET /healthz`: liveness and versions; with `?role=...&name=...`, whether such a client is
/// connected (`presence`).
pub async fn health(
    State(state): State<AppState>,
    query: Result<Query<Vec<(String, String)>>, QueryRejection>,
) -> Response {
    let Query(pairs) = match query {
        Ok(pairs) => pairs,
        Err(rejection) => return AppError::bad_request(rejection.body_text()).into_response(),
    };
    if !pairs.is_empty() {
        return match presence::asked(pairs) {
            Ok(asked) => presence::presence(&state, &asked),
            Err(error) => error.into_response(),
        };
    }
    let bundle = state.dispatcher.bundle();
    Json(json!({
        "status": "ok",
        "version": env!("CARGO_PKG_VERSION"),
        "protocol": PROTOCOL_VERSION,
        "acts": bundle.acts.len(),
    }))
    .into_response()
}

/// `POST /api/acts/{label}/trigger` (credential needed): 202 with the trigger id and resolved
/// commands.
pub async fn trigger_act(
    State(state): State<AppState>,
    _: Authorized,
    label: Result<Path<String>, PathRejection>,
    body: RequestBody,
) -> Result<impl IntoResponse, AppError> {
    let Path(label) = label.map_err(|e| {
        AppError::bad_request(format!("the act label in the address is not right: {e}"))
    })?;
    let example = r#"{"context": "TextGroup", "interrupt": true, "ref": "b1"}"#;
    let body: TriggerOptions = body.object(example)?.unwrap_or_default();
    if let Some(failure) = state.hub.log_failure() {
        return Err(AppError::log_unwritable(failure.refusal()));
    }
    let request = TriggerRequest {
        context: body.context,
        interrupt: body.interrupt,
        reference: body.reference,
        ..TriggerRequest::new(label, Source::Http)
    };
    let triggered = state.dispatcher.trigger(request)?;
    logged(&state).await?;
    Ok((StatusCode::ACCEPTED, Json(triggered)))
}

/// `POST /api/stop` (credential needed): stops speech, drive and every queue.
pub async fn stop_all(
    State(state): State<AppState>,
    _: Authorized,
) -> Result<impl IntoResponse, AppError> {
    state.dispatcher.stop(Source::Http, "stop request");
    logged(&state).await?;
    Ok((StatusCode::ACCEPTED, Json(json!({ "stopped": true }))))
}

/// Waits until the corpus log holds every event published so far (those of the request just
/// carried out among them), so that the answer never claims what a crash could lose.
async fn logged(state: &AppState) -> Result<(), AppError> {
    let hub = &state.hub;
    (hub.logged(hub.published_seq()).await)
        .map_err(|failure| AppError::log_unwritable(failure.after_the_fact()))
}

/// `GET /api/context`: the current context and the ones available.
pub async fn get_context(State(state): State<AppState>) -> Json<Value> {
    let bundle = state.dispatcher.bundle();
    Json(json!({ "context": state.dispatcher.context(), "available": bundle.contexts }))
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ContextBody {
    context: String,
}

/// `PUT /api/context` with `{"context": "TextGroup"}` (credential needed).
pub async fn put_context(
    State(state): State<AppState>,
    _: Authorized,
    body: RequestBody,
) -> Result<Json<Value>, AppError> {
    let example = r#"{"context": "TextGroup"}"#;
    let body: ContextBody = body
        .object(example)?
        .ok_or_else(|| AppError::bad_request(format!("expected a body, e.g. {example}")))?;
    state.dispatcher.set_context(&body.context, Source::Http)?;
    logged(&state).await?;
    Ok(get_context(State(state)).await)
}

/// `GET /api/state` (credential needed: it names clients and holds the dialog manager's
/// reasons): display, pose, speech, adapter queues, channels, context, connected clients,
/// pending proposals, the visitor session and the server's limits in force.
pub async fn get_state(State(state): State<AppState>, _: Authorized) -> Json<Value> {
    let adapters = state.dispatcher.adapter_status();
    let speaking = (adapters.get(state.devices.speech_adapter))
        .and_then(|s| s.current.as_ref()?.spoken().map(str::to_owned));
    let bundle = state.dispatcher.bundle();
    // What the touchscreen should show by the schedule, by this machine's clock.
    let scheduled = bundle.config.showing_at(&WallClock::now());
    Json(json!({
        "display": state.devices.display.snapshot(),
        "schedule": scheduled,
        "pose": (state.devices.drive.as_ref().map(|d| d.pose()))
            .or_else(|| state.devices.rosbridge.as_ref().and_then(|r| r.pose())),
        "waypoint": (state.devices.drive.as_ref().and_then(|d| d.waypoint()))
            .or_else(|| state.devices.rosbridge.as_ref().and_then(|r| r.waypoint())),
        "robot_link": state.devices.rosbridge.as_ref().map(|r| r.link_status()),
        "speaking": speaking,
        "queues": adapters,
        "channels": state.dispatcher.channel_status(),
        "context": state.dispatcher.context(),
        "language": state.dispatcher.language(),
        "languages": state.dispatcher.bundle().config.languages.all(),
        "clients": state.clients(),
        "proposals": state.proposals.pending(),
        "session": state.visits.current(),
        "consent": state.visits.consent(),
        "recording": state.recordings.view(),
        "fleet": state.fleet.state_json(),
        "limits": LimitsView::new(&state.limits.server, state.limits.open_files),
        // While the corpus log cannot be written: what the operator is told.
        "corpus": state.hub.logged_progress().borrow().alert.as_deref(),
    }))
}

/// Whole days after the asked-for one that a kiosk's timetable covers: a week and a day, so a
/// kiosk that cannot ask again for a while still keeps to the hours.
const TIMETABLE_DAYS: u16 = 8;

/// `GET /api/schedule/{at}` (`at`: the kiosk's wall-clock time, `YYYY-MM-DDTHH:MM`): what the
/// touchscreen shows then by the bundle's opening hours, and every change after it for
/// [`TIMETABLE_DAYS`] days. The kiosk applies them by its own clock; it never evaluates the
/// schedule itself.
pub async fn get_schedule(
    State(state): State<AppState>,
    at: Result<Path<String>, PathRejection>,
) -> Result<impl IntoResponse, AppError> {
    let example = "/api/schedule/2025-12-01T08:59";
    let at = at.ok().and_then(|Path(at)| WallClock::parse(&at));
    let Some(at) = at else {
        return Err(AppError::bad_request(format!(
            "expected the kiosk's local time as YYYY-MM-DDTHH:MM, e.g. {example}"
        )));
    };
    let bundle = state.dispatcher.bundle();
    Ok(Json(json!(bundle.config.timetable(&at, TIMETABLE_DAYS))))
}

/// `GET /favicon.ico`: browsers ask every top-level page's server for one; there is none, and
/// saying so with 204 keeps a 404 out of the kiosk's console.
pub async fn no_favicon() -> StatusCode {
    StatusCode::NO_CONTENT
}

/// A known route with the wrong method: a JSON 405.
pub async fn method_not_allowed() -> AppError {
    AppError::new(
        StatusCode::METHOD_NOT_ALLOWED,
        ErrorCode::MethodNotAllowed,
        "this route does not take that method; see docs/PROTOCOL.md",
    )
}

/// Anything else: a JSON 404.
pub async fn not_found() -> AppError {
    AppError::not_found("no such route; see docs/PROTOCOL.md")
}
