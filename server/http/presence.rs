//! `GET /healthz?role=ROLE&name=NAME`: whether a websocket client of that role (and name) is
//! connected, for a kiosk PC's watchdog (`kiosk/watchdog.sh --alive`): a touchscreen whose tab
//! crashed keeps its browser process, so only Docent can tell that its page is gone. `200`
//! while one is connected; `503` while none is, with how long none has been on the monotonic
//! clock (a wall clock moved by NTP would make it lie). Like `/healthz`, it needs no
//! credential and says nothing but whether such a client is connected.

use std::collections::HashMap;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use axum::Json;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use serde::Serialize;

use crate::events::ClientRole;
use crate::http::AppError;
use crate::state::AppState;
use crate::sync::lock;

/// The longest name asked about, in characters (the kiosk page takes at most 40).
const MAX_NAME_CHARS: usize = 64;
/// Names whose last leaving is remembered; beyond them the oldest is forgotten, so that
/// clients making up names cannot grow the server's memory.
const REMEMBERED: usize = 1024;

/// When the last client of each role and name left, on the monotonic clock.
#[derive(Debug)]
pub struct Absences {
    /// When the server started: "none since" for a client never seen leave.
    started: Instant,
    left: Mutex<HashMap<(ClientRole, Option<String>), Instant>>,
}

impl Default for Absences {
    fn default() -> Self {
        Absences {
            started: Instant::now(),
            left: Mutex::default(),
        }
    }
}

impl Absences {
    /// A client of `role` named `name` left at `at`.
    pub fn left(&self, role: ClientRole, name: Option<&str>, at: Instant) {
        let mut left = lock(&self.left);
        let key = (role, name.map(str::to_owned));
        if left.len() >= REMEMBERED
            && !left.contains_key(&key)
            && let Some(oldest) = (left.iter())
                .min_by_key(|(_, at)| **at)
                .map(|(k, _)| k.clone())
        {
            left.remove(&oldest);
        }
        left.insert(key, at);
    }

    /// Since when no client of `role` (named `name`, if given) is connected, as far as
    /// remembered: its last leaving, else the server's start.
    fn since(&self, role: ClientRole, name: Option<&str>) -> (Instant, Since) {
        let left = lock(&self.left);
        let last = (left.iter())
            .filter(|((r, n), _)| *r == role && name.is_none_or(|name| n.as_deref() == Some(name)))
            .map(|(_, at)| *at)
            .max();
        match last {
            Some(at) => (at, Since::Left),
            None => (self.started, Since::Start),
        }
    }
}

/// What "none since" counts from.
#[derive(Clone, Copy, Debug, Serialize)]
#[serde(rename_all = "lowercase")]
enum Since {
    /// The last such client left.
    Left,
    /// The server started, and no such client left since (as far as remembered).
    Start,
}

/// The question: a role, and a name if any.
#[derive(Debug, PartialEq, Eq)]
pub struct Asked {
    role: ClientRole,
    name: Option<String>,
}

/// Reads `role=ROLE&name=NAME` (name optional); anything else is a client error that says
/// what to send.
pub fn asked(pairs: Vec<(String, String)>) -> Result<Asked, AppError> {
    let mut role = None;
    let mut name = None;
    for (key, value) in pairs {
        let slot = match key.as_str() {
            "role" => &mut role,
            "name" => &mut name,
            other => {
                return Err(bad(format!(
                    "unknown parameter `{other}`; /healthz takes `role` and `name` only"
                )));
            }
        };
        if slot.replace(value).is_some() {
            return Err(bad(format!("`{key}` is given twice")));
        }
    }
    let role = role.ok_or_else(|| bad("`role` is missing".into()))?;
    let role = serde_json::from_value(serde_json::Value::String(role.clone())).map_err(|_| {
        bad(format!(
            "`role` is `{role}`; it is one of kiosk, projector, operator, dm, adapter"
        ))
    })?;
    if let Some(name) = &name {
        let chars = name.chars().count();
        if chars == 0 || chars > MAX_NAME_CHARS || name.chars().any(char::is_control) {
            return Err(bad(format!(
                "`name` must be 1 to {MAX_NAME_CHARS} printable characters"
            )));
        }
    }
    Ok(Asked { role, name })
}

fn bad(message: String) -> AppError {
    AppError::bad_request(format!("{message} (GET /healthz?role=kiosk&name=NAME)"))
}

#[derive(Serialize)]
struct Presence<'a> {
    role: ClientRole,
    #[serde(skip_serializing_if = "Option::is_none")]
    name: Option<&'a str>,
    /// How many such clients are connected.
    connected: usize,
    /// Their connection ids.
    clients: Vec<u64>,
    /// While none is: for how long, in milliseconds of the monotonic clock.
    #[serde(skip_serializing_if = "Option::is_none")]
    none_for_ms: Option<u64>,
    /// While none is: what that counts from.
    #[serde(skip_serializing_if = "Option::is_none")]
    since: Option<Since>,
}

/// The answer to `asked`: `200` with the connected clients, or `503` with since when none is.
pub fn presence(state: &AppState, asked: &Asked) -> Response {
    let name = asked.name.as_deref();
    let clients: Vec<u64> = (state.clients().into_iter())
        .filter(|(_, c)| c.role == asked.role && name.is_none_or(|n| c.name.as_deref() == Some(n)))
        .map(|(id, _)| id)
        .collect();
    let mut answer = Presence {
        role: asked.role,
        name,
        connected: clients.len(),
        clients,
        none_for_ms: None,
        since: None,
    };
    if answer.connected > 0 {
        return (StatusCode::OK, Json(answer)).into_response();
    }
    let (at, since) = state.absences().since(asked.role, name);
    let gone: Duration = Instant::now().saturating_duration_since(at);
    answer.none_for_ms = Some(u64::try_from(gone.as_millis()).unwrap_or(u64::MAX));
    answer.since = Some(since);
    (StatusCode::SERVICE_UNAVAILABLE, Json(answer)).into_response()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pairs(list: &[(&str, &str)]) -> Vec<(String, String)> {
        (list.iter())
            .map(|(k, v)| ((*k).to_owned(), (*v).to_owned()))
            .collect()
    }

    #[test]
    fn a_role_and_a_name_are_read_and_anything_else_is_refused() {
        let read = asked(pairs(&[("role", "kiosk"), ("name", "entrance")])).unwrap();
        assert_eq!(
            read,
            Asked {
                role: ClientRole::Kiosk,
                name: Some("entrance".into())
            }
        );
        assert!(asked(pairs(&[("role", "projector")])).is_ok());
        let long = "x".repeat(65);
        for bad in [
            pairs(&[]),
            pairs(&[("name", "x")]),
            pairs(&[("role", "robot")]),
            pairs(&[("role", "kiosk"), ("role", "kiosk")]),
            pairs(&[("role", "kiosk"), ("colour", "red")]),
            pairs(&[("role", "kiosk"), ("name", "")]),
            pairs(&[("role", "kiosk"), ("name", "a\nb")]),
            pairs(&[("role", "kiosk"), ("name", long.as_str())]),
        ] {
            assert!(asked(bad.clone()).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn none_since_is_the_last_leaving_else_the_start_and_old_names_are_forgotten() {
        let absences = Absences::default();
        let kiosk = ClientRole::Kiosk;
        assert!(matches!(absences.since(kiosk, Some("a")).1, Since::Start));
        let at = absences.started + Duration::from_secs(5);
        absences.left(kiosk, Some("a"), at);
        let (since, from) = absences.since(kiosk, Some("a"));
        assert_eq!(since, at);
        assert!(matches!(from, Since::Left));
        assert_eq!(absences.since(kiosk, None).0, at);
        assert!(matches!(absences.since(kiosk, Some("b")).1, Since::Start));
        for n in 0..REMEMBERED {
            let later = at + Duration::from_secs(1 + n as u64);
            absences.left(kiosk, Some(&n.to_string()), later);
        }
        assert_eq!(lock(&absences.left).len(), REMEMBERED);
        assert!(matches!(absences.since(kiosk, Some("a")).1, Since::Start));
    }
}
