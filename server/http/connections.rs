//! Accepting connections with limits, so that slow or numerous clients cannot starve the
//! others (slowloris): a request's headers must be complete within
//! [`ConnectionLimits::header_timeout`] (also the most an idle keep-alive connection waits for
//! its next request), its body within [`ConnectionLimits::body_timeout`]; one address may hold
//! at most [`ConnectionLimits::per_address`] connections and the server
//! [`ConnectionLimits::total`]. A connection over a limit is answered `503
//! too-many-connections` and closed at once. A websocket keeps its connection's place for as
//! long as it is open ([`ConnectionSlot`]). Trusted proxies are held only to the total.
//!
//! axum's own `serve` offers none of these, so this is its accept loop with hyper's HTTP/1
//! server configured, and requests with both `Content-Length` and `Transfer-Encoding` refused
//! (`framing`).

use std::collections::HashMap;
use std::convert::Infallible;
use std::future::Future;
use std::io;
use std::net::{IpAddr, SocketAddr};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use axum::Router;
use axum::extract::ConnectInfo;
use axum::response::IntoResponse;
use hyper::body::Incoming;
use hyper_util::rt::{TokioIo, TokioTimer};
use hyper_util::service::TowerToHyperService;
use tokio::io::AsyncWriteExt;
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::{OwnedSemaphorePermit, Semaphore};
use tokio_util::sync::CancellationToken;
use tokio_util::task::TaskTracker;
use tower::ServiceExt;

use crate::access::{RefusalLog, TrustedProxies, counted_as};
use crate::content::config::ServerLimits;
use crate::http::AppError;
use crate::http::framing::{Ambiguous, Sniffed};
use crate::sync::lock;
use crate::wire::ErrorCode;

/// How long a connection may still take to finish its request once the server shuts down.
const SHUTDOWN_GRACE: Duration = Duration::from_secs(3);

/// How long slow clients may take, and how many connections there may be: `docent.yaml`'s
/// `server:` limits ([`ServerLimits`]), whose defaults are these.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ConnectionLimits {
    /// A request's headers must have arrived within this long of its first byte being
    /// awaited (an idle keep-alive connection is closed after it too).
    pub header_timeout: Duration,
    /// A request's body must have arrived within this long of its headers (`408`).
    pub body_timeout: Duration,
    /// Open connections (websockets included) from one client address.
    pub per_address: usize,
    /// Open connections in all.
    pub total: usize,
}

impl From<&ServerLimits> for ConnectionLimits {
    fn from(limits: &ServerLimits) -> Self {
        ConnectionLimits {
            header_timeout: limits.header_timeout,
            body_timeout: limits.body_timeout,
            per_address: limits.per_address,
            total: limits.total,
        }
    }
}

impl Default for ConnectionLimits {
    /// What a `docent.yaml` that says nothing about them gets.
    fn default() -> Self {
        ConnectionLimits::from(&ServerLimits::default())
    }
}

/// Why a connection found no place.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Refusal {
    /// The server holds `total` connections.
    Total,
    /// The client's address holds `per_address` connections.
    PerAddress,
}

impl Refusal {
    /// What the client is told.
    fn why(self) -> &'static str {
        match self {
            Refusal::Total => "the server has as many connections open as it takes",
            Refusal::PerAddress => "this address has as many connections open as one address may",
        }
    }

    /// The setting that raises the limit, as the log names it for the technician.
    fn setting(self) -> &'static str {
        match self {
            Refusal::Total => "server: connections: total",
            Refusal::PerAddress => "server: connections: per_address",
        }
    }
}

/// A connection's place among the open ones, given up when the last holder drops it (the
/// connection, and the websocket that took it over).
#[derive(Clone, Debug)]
pub struct ConnectionSlot {
    _guard: Arc<SlotGuard>,
}

/// Counts one connection against its address and the total while it lives.
#[derive(Debug)]
struct SlotGuard {
    counts: Arc<Mutex<HashMap<IpAddr, usize>>>,
    address: Option<IpAddr>,
    _total: OwnedSemaphorePermit,
}

impl Drop for SlotGuard {
    fn drop(&mut self) {
        let Some(address) = self.address else { return };
        let mut counts = lock(&self.counts);
        if let Some(count) = counts.get_mut(&address) {
            *count -= 1;
            if *count == 0 {
                counts.remove(&address);
            }
        }
    }
}

/// The places left, per address and in all.
struct Slots {
    limits: ConnectionLimits,
    proxies: TrustedProxies,
    total: Arc<Semaphore>,
    counts: Arc<Mutex<HashMap<IpAddr, usize>>>,
}

impl Slots {
    /// A place for a connection from `peer`, or why there is none.
    fn take(&self, peer: IpAddr) -> Result<ConnectionSlot, Refusal> {
        let total = (Arc::clone(&self.total).try_acquire_owned()).map_err(|_| Refusal::Total)?;
        let address = (!self.proxies.contains(peer)).then(|| counted_as(peer));
        if let Some(address) = address {
            let mut counts = lock(&self.counts);
            let count = counts.entry(address).or_default();
            if *count >= self.limits.per_address {
                return Err(Refusal::PerAddress);
            }
            *count += 1;
        }
        let guard = SlotGuard {
            counts: Arc::clone(&self.counts),
            address,
            _total: total,
        };
        Ok(ConnectionSlot {
            _guard: Arc::new(guard),
        })
    }
}

/// Serves `router` on `listener` within `limits` until `shutdown` completes, then lets every
/// connection finish its request in progress (within a grace of 3 s) and returns.
pub async fn serve_connections(
    listener: TcpListener,
    router: Router,
    limits: ConnectionLimits,
    proxies: TrustedProxies,
    shutdown: impl Future<Output = ()> + Send + 'static,
) {
    let slots = Slots {
        limits,
        proxies,
        total: Arc::new(Semaphore::new(limits.total)),
        counts: Arc::default(),
    };
    let refusals = Arc::new(RefusalLog::default());
    let closing = CancellationToken::new();
    let connections = TaskTracker::new();
    tokio::pin!(shutdown);
    loop {
        let (tcp, remote) = tokio::select! {
            () = &mut shutdown => break,
            accepted = listener.accept() => match accepted {
                Ok(accepted) => accepted,
                Err(e) => {
                    accept_failed(e).await;
                    continue;
                }
            },
        };
        // Commands are small frames that must go out at once.
        let _ = tcp.set_nodelay(true);
        match slots.take(remote.ip()) {
            Ok(slot) => {
                let closing = closing.clone();
                connections.spawn(serve_one(
                    tcp,
                    remote,
                    router.clone(),
                    limits,
                    slot,
                    closing,
                ));
            }
            Err(refusal) => {
                if let Some(unlogged) = refusals.admit() {
                    let (why, setting) = (refusal.why(), refusal.setting());
                    tracing::warn!(
                        address = %remote.ip(),
                        unlogged,
                        "connection refused: {why} ({setting} in docent.yaml raises it)"
                    );
                }
                connections.spawn(refuse(tcp, refusal.why()));
            }
        }
    }
    closing.cancel();
    connections.close();
    connections.wait().await;
}

/// Errors from `accept` that concern one client only; others (out of file descriptors) are
/// logged and waited out, as axum's `serve` does.
async fn accept_failed(e: io::Error) {
    use io::ErrorKind::{ConnectionAborted, ConnectionRefused, ConnectionReset};
    if matches!(
        e.kind(),
        ConnectionRefused | ConnectionAborted | ConnectionReset
    ) {
        return;
    }
    tracing::error!("cannot accept connections: {e}; trying again in 1 s");
    tokio::time::sleep(Duration::from_secs(1)).await;
}

/// Serves one HTTP/1 connection within `limits`, its requests knowing their client's
/// address and slot; once `closing` is cancelled it finishes the request in progress and
/// closes.
async fn serve_one(
    tcp: TcpStream,
    remote: SocketAddr,
    router: Router,
    limits: ConnectionLimits,
    slot: ConnectionSlot,
    closing: CancellationToken,
) {
    let ambiguous = Ambiguous::default();
    let requests = Arc::new(AtomicU64::new(0));
    let watched = ambiguous.clone();
    let service = tower::service_fn(move |mut request: hyper::Request<Incoming>| {
        let number = requests.fetch_add(1, Ordering::Relaxed) + 1;
        let refused = watched.is(number);
        request.extensions_mut().insert(ConnectInfo(remote));
        request.extensions_mut().insert(slot.clone());
        request.extensions_mut().insert(limits);
        let router = router.clone();
        async move {
            if refused {
                return Ok::<_, Infallible>(conflicting_length().into_response());
            }
            router.oneshot(request.map(axum::body::Body::new)).await
        }
    });
    let io = TokioIo::new(Sniffed::new(tcp, ambiguous));
    let connection = hyper::server::conn::http1::Builder::new()
        .timer(TokioTimer::new())
        .header_read_timeout(limits.header_timeout)
        .serve_connection(io, TowerToHyperService::new(service))
        .with_upgrades();
    tokio::pin!(connection);
    let finished = tokio::select! {
        result = connection.as_mut() => Some(result),
        () = closing.cancelled() => None,
    };
    let result = match finished {
        Some(result) => result,
        None => {
            connection.as_mut().graceful_shutdown();
            // A client in the middle of sending its headers counts as busy to hyper; it gets
            // no more than the grace, not the whole header time limit.
            match tokio::time::timeout(SHUTDOWN_GRACE, connection).await {
                Ok(result) => result,
                Err(_) => return,
            }
        }
    };
    if let Err(e) = result {
        tracing::debug!("connection ended: {e}");
    }
}

/// `400 conflicting-length`: see `framing`.
fn conflicting_length() -> AppError {
    AppError::bad_request_with_code(
        ErrorCode::ConflictingLength,
        "a request may not carry both Content-Length and Transfer-Encoding; send one",
    )
}

/// Answers a connection over a limit with `503` and closes it.
async fn refuse(mut tcp: TcpStream, why: &str) {
    let body = serde_json::json!({
        "code": ErrorCode::TooManyConnections,
        "error": format!("{why}; try again later"),
    })
    .to_string();
    let response = format!(
        "HTTP/1.1 503 Service Unavailable\r\ncontent-type: application/json\r\n\
         retry-after: 1\r\nconnection: close\r\ncontent-length: {}\r\n\r\n{body}",
        body.len()
    );
    // A client that does not read cannot hold the place it was refused.
    let write = async {
        tcp.write_all(response.as_bytes()).await?;
        tcp.shutdown().await
    };
    let _ = tokio::time::timeout(Duration::from_secs(1), write).await;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn places_are_counted_per_address_and_in_all_and_given_back() {
        let limits = ConnectionLimits {
            per_address: 2,
            total: 3,
            ..ConnectionLimits::default()
        };
        let proxy: IpAddr = "10.0.0.2".parse().unwrap();
        let slots = Slots {
            limits,
            proxies: TrustedProxies::new(vec![proxy]),
            total: Arc::new(Semaphore::new(limits.total)),
            counts: Arc::default(),
        };
        let a: IpAddr = "192.0.2.1".parse().unwrap();
        let first = slots.take(a).unwrap();
        let _second = slots.take(a).unwrap();
        assert_eq!(slots.take(a).unwrap_err(), Refusal::PerAddress);
        drop(first);
        let third = slots.take(a).unwrap();
        let b: IpAddr = "192.0.2.2".parse().unwrap();
        let _fourth = slots.take(b).unwrap();
        // The total is full now; a trusted proxy is held to it too.
        assert_eq!(slots.take(proxy).unwrap_err(), Refusal::Total);
        drop(third);
        let _proxied = [slots.take(proxy).unwrap()];
        assert_eq!(lock(&slots.counts).get(&proxy), None);
    }

    #[test]
    fn an_ipv6_network_counts_as_one_address() {
        let limits = ConnectionLimits {
            per_address: 2,
            ..ConnectionLimits::default()
        };
        let slots = Slots {
            limits,
            proxies: TrustedProxies::default(),
            total: Arc::new(Semaphore::new(limits.total)),
            counts: Arc::default(),
        };
        let held: Vec<_> = ["2001:db8:1:2::1", "2001:db8:1:2::2"]
            .iter()
            .map(|a| slots.take(a.parse().unwrap()).unwrap())
            .collect();
        assert!(slots.take("2001:db8:1:2:ffff::9".parse().unwrap()).is_err());
        assert!(slots.take("2001:db8:1:3::1".parse().unwrap()).is_ok());
        drop(held);
    }

    #[test]
    fn the_documented_defaults() {
        let limits = ConnectionLimits::default();
        assert_eq!(limits.header_timeout, Duration::from_secs(30));
        assert_eq!(limits.body_timeout, Duration::from_secs(30));
        assert_eq!((limits.per_address, limits.total), (128, 1024));
    }
}
