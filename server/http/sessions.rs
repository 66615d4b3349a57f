//! The `/sessions` page, where researchers replay recorded visitor sessions and annotate them
//! (an askama shell; `static/sessions/main.js` signs in as the content report does and fills
//! it in), and its data, behind the operator's or dialog manager's credential
//! (`Authorization: Bearer`): `GET /api/sessions` (the corpus's sessions) and
//! `GET /api/sessions/{name}` (one session: manifest, media, its log read into a timeline on
//! the session clock by the exports' own reader, the codebook and the annotations). Changing
//! annotations: `sessions_annotate.rs`; media: `sessions_media.rs`. A session is named only
//! through `session_name.rs` (`corpus::catalog::find_session`), so no request reaches outside
//! `sessions/NAME`.

use askama::Template;
use axum::Json;
use axum::extract::State;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use serde_json::{Value, json};

use crate::content::{BundleArea, resolve_in_bundle};
use crate::corpus::annotations::read_annotations;
use crate::corpus::catalog::Catalog;
use crate::corpus::export::timeline::{Marked, Outcome, Timeline, Touched};
use crate::corpus::export::{ExportError, SessionExport};
use crate::corpus::layout::SESSION_MANIFEST;
use crate::http::AppError;
use crate::http::auth::Authorized;
use crate::http::session_name::{SessionName, session_dir};
use crate::http::sessions_media::media_list;
use crate::http::shells::html;
use crate::state::AppState;
use crate::wire::ErrorCode;

/// `pages/sessions/sessions.html`: the replay and annotation page's shell.
#[derive(Template)]
#[template(path = "sessions/sessions.html")]
pub struct SessionsPage<'a> {
    /// Where the page fetches the sessions, e.g. `/api/sessions`.
    pub api_path: &'a str,
    /// False on an `--open` development server: the page fetches without asking.
    pub needs_credential: bool,
}

/// `GET /sessions`: the shell. Open to anyone: it holds nothing until its reader signs in.
pub async fn sessions_page(State(state): State<AppState>) -> Response {
    let page = SessionsPage {
        api_path: "/api/sessions",
        needs_credential: !state.access.is_open(),
    };
    html(page.render())
}

/// Runs `work` off the async runtime (it reads files).
async fn blocking<T: Send + 'static>(
    work: impl FnOnce() -> Result<T, AppError> + Send + 'static,
) -> Result<T, AppError> {
    tokio::task::spawn_blocking(work)
        .await
        .unwrap_or_else(|e| Err(AppError::internal(e)))
}

/// `GET /api/sessions` (bearer): every session of the corpus, oldest first.
pub async fn list_sessions(_: Authorized, State(state): State<AppState>) -> Response {
    let corpus = state.replay.corpus.clone();
    let listed = blocking(move || {
        let catalog = Catalog::read(&corpus).map_err(AppError::internal)?;
        let sessions: Vec<Value> = (catalog.sessions.iter())
            .map(|s| {
                let annotations = read_annotations(&s.dir).map_or(0, |a| a.annotations.len());
                let manifest = s.manifest.as_ref();
                json!({
                    "name": s.name,
                    "state": s.state().word(),
                    "started": s.started(),
                    "length_us": s.last_session_us(),
                    "events": s.events(),
                    "annotations": annotations,
                    "media": media_list(&s.dir).len(),
                    "group": s.group(),
                    "consent": manifest.map(|m| m.consent.as_str()),
                })
            })
            .collect();
        Ok(json!({ "sessions": sessions }))
    });
    match listed.await {
        Ok(body) => Json(body).into_response(),
        Err(e) => e.into_response(),
    }
}

/// `GET /api/sessions/{name}` (bearer): the session as the page replays it.
pub async fn get_session(
    _: Authorized,
    State(state): State<AppState>,
    SessionName(name): SessionName,
) -> Result<Response, AppError> {
    let corpus = state.replay.corpus.clone();
    let bundle = state.dispatcher.bundle();
    let body = blocking(move || {
        let (name, dir) = session_dir(&corpus, &name)?;
        let session = SessionExport::open(&dir).map_err(|e| opened(&name, e))?;
        let annotated = read_annotations(&dir).map_err(AppError::internal)?;
        let manifest: Value = std::fs::read(dir.join(SESSION_MANIFEST))
            .ok()
            .and_then(|t| serde_json::from_slice(&t).ok())
            .unwrap_or(Value::Null);
        let page_shown = |page: &str| {
            (resolve_in_bundle(&bundle.root, BundleArea::Pages, page).is_ok())
                .then(|| format!("/pages/{page}"))
        };
        let problems: Vec<Value> = (annotated.problems.iter())
            .map(|(line, why)| json!({"line": line, "problem": why}))
            .collect();
        let warnings: Vec<String> = session.warnings().iter().map(|w| w.to_string()).collect();
        Ok(json!({
            "name": name,
            "manifest": manifest,
            "media": media_list(&dir),
            "timeline": timeline_view(session.timeline(), page_shown),
            "codebook": bundle.config.codebook,
            "annotations": annotated.annotations,
            "annotation_problems": problems,
            "warnings": warnings,
        }))
    });
    Ok(Json(body.await?).into_response())
}

/// What a session that cannot be opened answers.
fn opened(name: &str, e: ExportError) -> AppError {
    match e {
        ExportError::Recording(_) => AppError::new(
            StatusCode::CONFLICT,
            ErrorCode::SessionRecording,
            format!("session {name} is still being recorded: it can be replayed once it has ended"),
        ),
        ExportError::UnknownSession(_) | ExportError::NotASession(_) => AppError::new(
            StatusCode::NOT_FOUND,
            ErrorCode::UnknownSession,
            format!("there is no session {name} in the corpus"),
        ),
        ExportError::DamagedLog { .. } | ExportError::DamagedManifest { .. } => AppError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            ErrorCode::SessionDamaged,
            e.to_string(),
        ),
        ExportError::Read { .. } | ExportError::Write { .. } => AppError::internal(e),
    }
}

/// How a command ended, in a word (and its reason).
fn outcome(outcome: &Outcome) -> Value {
    match outcome {
        Outcome::Done => json!({"outcome": "done"}),
        Outcome::Failed(reason) => json!({"outcome": "failed", "reason": reason}),
        Outcome::Cancelled(reason) => json!({"outcome": "cancelled", "reason": reason}),
        Outcome::Open => json!({"outcome": "open"}),
    }
}

/// The timeline as JSON, every time in µs on the session clock; each page with the address
/// the live bundle still serves it at (`url`, null when it no longer has it).
fn timeline_view(t: &Timeline, page_url: impl Fn(&str) -> Option<String>) -> Value {
    let with = |mut item: Value, extra: Value| {
        if let (Some(item), Value::Object(extra)) = (item.as_object_mut(), extra) {
            item.extend(extra);
        }
        item
    };
    let utterances: Vec<Value> = (t.utterances.iter())
        .map(|u| {
            let item = json!({"start_us": u.start_us, "end_us": u.end_us, "text": u.text,
                "label": u.label, "source": u.source});
            with(item, outcome(&u.outcome))
        })
        .collect();
    let commands: Vec<Value> = (t.commands.iter())
        .map(|c| {
            let item = json!({"start_us": c.start_us, "end_us": c.end_us, "verb": c.verb,
                "arg": c.arg});
            with(item, outcome(&c.outcome))
        })
        .collect();
    let pages: Vec<Value> = (t.pages.iter())
        .map(|p| {
            json!({"start_us": p.start_us, "end_us": p.end_us, "page": p.page,
            "url": page_url(&p.page)})
        })
        .collect();
    let touches: Vec<Value> = (t.touches.iter())
        .map(|touch| {
            let (kind, value) = match &touch.what {
                Touched::Act { label } => ("act", label.clone()),
                Touched::Refused { label, code } => ("refused", format!("{label} ({code})")),
                Touched::Page { page } => ("page", page.clone()),
            };
            json!({"at_us": touch.at_us, "kind": kind, "value": value})
        })
        .collect();
    let marks: Vec<Value> = (t.marks.iter())
        .map(|m| {
            let (kind, value) = match &m.what {
                Marked::Situation(s) => ("situation", s),
                Marked::Group(g) => ("group", g),
                Marked::Note(text) => ("note", text),
            };
            json!({"at_us": m.at_us, "kind": kind, "value": value})
        })
        .collect();
    json!({
        "length_us": t.end_us,
        "ended": t.ended,
        "utterances": utterances,
        "commands": commands,
        "pages": pages,
        "touches": touches,
        "marks": marks,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sessions_page_carries_its_contract_and_no_session() {
        let page = SessionsPage {
            api_path: "/api/sessions",
            needs_credential: true,
        }
        .render()
        .expect("renders");
        assert!(page.starts_with("<!doctype html>"), "{page}");
        assert!(page.contains(r#"data-api="/api/sessions""#), "{page}");
        assert!(page.contains(r#"data-credential="required""#), "{page}");
        assert!(page.contains(r#"src="/static/sessions/main.js""#), "{page}");
        assert!(page.contains(r#"<dialog id="signin""#), "{page}");
        for id in [
            "session-list",
            "timeline",
            "playhead",
            "play",
            "speed",
            "now-page",
        ] {
            assert!(page.contains(&format!(r#"id="{id}""#)), "no #{id}");
        }
    }

    #[test]
    fn every_sessions_script_is_served_with_what_it_imports() {
        let (_, main) = crate::http::static_files::lookup("sessions/main.js").expect("main");
        let mut pending = vec![("sessions/main.js".to_owned(), main)];
        while let Some((name, text)) = pending.pop() {
            for line in text.lines().filter(|l| l.starts_with("import ")) {
                let module = line.split('"').nth(1).expect("a quoted module");
                let path = match module.strip_prefix("../") {
                    Some(rest) => rest.to_owned(),
                    None => format!("sessions/{}", module.trim_start_matches("./")),
                };
                let found = crate::http::static_files::lookup(&path);
                assert!(
                    found.is_some(),
                    "{module}, imported by {name}, is not served"
                );
                if path.starts_with("sessions/") {
                    pending.push((path, found.expect("found").1));
                }
            }
        }
        assert!(crate::http::static_files::lookup("sessions.css").is_some());
    }
}
