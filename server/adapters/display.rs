//! The `display` adapter: `DISPLAY_PAGE`, `PROJECT` and `HIGHLIGHT` change the server's display
//! state and go to every connected kiosk or projector client. A client that connects later gets the current
//! state at once, taken under the same lock as changes, so it neither misses nor repeats one.
//!
//! A `PROJECT` of a video (by its extension, the list `static/projector.js` plays) is done
//! when a projector client reports the film's end (`done`, or `failed` on a media error), so a
//! `WAIT` can sequence speech after it. The first answer from any projector settles it. With
//! no projector connected it is done at once: there is no film to wait for. A later `PROJECT`
//! or `HIGHLIGHT`, or a stop, cancels the one still playing; the last projector leaving fails
//! it. Images, highlights and pages are done at once.

use std::collections::{BTreeMap, HashSet};
use std::sync::{Arc, Mutex};

use serde::Serialize;
use tokio::sync::broadcast;

use crate::adapters::{Adapter, AdapterStatus, CancelScope, Command, Outcome, Reply};
use crate::content::{Area, Args, MediaKind, Verb};
use crate::events::{ClientRole, EventKind, Hub};
use crate::sync::lock;
use crate::ws::outbox::Frame;
use crate::ws::protocol::command_frame;

/// How many display frames a slow client may fall behind before it is resynchronised.
const DISPLAY_CHANNEL_CAPACITY: usize = 256;

/// What the touchscreen and projector show.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Display {
    /// Page under `pages/` on the touchscreen.
    pub page: Option<String>,
    /// File under `media/` on the projector; `None` is black.
    pub projector: Option<String>,
    /// Whether the projector shows `projector` as a picture or plays it as a video.
    pub projector_kind: Option<MediaKind>,
    /// The `HIGHLIGHT` argument lit on the projector instead of a file, as written; `None`
    /// when cleared.
    pub highlight: Option<String>,
    /// The areas of `highlight`, parsed at load: what the projector draws.
    pub highlight_areas: Option<Vec<Area>>,
}

/// The display state and the channels to display clients. Shared by the adapter and the
/// websocket connections.
pub struct DisplayState {
    current: Mutex<Display>,
    kiosk: broadcast::Sender<Frame>,
    projector: broadcast::Sender<Frame>,
    /// Connected projector clients and the video commands they are playing. Locked after
    /// `current` when both are needed; no reply is finished under it.
    films: Mutex<Films>,
}

/// Projector clients and the `PROJECT` commands of videos waiting for their end.
#[derive(Default)]
struct Films {
    projectors: HashSet<u64>,
    playing: BTreeMap<u64, Reply>,
}

impl DisplayState {
    /// Starts with the kiosk on `home` and the projector black.
    pub fn new(home: Option<String>) -> Self {
        DisplayState {
            current: Mutex::new(Display {
                page: home,
                ..Display::default()
            }),
            kiosk: broadcast::channel(DISPLAY_CHANNEL_CAPACITY).0,
            projector: broadcast::channel(DISPLAY_CHANNEL_CAPACITY).0,
            films: Mutex::default(),
        }
    }

    /// A projector client said hello: videos projected from now on wait for its answer.
    pub fn projector_joined(&self, client: u64) {
        lock(&self.films).projectors.insert(client);
    }

    /// A projector client left; when it was the last one, the videos still playing fail.
    pub fn projector_left(&self, client: u64) {
        let orphans = {
            let mut films = lock(&self.films);
            films.projectors.remove(&client);
            match films.projectors.is_empty() {
                true => std::mem::take(&mut films.playing),
                false => BTreeMap::new(),
            }
        };
        for reply in orphans.into_values() {
            reply.finish(Outcome::Failed("the projector disconnected".into()));
        }
    }

    /// A projector's answer to the video command `id`: `done` at the film's end, `failed` on a
    /// media error. An answer for a command no longer playing (another projector answered,
    /// or it was replaced or stopped) is ignored.
    pub fn answer(&self, client: u64, id: u64, outcome: Outcome) {
        let reply = {
            let mut films = lock(&self.films);
            if !films.projectors.contains(&client) {
                return;
            }
            films.playing.remove(&id)
        };
        if let Some(reply) = reply {
            reply.finish(outcome);
        }
    }

    /// Takes the video commands still playing (all of them, or only `PROJECT`s: the same).
    fn take_playing(&self) -> BTreeMap<u64, Reply> {
        std::mem::take(&mut lock(&self.films).playing)
    }

    /// The current display.
    pub fn snapshot(&self) -> Display {
        self.lock().clone()
    }

    /// The current display and a receiver of later command frames for `role` (kiosk or
    /// projector; other roles get `None`).
    pub fn subscribe(&self, role: ClientRole) -> (Display, Option<broadcast::Receiver<Frame>>) {
        let current = self.lock();
        let rx = match role {
            ClientRole::Kiosk => Some(self.kiosk.subscribe()),
            ClientRole::Projector => Some(self.projector.subscribe()),
            _ => None,
        };
        (current.clone(), rx)
    }

    /// A kiosk shows `page` on its own: the state follows (and the log says so) without
    /// sending anything to display clients.
    pub fn page_shown(&self, page: String, hub: &Hub) {
        let mut current = self.lock();
        if current.page.as_deref() == Some(page.as_str()) {
            return;
        }
        current.page = Some(page);
        hub.publish(display_changed(&current));
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Display> {
        lock(&self.current)
    }
}

/// The built-in display adapter.
pub struct DisplayAdapter {
    state: Arc<DisplayState>,
    hub: Hub,
}

impl DisplayAdapter {
    /// A display adapter over `state`.
    pub fn new(state: Arc<DisplayState>, hub: Hub) -> Self {
        DisplayAdapter { state, hub }
    }
}

impl Adapter for DisplayAdapter {
    fn name(&self) -> &'static str {
        "display"
    }

    fn submit(&self, command: Command, reply: Reply) {
        let arg = command.arg.as_deref().map(str::to_owned);
        let mut video = false;
        let mut current = self.state.lock();
        let channel = match (&command.verb, &*command.args) {
            (Verb::DisplayPage, _) => {
                current.page = arg;
                &self.state.kiosk
            }
            // The projector shows a file or highlights, never both: each replaces the other.
            (Verb::Project, Args::Project { kind, .. }) => {
                video = *kind == MediaKind::Video;
                current.projector = arg;
                current.projector_kind = Some(*kind);
                current.highlight = None;
                current.highlight_areas = None;
                &self.state.projector
            }
            (Verb::Highlight, Args::Highlight { areas }) => {
                current.highlight = arg;
                current.highlight_areas = Some(areas.clone());
                current.projector = None;
                current.projector_kind = None;
                &self.state.projector
            }
            _ => {
                drop(current);
                let reason = format!("the display cannot carry out {}", command.verb);
                return reply.finish(Outcome::Failed(reason));
            }
        };
        reply.started();
        // A new projection ends a film still playing; a film waits for a projector's answer,
        // on the books before the frame goes out so that a fast answer finds it.
        let mut replaced = BTreeMap::new();
        let mut reply = Some(reply);
        if command.verb != Verb::DisplayPage {
            let mut films = lock(&self.state.films);
            replaced = std::mem::take(&mut films.playing);
            if video
                && !films.projectors.is_empty()
                && let Some(reply) = reply.take()
            {
                films.playing.insert(command.id, reply);
            }
        }
        // No connected client is fine: the state is kept for the next one.
        let _ = channel.send(Frame::from(command_frame(&command)));
        // Logged under the display lock, so the log's order of changes is the clients' order.
        self.hub.publish(display_changed(&current));
        drop(current);
        let reason = format!("replaced by a later {}", command.verb);
        for earlier in replaced.into_values() {
            earlier.finish(Outcome::Cancelled(reason.clone()));
        }
        if let Some(reply) = reply {
            reply.finish(Outcome::Done);
        }
    }

    fn cancel(&self, scope: CancelScope<'_>, reason: &str) {
        // Only films waiting for their end are ever outstanding here; all are PROJECTs.
        if matches!(scope, CancelScope::Verb(verb) if *verb != Verb::Project) {
            return;
        }
        for reply in self.state.take_playing().into_values() {
            reply.finish(Outcome::Cancelled(reason.to_owned()));
        }
    }

    fn status(&self) -> AdapterStatus {
        let films = lock(&self.state.films);
        AdapterStatus {
            queued: films.playing.len(),
            current: (films.playing.values().next()).map(|r| r.command().describe()),
        }
    }
}

/// The event that says what `display` now shows.
fn display_changed(display: &Display) -> EventKind {
    EventKind::DisplayChanged {
        page: display.page.clone(),
        projector: display.projector.clone(),
        highlight: display.highlight.clone(),
    }
}
