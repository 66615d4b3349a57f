//! Extractors for who is asking: [`Peer`] (the client's address) and [`Authorized`] (a valid
//! `Authorization: Bearer` credential, or an `--open` server), and [`same_origin`], which
//! keeps other web sites' pages in a visitor's or developer's browser from using the API.
//! Refusals are JSON errors with `WWW-Authenticate` or `Retry-After`; the credential itself
//! is never logged or echoed.

use std::convert::Infallible;
use std::net::{IpAddr, SocketAddr};

use axum::extract::{ConnectInfo, FromRequestParts};
use axum::http::request::Parts;
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};

use crate::access::{Needed, Refusal, is_loopback, whole_seconds};
use crate::http::AppError;
use crate::state::AppState;

/// The client's address, when the server was started with connection info (tests calling
/// the router directly have none). Behind a reverse proxy on this machine the connection
/// comes from loopback: then the address the proxy names last in `X-Forwarded-For` is the
/// client's, so a remote client never passes for a local one.
pub struct Peer(pub Option<IpAddr>);

impl<S: Send + Sync> FromRequestParts<S> for Peer {
    type Rejection = Infallible;

    async fn from_request_parts(parts: &mut Parts, _: &S) -> Result<Self, Infallible> {
        let direct = parts
            .extensions
            .get::<ConnectInfo<SocketAddr>>()
            .map(|ConnectInfo(addr)| addr.ip());
        Ok(Peer(client_address(direct, &parts.headers)))
    }
}

/// The client's address: the direct peer, or, when that is a proxy on loopback, the last
/// `X-Forwarded-For` entry (an unreadable one counts as an unknown remote address).
fn client_address(direct: Option<IpAddr>, headers: &HeaderMap) -> Option<IpAddr> {
    // `is_loopback` also knows `::ffff:127.0.0.1`, how a proxy's connection to 127.0.0.1
    // arrives on a server listening on `[::]`.
    let proxied = is_loopback(direct);
    let Some(forwarded) = headers.get("x-forwarded-for").filter(|_| proxied) else {
        return direct;
    };
    let last = forwarded.to_str().ok().and_then(|v| v.rsplit(',').next());
    let parsed = last.and_then(|v| v.trim().parse::<IpAddr>().ok());
    Some(parsed.unwrap_or(IpAddr::V4(std::net::Ipv4Addr::UNSPECIFIED)))
}

/// Proof that the request carries the operator's or dialog manager's credential.
pub struct Authorized;

impl FromRequestParts<AppState> for Authorized {
    type Rejection = AppError;

    async fn from_request_parts(parts: &mut Parts, state: &AppState) -> Result<Self, AppError> {
        same_origin(&parts.headers)?;
        let Ok(Peer(peer)) = Peer::from_request_parts(parts, state).await;
        let token = bearer(&parts.headers);
        match state.access.check(peer, Needed::Either, token) {
            Ok(()) => Ok(Authorized),
            Err(refusal) => Err(refusal_error(refusal, Needed::Either)),
        }
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
            "cross-origin",
            "requests from pages of another site are refused",
        )),
    }
}

/// The token of an `Authorization: Bearer ...` header, if there is one.
fn bearer(headers: &HeaderMap) -> Option<&str> {
    let value = headers.get(header::AUTHORIZATION)?.to_str().ok()?;
    let (scheme, token) = value.split_once(' ')?;
    scheme.eq_ignore_ascii_case("bearer").then(|| token.trim())
}

/// 401 with `WWW-Authenticate: Bearer`, or 429 with `Retry-After`.
fn refusal_error(refusal: Refusal, needed: Needed) -> AppError {
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
    fn a_proxy_on_loopback_names_the_client_in_x_forwarded_for() {
        let local: Option<IpAddr> = Some("127.0.0.1".parse().unwrap());
        let remote: Option<IpAddr> = Some("192.168.1.5".parse().unwrap());
        let mut headers = HeaderMap::new();
        assert_eq!(client_address(local, &headers), local);
        headers.insert(
            "x-forwarded-for",
            HeaderValue::from_static("10.0.0.1, 192.168.1.5"),
        );
        assert_eq!(client_address(local, &headers), remote);
        // Only a proxy on this machine is believed.
        let mapped = Some("::ffff:127.0.0.1".parse().unwrap());
        assert_eq!(client_address(mapped, &headers), remote);
        let stranger = Some("192.168.1.9".parse().unwrap());
        assert_eq!(client_address(stranger, &headers), stranger);
        headers.insert("x-forwarded-for", HeaderValue::from_static("garbage"));
        let unknown = client_address(local, &headers).unwrap();
        assert!(!unknown.is_loopback());
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
