//! The server's shared state: cheap handles cloned into every request and connection.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;

use serde::Serialize;

use crate::access::Access;
use crate::adapters::Devices;
use crate::content::config::ServerLimits;
use crate::corpus::SessionFolders;
use crate::dispatch::Dispatcher;
use crate::events::{ClientRole, Hub};
use crate::http::{Absences, MissingPageReports, Replay};
use crate::lifecycle::Lifecycle;
use crate::operator::{Proposals, Visits};
use crate::recording::Recordings;
use crate::reload::{ReloadStatus, ReloadView};
use crate::robot::Reactions;
use crate::sync::lock;
use crate::wire::linger::Linger;
use crate::wire::outbox::{Frame, Outbox};
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

/// The server's limits in force: read once at start-up (`Server::start`), never reloaded.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Limits {
    /// Connections, time limits, message size and outgoing queue length.
    pub server: ServerLimits,
    /// The open-files limit after start-up raised it (`http::make_room`); `None`: unlimited
    /// or not looked at (a server not started by `Server::start`).
    pub open_files: Option<u64>,
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
    /// Credentials and failed-attempt memory.
    pub access: Arc<Access>,
    /// Proposals from dialog managers waiting for an operator.
    pub proposals: Arc<Proposals>,
    /// The visitor session: marked by operators and dialog managers, or started by a touch.
    pub visits: Arc<Visits>,
    /// The allowance of `page.missing` reports (a flood of bad links is not all logged).
    pub missing_pages: Arc<MissingPageReports>,
    /// What live reload has to tell operators (a refused save, a missing folder).
    pub reload: Arc<ReloadStatus>,
    /// The corpus folder as the `/sessions` page reads it, and its media tickets.
    pub replay: Arc<Replay>,
    /// The kiosks' recordings of visitor sessions.
    pub recordings: Arc<Recordings>,
    /// The site's reactions to robot events: when each last fired.
    pub reactions: Arc<Reactions>,
    /// The fleet over MQTT: this robot's bridge and the fleet view, when started with a broker.
    pub fleet: Arc<crate::fleet::FleetHandles>,
    /// The caption of what the robot is saying, told to screens and consoles (`ws::Captions`).
    pub captions: Arc<crate::ws::Captions>,
    /// Media files converted for Chromium, served under their own names.
    pub media: Arc<crate::media::Media>,
    /// The server's limits in force since start-up (`server:` in `docent.yaml`): what each
    /// connection is held to and `GET /api/state` reports.
    pub limits: Limits,
    clients: Arc<Clients>,
}

/// Sends frames to connected clients by id or role, without the rest of the state: what the
/// dispatcher's notifier holds (`ws::notices`).
#[derive(Clone)]
pub struct ClientLinks(Arc<Clients>);

impl ClientLinks {
    /// Queues `frame` for client `id`; false when it is not connected (or too slow).
    pub fn send_to(&self, id: u64, frame: &Frame) -> bool {
        let outbox = lock(&self.0.connected).get(&id).map(|c| c.outbox.clone());
        outbox.is_some_and(|outbox| outbox.send(frame.clone()))
    }

    /// Queues `frame` for client `id` to go out with its next frames, or within 2 ms
    /// (`wire::linger`); false when it is not connected (or too slow).
    pub fn send_lingering_to(&self, id: u64, frame: &Frame) -> bool {
        let outbox = lock(&self.0.connected).get(&id).map(|c| c.outbox.clone());
        outbox.is_some_and(|outbox| self.0.linger.send(&outbox, frame.clone()))
    }

    /// Queues `frame` for client `id`, held until the log holds event `logged` (an answer
    /// acknowledges only what is logged); false when it is not connected (or too slow).
    pub fn send_logged_to(
        &self,
        id: u64,
        frame: Frame,
        logged: u64,
        reference: Option<String>,
    ) -> bool {
        let outbox = lock(&self.0.connected).get(&id).map(|c| c.outbox.clone());
        outbox.is_some_and(|outbox| outbox.send_logged(frame, logged, reference))
    }

    /// Queues `frame` for every connected client in `role`.
    pub fn send_to_role(&self, role: ClientRole, frame: &Frame) {
        let outboxes: Vec<Outbox> = (lock(&self.0.connected).values())
            .filter(|c| c.info.role == role)
            .map(|c| c.outbox.clone())
            .collect();
        for outbox in outboxes {
            outbox.send(frame.clone());
        }
    }
}

struct Clients {
    next: AtomicU64,
    connected: Mutex<BTreeMap<u64, Connected>>,
    /// Sends the notices that found no company (`wire::linger`).
    linger: Arc<Linger>,
    /// When each role and name was last left (`GET /healthz?role=...`).
    absences: Absences,
}

struct Connected {
    info: ClientInfo,
    /// For frames relayed from another client (WebRTC signalling).
    outbox: Outbox,
    /// Operators that signalled this client (a kiosk answers only them).
    signalled_by: Vec<u64>,
}

impl AppState {
    /// State over a running dispatcher and its devices, writing the corpus folder `corpus`.
    pub fn new(
        dispatcher: Arc<Dispatcher>,
        devices: Arc<Devices>,
        life: Lifecycle,
        access: Access,
        corpus: PathBuf,
        folders: SessionFolders,
    ) -> Self {
        let hub = dispatcher.hub().clone();
        let display = Arc::clone(&devices.display);
        let shown = Box::new(move || display.snapshot());
        // A session's end returns the visitor's language to the default in the same step.
        let live = Arc::clone(&dispatcher);
        let after_end = Box::new(move || live.back_to_default());
        let visits = Arc::new(Visits::new(hub.clone(), shown, after_end));
        // Sessions a touch started end when visitors stop touching (the live bundle's setting).
        let live = Arc::clone(&dispatcher);
        let idle = Arc::clone(&visits)
            .end_idle_sessions(move || live.bundle().config.corpus, life.shutdown.clone());
        life.spawn(idle);
        let clients = Arc::new(Clients {
            next: AtomicU64::default(),
            connected: Mutex::default(),
            linger: Linger::start(&life),
            absences: Absences::default(),
        });
        let links = ClientLinks(Arc::clone(&clients));
        let captions = crate::ws::Captions::new(links.clone());
        let live = Arc::clone(&dispatcher);
        let speech = Arc::clone(&dispatcher);
        let follow = Arc::clone(&captions).follow(
            hub.subscribe(),
            move || live.bundle().config.captions,
            move || speech.saying_now(),
            life.shutdown.clone(),
        );
        life.spawn(follow);
        let recordings = Arc::new(Recordings::new(
            hub.clone(),
            Arc::clone(&visits),
            links,
            folders,
            life.clone(),
        ));
        // Subscribed now, before any client can connect or any session start.
        let live = Arc::clone(&dispatcher);
        let follow = Arc::clone(&recordings)
            .follow(move || live.bundle().config.corpus, life.shutdown.clone());
        life.spawn(follow);
        AppState {
            dispatcher,
            hub,
            devices,
            access: Arc::new(access),
            proposals: Arc::default(),
            visits,
            missing_pages: Arc::default(),
            reload: Arc::default(),
            replay: Arc::new(Replay::new(corpus)),
            recordings,
            reactions: Arc::default(),
            fleet: Arc::default(),
            captions,
            media: crate::media::Media::idle(),
            limits: Limits::default(),
            clients,
            life,
        }
    }

    /// A handle that reaches connected clients.
    pub fn links(&self) -> ClientLinks {
        ClientLinks(Arc::clone(&self.clients))
    }

    /// A fresh connection id.
    pub fn next_client_id(&self) -> u64 {
        self.clients.next.fetch_add(1, Ordering::Relaxed) + 1
    }

    /// Records a client that said hello.
    pub fn client_joined(&self, id: u64, info: ClientInfo, outbox: Outbox) {
        let signalled_by = Vec::new();
        let client = Connected {
            info,
            outbox,
            signalled_by,
        };
        lock(&self.clients.connected).insert(id, client);
    }

    /// Forgets a client; returns what it was, and notes when its role and name were left.
    pub fn client_left(&self, id: u64) -> Option<ClientInfo> {
        let info = lock(&self.clients.connected).remove(&id)?.info;
        let name = info.name.as_deref();
        self.clients.absences.left(info.role, name, Instant::now());
        Some(info)
    }

    /// When each role and name was last left.
    pub fn absences(&self) -> &Absences {
        &self.clients.absences
    }

    /// Sends `frame` to every connected client in `role` (a bundle change for kiosks).
    pub fn send_to_role(&self, role: ClientRole, frame: &str) {
        let outboxes: Vec<Outbox> = (lock(&self.clients.connected).values())
            .filter(|c| c.info.role == role)
            .map(|c| c.outbox.clone())
            .collect();
        // Sent outside the lock, which every hello and goodbye needs.
        for outbox in outboxes {
            outbox.send(Frame::from(frame.to_owned()));
        }
    }

    /// Connected clients by id.
    pub fn clients(&self) -> BTreeMap<u64, ClientInfo> {
        (lock(&self.clients.connected).iter())
            .map(|(id, c)| (*id, c.info.clone()))
            .collect()
    }

    /// A connected client's role.
    pub fn role_of(&self, id: u64) -> Option<ClientRole> {
        lock(&self.clients.connected).get(&id).map(|c| c.info.role)
    }

    /// The outgoing queue of client `to`, for relaying a signal; when the sender is a
    /// `caller` (an operator), the receiver remembers it so that it may answer.
    pub fn signal_route(&self, to: u64, caller: Option<u64>) -> Option<Outbox> {
        let mut clients = lock(&self.clients.connected);
        let target = clients.get_mut(&to)?;
        if let Some(caller) = caller
            && !target.signalled_by.contains(&caller)
        {
            target.signalled_by.push(caller);
        }
        Some(target.outbox.clone())
    }

    /// Forgets client `from` as a signaller; returns the outboxes of the clients it had
    /// signalled (so they can be told it hung up).
    pub fn signaller_left(&self, from: u64) -> Vec<Outbox> {
        let mut clients = lock(&self.clients.connected);
        (clients.values_mut())
            .filter_map(|c| {
                let at = c.signalled_by.iter().position(|&id| id == from)?;
                c.signalled_by.swap_remove(at);
                Some(c.outbox.clone())
            })
            .collect()
    }

    /// Whether client `from` signalled client `to` before.
    pub fn was_signalled_by(&self, to: u64, from: u64) -> bool {
        (lock(&self.clients.connected).get(&to)).is_some_and(|c| c.signalled_by.contains(&from))
    }

    /// The state a client is welcomed with.
    pub fn state_view(&self) -> StateView {
        StateView {
            display: self.devices.display.snapshot(),
            pose: (self.devices.drive.as_ref().map(|d| d.pose()))
                .or_else(|| self.devices.rosbridge.as_ref().and_then(|r| r.pose())),
            context: self.dispatcher.context(),
            language: self.dispatcher.language(),
            reload: ReloadView {
                media: self.media.views(),
                ..self.reload.view()
            },
            corpus: self
                .hub
                .logged_progress()
                .borrow()
                .alert
                .as_deref()
                .map(str::to_owned),
        }
    }
}
