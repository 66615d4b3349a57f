//! The `display` adapter: `DISPLAY_PAGE`, `PROJECT` and `HIGHLIGHT` change the server's display
//! state and go to every connected kiosk or projector client. A client that connects later gets the current
//! state at once, taken under the same lock as changes, so it neither misses nor repeats one.

use std::sync::{Arc, Mutex};

use serde::Serialize;
use tokio::sync::broadcast;

use crate::adapters::{Adapter, AdapterStatus, CancelScope, Command, Outcome, Reply};
use crate::content::Verb;
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
    /// The `HIGHLIGHT` argument lit on the projector instead of a file; `None` when cleared.
    pub highlight: Option<String>,
}

/// The display state and the channels to display clients. Shared by the adapter and the
/// websocket connections.
pub struct DisplayState {
    current: Mutex<Display>,
    kiosk: broadcast::Sender<Frame>,
    projector: broadcast::Sender<Frame>,
}

impl DisplayState {
    /// Starts with the kiosk on `home` and the projector black.
    pub fn new(home: Option<String>) -> Self {
        DisplayState {
            current: Mutex::new(Display {
                page: home,
                projector: None,
                highlight: None,
            }),
            kiosk: broadcast::channel(DISPLAY_CHANNEL_CAPACITY).0,
            projector: broadcast::channel(DISPLAY_CHANNEL_CAPACITY).0,
        }
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
        let mut current = self.state.lock();
        let channel = match command.verb {
            Verb::DisplayPage => {
                current.page = arg;
                &self.state.kiosk
            }
            // The projector shows a file or highlights, never both: each replaces the other.
            Verb::Project => {
                current.projector = arg;
                current.highlight = None;
                &self.state.projector
            }
            Verb::Highlight => {
                current.highlight = arg;
                current.projector = None;
                &self.state.projector
            }
            _ => {
                drop(current);
                let reason = format!("the display cannot carry out {}", command.verb);
                return reply.finish(Outcome::Failed(reason));
            }
        };
        // No connected client is fine: the state is kept for the next one.
        let _ = channel.send(Frame::from(command_frame(&command)));
        reply.started();
        // Logged under the display lock, so the log's order of changes is the clients' order.
        self.hub.publish(EventKind::DisplayChanged {
            page: current.page.clone(),
            projector: current.projector.clone(),
            highlight: current.highlight.clone(),
        });
        drop(current);
        reply.finish(Outcome::Done);
    }

    fn cancel(&self, _scope: CancelScope<'_>, _reason: &str) {
        // Nothing is ever queued here.
    }

    fn status(&self) -> AdapterStatus {
        AdapterStatus::default()
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
