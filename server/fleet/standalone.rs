//! `docent fleet --mqtt URL`: a server of the fleet view alone (no bundle, no robot), e.g. on
//! the front desk's computer. It asks for the operator credential as `docent serve` does, and
//! shows that same credential to the robots when it stops one: a fleet shares one operator
//! credential (docs/FLEET.md, "Credentials").

use std::future::Future;
use std::sync::Arc;
use std::time::Duration;

use axum::routing::get;
use tokio::net::TcpListener;

use super::broker::Broker;
use super::http::{FleetHttp, routes};
use super::view::FleetView;
use crate::access::{Access, AccessMode, TrustedProxies};
use crate::http::{ConnectionLimits, serve_connections};
use crate::lifecycle::Lifecycle;

/// How long shutdown waits for the broker link to close.
const SHUTDOWN_GRACE: Duration = Duration::from_secs(2);

/// What `docent fleet` was asked for.
#[derive(Clone, Debug)]
pub struct FleetOptions {
    /// The broker and the login.
    pub broker: Broker,
    /// The operator credential (or `--open` on loopback).
    pub access: AccessMode,
}

/// Serves the fleet view on `listener` until `shutdown` completes.
pub async fn serve_fleet(
    listener: TcpListener,
    options: FleetOptions,
    shutdown: impl Future<Output = ()> + Send + 'static,
) -> std::io::Result<()> {
    let life = Lifecycle::new();
    let token = match &options.access {
        AccessMode::Guarded(credentials) => Some(credentials.operator.clone()),
        AccessMode::Open => None,
    };
    // Unique: a broker disconnects a client whose id another one takes.
    let client_id = format!("docent-fleet-{:08x}", rand::random::<u32>());
    let view = FleetView::start(&options.broker, &client_id, token, &life);
    let http = FleetHttp {
        view: Some(view),
        access: Arc::new(Access::new(options.access, TrustedProxies::default())),
        hub: None,
        shutdown: life.shutdown.clone(),
    };
    let router = routes::<FleetHttp>()
        .route(
            "/",
            get(|| async { axum::response::Redirect::to("/fleet") }),
        )
        .route(
            "/static/{*path}",
            get(crate::http::static_files::serve_static),
        )
        .with_state(http);
    let stop = life.shutdown.clone();
    let signal = async move {
        tokio::select! {
            () = shutdown => {}
            () = stop.cancelled() => {}
        }
        stop.cancel();
    };
    serve_connections(
        listener,
        router,
        ConnectionLimits::default(),
        TrustedProxies::default(),
        signal,
    )
    .await;
    life.shutdown.cancel();
    life.tracker.close();
    let _ = tokio::time::timeout(SHUTDOWN_GRACE, life.tracker.wait()).await;
    Ok(())
}
