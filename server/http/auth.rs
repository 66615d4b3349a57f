//! Extractors for who is asking: [`Peer`] (the client's address) and [`Authorized`] (a valid
//! `Authorization: Bearer` credential, or an `--open` server), and [`same_origin`], which
//! keeps other web sites' pages in a visitor's or developer's browser from using the API.
//! Refusals are JSON errors with `WWW-Authenticate` or `Retry-After`, logged (as
//! `request.refused`, within a shared allowance); the credential itself is never logged or
//! echoed.

use std::convert::Infallible;
use std::net::{IpAddr, SocketAddr};

use axum::extract::{ConnectInfo, FromRequestParts};
use axum::http::request::Parts;
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};

use crate::access::{Access, ClientAddress, Needed, Refusal, whole_seconds};
use crate::events::{EventKind, Hub, RequestRefused};
use crate::http::AppError;
use crate::state::AppState;
use crate::wire::ErrorCode;

/// Who is asking: the connection's peer address (unknown for tests calling the router
/// directly), or the client a trusted reverse proxy names in `X-Forwarded-For` (see
/// [`crate::access::TrustedProxies`]). From any other peer the header cannot change the
/// address; it can only make a loopback client count as remote.
pub struct Peer(pub ClientAddress);

impl FromRequestParts<AppState> for Peer {
    type Rejection = Infallible;

    async fn from_request_parts(parts: &mut Parts, state: &AppState) -> Result<Self, Infallible> {
        let direct = parts
            .extensions
            .get::<ConnectInfo<SocketAddr>>()
            .map(|ConnectInfo(addr)| addr.ip());
        let forwarded: Vec<Option<&str>> = (parts.headers.get_all("x-forwarded-for").iter())
            .map(|v| v.to_str().ok())
            .collect();
        Ok(Peer(state.access.proxies().client(direct, &forwarded)))
    }
}

/// Proof that the request carries the operator's or dialog manager's credential.
pub struct Authorized;

impl FromRequestParts<AppState> for Authorized {
    type Rejection = AppError;

    async fn from_request_parts(parts: &mut Parts, state: &AppState) -> Result<Self, AppError> {
        same_origin(&parts.headers)?;
        let Ok(Peer(client)) = Peer::from_request_parts(parts, state).await;
        let token = bearer(&parts.headers);
        match state.access.check(client, Needed::Either, token) {
            Ok(()) => Ok(Authorized),
            Err(refusal) => {
                log_refusal((&state.access, Some(&state.hub)), parts, client.ip, refusal);
                Err(refusal_error(refusal, Needed::Either))
            }
        }
    }
}

/// The longest request path written into a `request.refused` event.
const MAX_LOGGED_PATH: usize = 256;

/// Writes a counted refusal to the server log and the corpus, within the shared allowance
/// (an address already waiting is not logged again; see [`crate::access::RefusalLog`]).
/// `hub` is the corpus's, when the server has one (`docent fleet` has none).
pub(crate) fn log_refusal(
    (access, hub): (&Access, Option<&Hub>),
    parts: &Parts,
    peer: Option<IpAddr>,
    refusal: Refusal,
) {
    if matches!(refusal, Refusal::Locked(_)) {
        return;
    }
    let Some(unlogged) = access.admit_refusal_log() else {
        return;
    };
    let mut path = parts.uri.path().to_owned();
    if path.len() > MAX_LOGGED_PATH {
        let cut = (0..=MAX_LOGGED_PATH)
            .rev()
            .find(|i| path.is_char_boundary(*i));
        path.truncate(cut.unwrap_or(0));
    }
    let address = peer.map(|p| p.to_string());
    let code = refusal.code();
    let method = parts.method.as_str().to_owned();
    tracing::warn!(
        method,
        path,
        address,
        code = code.as_str(),
        unlogged,
        "HTTP credential refused"
    );
    if let Some(hub) = hub {
        hub.publish(EventKind::RequestRefused(RequestRefused {
            method,
            path,
            code: code.into(),
            address,
            unlogged,
        }));
    }
}

/// Refuses a request a browser sent from a page of another site (its `Origin` names another
/// host than the request's `Host`). Clients that are not browsers send no `Origin` and pass.
/// Without this, any web page open in a browser next to an `--open` development server could
/// drive the robot.
pub fn same_origin(headers: &HeaderMap) -> Result<(), AppError> {
    let Some(origin) = headers.get(header::ORIGIN) else {
        return Ok(());
    };
    let host = headers.get(header::HOST).and_then(|h| h.to_str().ok());
    let origin_host = origin
        .to_str()
        .ok()
        .and_then(|o| o.split_once("://"))
        .map(|(_, rest)| rest.trim_end_matches('/'));
    match (origin_host, host) {
        (Some(o), Some(h)) if o.eq_ignore_ascii_case(h) => Ok(()),
        _ => Err(AppError::new(
            StatusCode::FORBIDDEN,
            ErrorCode::CrossOrigin,
            "requests from pages of another site are refused",
        )),
    }
}

/// The token of an `Authorization: Bearer ...` header, if there is one.
pub(crate) fn bearer(headers: &HeaderMap) -> Option<&str> {
    let value = headers.get(header::AUTHORIZATION)?.to_str().ok()?;
    let (scheme, token) = value.split_once(' ')?;
    scheme.eq_ignore_ascii_case("bearer").then(|| token.trim())
}

/// 401 with `WWW-Authenticate: Bearer`, or 429 with `Retry-After`.
pub(crate) fn refusal_error(refusal: Refusal, needed: Needed) -> AppError {
    let message = refusal.message(needed);
    match refusal {
        Refusal::TooManyAttempts(wait) | Refusal::Locked(wait) => {
            let seconds = HeaderValue::from(whole_seconds(wait));
            AppError::new(StatusCode::TOO_MANY_REQUESTS, refusal.code(), message)
                .with_header(header::RETRY_AFTER, seconds)
        }
        Refusal::Missing | Refusal::Wrong => {
            AppError::new(StatusCode::UNAUTHORIZED, refusal.code(), message).with_header(
                header::WWW_AUTHENTICATE,
                HeaderValue::from_static("Bearer realm=\"docent\""),
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_pages_of_this_server_may_send_requests_with_an_origin() {
        let mut headers = HeaderMap::new();
        assert!(
            same_origin(&headers).is_ok(),
            "no Origin: not a browser page"
        );
        headers.insert(header::HOST, HeaderValue::from_static("127.0.0.1:8080"));
        assert!(same_origin(&headers).is_ok());
        headers.insert(
            header::ORIGIN,
            HeaderValue::from_static("http://127.0.0.1:8080"),
        );
        assert!(same_origin(&headers).is_ok());
        for other in ["http://evil.example", "http://127.0.0.1:9999", "null"] {
            headers.insert(header::ORIGIN, HeaderValue::from_static(other));
            assert!(same_origin(&headers).is_err(), "{other}");
        }
    }

    #[test]
    fn bearer_tokens_are_read_from_the_authorization_header() {
        let mut headers = HeaderMap::new();
        assert_eq!(bearer(&headers), None);
        headers.insert(
            header::AUTHORIZATION,
            HeaderValue::from_static("Bearer abc123"),
        );
        assert_eq!(bearer(&headers), Some("abc123"));
        headers.insert(
            header::AUTHORIZATION,
            HeaderValue::from_static("bearer  abc123 "),
        );
        assert_eq!(bearer(&headers), Some("abc123"));
        headers.insert(
            header::AUTHORIZATION,
            HeaderValue::from_static("Basic YWJjOmRlZg=="),
        );
        assert_eq!(bearer(&headers), None);
    }
}
