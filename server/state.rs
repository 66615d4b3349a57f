//! The server's shared state: cheap handles cloned into every request and connection.

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use serde::Serialize;

use crate::adapters::Devices;
use crate::dispatch::Dispatcher;
use crate::events::{ClientRole, Hub};
use crate::lifecycle::Lifecycle;
use crate::sync::lock;
use crate::ws::protocol::StateView;

/// A connected websocket client, as `GET /api/state` lists it.
#[derive(Clone, Debug, Serialize)]
pub struct ClientInfo {
    /// Its role.
    pub role: ClientRole,
    /// Its self-given name.
    pub name: Option<String>,
    /// Verbs it serves (adapters).
    pub verbs: Vec<String>,
}

/// Everything handlers need. Cheap to clone.
#[derive(Clone)]
pub struct AppState {
    /// The dispatcher: the only way to devices.
    pub dispatcher: Arc<Dispatcher>,
    /// The event hub.
    pub hub: Hub,
    /// Device state handles (display, drive, ws adapters).
    pub devices: Arc<Devices>,
    /// Shutdown token and task tracker.
    pub life: Lifecycle,
    clients: Arc<Clients>,
}

#[derive(Default)]
struct Clients {
    next: AtomicU64,
    connected: Mutex<BTreeMap<u64, ClientInfo>>,
}

impl AppState {
    /// State over a running dispatcher and its devices.
    pub fn new(dispatcher: Arc<Dispatcher>, devices: Arc<Devices>, life: Lifecycle) -> Self {
        let hub = dispatcher.hub().clone();
        AppState {
            dispatcher,
            hub,
            devices,
            life,
            clients: Arc::default(),
        }
    }

    /// A fresh connection id.
    pub fn next_client_id(&self) -> u64 {
        self.clients.next.fetch_add(1, Ordering::Relaxed) + 1
    }

    /// Records a client that said hello.
    pub fn client_joined(&self, id: u64, info: ClientInfo) {
        lock(&self.clients.connected).insert(id, info);
    }

    /// Forgets a client.
    pub fn client_left(&self, id: u64) {
        lock(&self.clients.connected).remove(&id);
    }

    /// Connected clients by id.
    pub fn clients(&self) -> BTreeMap<u64, ClientInfo> {
        lock(&self.clients.connected).clone()
    }

    /// The state a client is welcomed with.
    pub fn state_view(&self) -> StateView {
        StateView {
            display: self.devices.display.snapshot(),
            pose: self.devices.drive.as_ref().map(|d| d.pose()),
            context: self.dispatcher.context(),
        }
    }
}
