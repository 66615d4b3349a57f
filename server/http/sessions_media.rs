//! A recorded session's media for the `/sessions` page. An `<audio>` or `<video>` element
//! cannot send the operator's Bearer header, and the credential must never be put in a URL;
//! fetching a whole recording into a blob would hold an hour of video in the page's memory
//! and lose seeking while it loads. So the page asks, with its credential, for a **media
//! ticket** (`POST /api/sessions/{name}/media-ticket`): a random 128-bit name, good for one
//! session's media only, that expires [`TICKET_IDLE`] after its last use (and at the latest
//! [`TICKET_MAX`] after it was given), and is forgotten when the server stops. The media are
//! then served at `/session-media/{ticket}/media/...` with HTTP range requests (tower-http's
//! `ServeFile`), so a player seeks without downloading what it skips.
//!
//! Only the files the session's manifest lists in `media` are served, and only when each part
//! of their path is a plain name inside the session's `media/` folder, none of them a link.

use std::collections::HashMap;
use std::path::{Component, Path, PathBuf};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use axum::extract::{Path as UrlPath, Request, State};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use serde::Serialize;
use serde_json::{Value, json};
use tower::ServiceExt;
use tower_http::services::ServeFile;

use crate::corpus::layout::SESSION_MANIFEST;
use crate::corpus::manifest::media_allowed;
use crate::http::AppError;
use crate::http::auth::Authorized;
use crate::http::session_name::{SessionName, session_dir};
use crate::state::AppState;
use crate::sync::lock;
use crate::wire::ErrorCode;

/// A ticket lapses this long after it was last used.
pub const TICKET_IDLE: Duration = Duration::from_secs(30 * 60);
/// ... and this long after it was given, used or not.
pub const TICKET_MAX: Duration = Duration::from_secs(12 * 3600);
/// Tickets kept at most (the oldest are dropped first).
const MAX_TICKETS: usize = 256;

/// The corpus folder the `/sessions` page reads, and the media tickets given out.
pub struct Replay {
    /// The corpus folder (absolute).
    pub corpus: PathBuf,
    tickets: Mutex<HashMap<String, Ticket>>,
}

struct Ticket {
    session: String,
    given: Instant,
    used: Instant,
}

impl Replay {
    /// For the corpus folder `corpus`, with no tickets yet.
    pub fn new(corpus: PathBuf) -> Replay {
        let tickets = Mutex::default();
        Replay { corpus, tickets }
    }

    /// A new ticket for `session`'s media.
    fn give(&self, session: &str) -> String {
        let ticket = format!("{:032x}", rand::random::<u128>());
        let now = Instant::now();
        let mut tickets = lock(&self.tickets);
        tickets.retain(|_, t| alive(t, now));
        if tickets.len() >= MAX_TICKETS
            && let Some(oldest) =
                (tickets.iter().min_by_key(|(_, t)| t.given)).map(|(name, _)| name.clone())
        {
            tickets.remove(&oldest);
        }
        let session = session.to_owned();
        let entry = Ticket {
            session,
            given: now,
            used: now,
        };
        tickets.insert(ticket.clone(), entry);
        ticket
    }

    /// The session `ticket` is good for, now; its use keeps it alive.
    fn redeem(&self, ticket: &str) -> Option<String> {
        let now = Instant::now();
        let mut tickets = lock(&self.tickets);
        let entry = tickets.get_mut(ticket).filter(|t| alive(t, now))?;
        entry.used = now;
        Some(entry.session.clone())
    }
}

fn alive(ticket: &Ticket, now: Instant) -> bool {
    now.duration_since(ticket.used) < TICKET_IDLE && now.duration_since(ticket.given) < TICKET_MAX
}

/// A recording the manifest lists (`session.json`'s `media`, written by the recorder).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MediaFile {
    /// Its path in the session folder: `media/audio-1.webm`.
    pub file: String,
    /// `audio` or `video`.
    pub track: String,
    /// Its MIME type, when given.
    pub mime: Option<String>,
    /// Where its first sample lies on the session clock (µs).
    pub start_us: u64,
}

/// The media the manifest in `dir` lists, read tolerantly (no list, or a manifest without
/// one, is no media); an entry whose path is not a plain one inside `media/` is left out, and
/// a session whose visitors declined or withdrew consent has none, whatever files are left.
pub fn media_list(dir: &Path) -> Vec<MediaFile> {
    let Ok(text) = std::fs::read(dir.join(SESSION_MANIFEST)) else {
        return Vec::new();
    };
    let manifest: Value = serde_json::from_slice(&text).unwrap_or(Value::Null);
    if !media_allowed(manifest["consent"].as_str().unwrap_or_default()) {
        return Vec::new();
    }
    let Some(entries) = manifest["media"].as_array() else {
        return Vec::new();
    };
    (entries.iter())
        .filter_map(|m| {
            let file = m["file"].as_str()?;
            plain_media_path(file)?;
            Some(MediaFile {
                file: file.to_owned(),
                track: m["track"].as_str().unwrap_or("audio").to_owned(),
                mime: m["mime"].as_str().map(str::to_owned),
                start_us: m["start_us"].as_u64().unwrap_or(0),
            })
        })
        .collect()
}

/// `media/NAME...` made only of plain names: its parts.
fn plain_media_path(file: &str) -> Option<Vec<&str>> {
    let mut parts = Vec::new();
    for part in Path::new(file).components() {
        match part {
            Component::Normal(name) => parts.push(name.to_str()?),
            _ => return None,
        }
    }
    (parts.len() >= 2 && parts[0] == "media").then_some(parts)
}

/// `POST /api/sessions/{name}/media-ticket` (bearer): a ticket for the session's media, and
/// where they are served with it.
pub async fn media_ticket(
    _: Authorized,
    State(state): State<AppState>,
    SessionName(name): SessionName,
) -> Result<Response, AppError> {
    let corpus = state.replay.corpus.clone();
    let (name, _) = session_dir(&corpus, &name)?;
    let ticket = state.replay.give(&name);
    let body = json!({
        "ticket": ticket,
        "base": format!("/session-media/{ticket}/"),
        "idle_s": TICKET_IDLE.as_secs(),
    });
    Ok((StatusCode::CREATED, axum::Json(body)).into_response())
}

/// `GET /session-media/{ticket}/{*file}`: one of the ticket's session's media files, with
/// range requests. No credential: the ticket is one.
pub async fn serve_media(
    State(state): State<AppState>,
    UrlPath((ticket, file)): UrlPath<(String, String)>,
    request: Request,
) -> Result<Response, AppError> {
    let Some(session) = state.replay.redeem(&ticket) else {
        return Err(AppError::new(
            StatusCode::FORBIDDEN,
            ErrorCode::BadTicket,
            "this media ticket is unknown or has expired: reload the session to get a new one",
        ));
    };
    let not_found = || AppError::not_found(format!("the session has no media file {file}"));
    let (_, dir) = session_dir(&state.replay.corpus, &session)?;
    let listed = media_list(&dir).into_iter().any(|m| m.file == file);
    let parts = plain_media_path(&file)
        .filter(|_| listed)
        .ok_or_else(not_found)?;
    // Never through a link: each part must be what it says.
    let mut path = dir.clone();
    for (n, part) in parts.iter().enumerate() {
        path.push(part);
        let meta = std::fs::symlink_metadata(&path).map_err(|_| not_found())?;
        let last = n + 1 == parts.len();
        if meta.file_type().is_symlink() || (last && !meta.is_file()) || (!last && !meta.is_dir()) {
            return Err(not_found());
        }
    }
    match ServeFile::new(&path).oneshot(request).await {
        Ok(response) => Ok(response.into_response()),
        Err(e) => Err(AppError::internal(e)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_plain_paths_inside_media_are_listed() {
        assert_eq!(
            plain_media_path("media/audio-1.webm"),
            Some(vec!["media", "audio-1.webm"])
        );
        for bad in [
            "events.jsonl",
            "media",
            "media/../session.json",
            "/media/a",
            "./media/a",
        ] {
            assert_eq!(plain_media_path(bad), None, "{bad}");
        }
    }

    #[test]
    fn a_ticket_is_good_for_its_session_until_it_lapses() {
        let replay = Replay::new(PathBuf::from("corpus"));
        let ticket = replay.give("s1");
        assert_eq!(ticket.len(), 32);
        assert_eq!(replay.redeem(&ticket).as_deref(), Some("s1"));
        assert_eq!(replay.redeem("0123"), None);
        let tickets = lock(&replay.tickets);
        let entry = tickets.get(&ticket).unwrap();
        assert!(alive(entry, entry.used + TICKET_IDLE / 2));
        assert!(!alive(entry, entry.used + TICKET_IDLE), "idle too long");
        assert!(!alive(entry, entry.given + TICKET_MAX), "too old");
    }
}
