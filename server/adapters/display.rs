//! The `display` adapter's state: what the touchscreen and the projector show, and the
//! commands they still owe a report for. `DISPLAY_PAGE`, `PROJECT` and `HIGHLIGHT` go to every
//! connected kiosk or projector client; a client that connects later gets the current state at
//! once, taken under the same lock as changes, so it neither misses nor repeats one.
//!
//! No outcome is claimed that a screen did not report (docs/ADAPTERS.md has the rules):
//! - With no client of its screen connected a command fails at once ("no projector
//!   connected", "no touchscreen connected").
//! - Otherwise it is done when the first client reports it: a page revealed, a picture or
//!   highlight painted, a film ended. A film reports `started` when it plays. A `failed`
//!   report (the browser's own reason) fails it; so does every recipient leaving, and a report
//!   (for a film: its start) missing after `adapters: timeout`.
//! - A later command for the same screen cancels one still waiting; a stop cancels all. A
//!   stopped or overdue projection blacks out the projector (a `cancel` frame).
//!
//! The projector's state follows its reports: `loading` until shown, then `shown`, a film
//! `playing` then black, or `held` when the projector keeps its last frame
//! (`projector: after_video: hold`, reported by the page with its `done`). A failed or
//! cancelled projection is black. A projector that connects is never sent a film to play: the
//! state never names one that is over, and the page starts films only from commands.

mod adapter;
mod adopt;
mod books;

pub use docent_protocol::ProjectorState;
pub use docent_protocol::state::Display;
use std::sync::{Arc, Mutex, Weak};
use std::time::Duration;

use tokio::sync::{Notify, broadcast};
use tokio::time::Instant;
use tokio_util::sync::CancellationToken;

use crate::adapters::Outcome;
use crate::events::{ClientRole, EventKind, Hub};
use crate::lifecycle::Lifecycle;
use crate::sync::lock;
use crate::wire::outbox::Frame;
use docent_protocol::frames::cancel_frame;

pub use adapter::DisplayAdapter;
use books::{Awaiting, Books, Showing};

/// How many display frames a slow client may fall behind before it is resynchronised.
const DISPLAY_CHANNEL_CAPACITY: usize = 256;

/// A touchscreen or a projector.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Screen {
    /// A kiosk shell.
    Kiosk,
    /// A projector shell.
    Projector,
}

impl Screen {
    /// The screen a client with `role` is, if any.
    pub fn of(role: ClientRole) -> Option<Screen> {
        match role {
            ClientRole::Kiosk => Some(Screen::Kiosk),
            ClientRole::Projector => Some(Screen::Projector),
            _ => None,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Screen::Kiosk => "touchscreen",
            Screen::Projector => "projector",
        }
    }
}

/// A screen's report on a command it was sent (`started`, `done`, `failed` frames).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ScreenReport {
    /// A film began to play.
    Started,
    /// Shown (a page, a picture, highlights) or, for a film, ended; `held` says the film's
    /// last frame stays on screen.
    Done {
        /// The projector keeps the film's last frame.
        held: bool,
    },
    /// It could not be shown, for this reason.
    Failed(String),
}

/// The display state as changed by commands and screens' reports.
struct Current {
    display: Display,
    /// The command whose picture, film or highlight the projector state is about.
    projecting: Option<u64>,
    /// A `DISPLAY_PAGE` came while no touchscreen was connected: the next kiosk to join is
    /// sent its page, even if it says it shows another (`adopt.rs`).
    page_commanded_unseen: bool,
}

/// The display state, the channels to display clients and the reports they owe. Shared by
/// the adapter and the websocket connections.
pub struct DisplayState {
    current: Mutex<Current>,
    kiosk: broadcast::Sender<Frame>,
    projector: broadcast::Sender<Frame>,
    /// Locked after `current` when both are needed; no reply is finished under it.
    books: Mutex<Books>,
    hub: Hub,
    /// How long a screen may take to report a command (`adapters: timeout`).
    timeout: Duration,
    /// Wakes the clock when a report falls due while it has no deadline (a deadline that went
    /// away only wakes it once for nothing, so settling needs no wake-up).
    wake: Arc<Notify>,
}

impl DisplayState {
    /// Starts with the kiosk on `home` and the projector black; a report missing after
    /// `timeout` fails its command (the clock runs as a task of `life`).
    pub fn start(home: Option<String>, timeout: Duration, hub: Hub, life: &Lifecycle) -> Arc<Self> {
        let state = Arc::new(DisplayState {
            current: Mutex::new(Current {
                display: Display {
                    page: home,
                    ..Display::default()
                },
                projecting: None,
                page_commanded_unseen: false,
            }),
            kiosk: broadcast::channel(DISPLAY_CHANNEL_CAPACITY).0,
            projector: broadcast::channel(DISPLAY_CHANNEL_CAPACITY).0,
            books: Mutex::default(),
            hub,
            timeout,
            wake: Arc::new(Notify::new()),
        });
        let clock = run_clock(
            Arc::downgrade(&state),
            Arc::clone(&state.wake),
            life.shutdown.clone(),
        );
        life.spawn(clock);
        state
    }

    /// [`subscribe`](Self::subscribe) for a client that just said hello; a kiosk or projector
    /// also joins its screen, under the same lock, so that every display command is either in
    /// the state it gets or sent to it and awaited from it.
    pub fn join(
        &self,
        role: ClientRole,
        client: u64,
    ) -> (Display, Option<broadcast::Receiver<Frame>>) {
        let mut current = lock(&self.current);
        if role == ClientRole::Kiosk {
            current.page_commanded_unseen = false;
        }
        let subscribed = self.subscribe_locked(&current, role);
        if let Some(screen) = Screen::of(role) {
            lock(&self.books).join(screen, client);
        }
        subscribed
    }

    /// A kiosk or projector client left; commands only it could report on fail.
    pub fn left(&self, role: ClientRole, client: u64) {
        let Some(screen) = Screen::of(role) else {
            return;
        };
        let orphans = lock(&self.books).leave(screen, client);
        let reason = format!("the {} disconnected", screen.name());
        for id in orphans {
            self.settle(id, Outcome::Failed(reason.clone()), ProjectorState::Black);
        }
    }

    /// A screen's report on command `id`. A report for a command no longer waiting (another
    /// screen answered, it was replaced, stopped or timed out) is ignored.
    pub fn report(&self, role: ClientRole, client: u64, id: u64, report: ScreenReport) {
        if Screen::of(role).is_none() {
            return;
        }
        let (showing, started) = {
            let mut books = lock(&self.books);
            let Some(entry) = books.owed_by(id, client) else {
                return;
            };
            let film_starts = report == ScreenReport::Started && entry.showing == Showing::Film;
            let first = film_starts && entry.due.take().is_some();
            if first {
                entry.reply.started();
            }
            (entry.showing, first)
        };
        if started {
            return self.projector_now(id, ProjectorState::Playing);
        }
        let (outcome, after) = match report {
            ScreenReport::Started => return,
            ScreenReport::Failed(reason) => (Outcome::Failed(reason), ProjectorState::Black),
            ScreenReport::Done { held } => match showing {
                Showing::Film if held => (Outcome::Done, ProjectorState::Held),
                Showing::Film => (Outcome::Done, ProjectorState::Black),
                _ => (Outcome::Done, ProjectorState::Shown),
            },
        };
        self.settle(id, outcome, after);
    }

    /// Takes `id` off the books and finishes it with `outcome`; the projector state becomes
    /// `after` when the projection is still this command's.
    fn settle(&self, id: u64, outcome: Outcome, after: ProjectorState) {
        let Some(entry) = lock(&self.books).awaiting.remove(&id) else {
            return;
        };
        if entry.showing.screen() == Screen::Projector {
            self.projector_now(id, after);
        }
        entry.reply.finish(outcome);
    }

    /// The projector state becomes `now` if the projection is still command `id`'s.
    fn projector_now(&self, id: u64, now: ProjectorState) {
        let mut current = lock(&self.current);
        if current.projecting != Some(id) || current.display.projector_state == now {
            return;
        }
        set_projector(&mut current, now);
        self.hub.publish(display_changed(&current.display));
    }

    /// Fails the commands whose report is overdue at `now`.
    fn expire(&self, now: Instant) {
        let overdue = lock(&self.books).take(|entry| entry.due.is_some_and(|due| due <= now));
        for (id, entry) in overdue {
            let screen = entry.showing.screen();
            let what = match entry.showing {
                Showing::Film => "the film playing",
                _ => "it shown",
            };
            let reason = format!(
                "the {} did not report {what} within {:?}",
                screen.name(),
                self.timeout
            );
            if screen == Screen::Projector {
                // Whatever the projector shows late would contradict the log: it goes black.
                self.black_out(&[id], &reason);
            }
            entry.reply.finish(Outcome::Failed(reason));
        }
    }

    /// Cancels the commands `pick` chooses; a cancelled projection blacks the projector out.
    fn cancel_where(&self, pick: impl Fn(&Awaiting) -> bool, reason: &str) {
        let taken = lock(&self.books).take(pick);
        let ids: Vec<u64> = taken.iter().map(|(id, _)| *id).collect();
        self.black_out(&ids, reason);
        for (_, entry) in taken {
            entry.reply.finish(Outcome::Cancelled(reason.to_owned()));
        }
    }

    /// When the projection is one of `ids`, the projector goes black: the state says so and
    /// the projectors get a `cancel` frame (a film stops).
    fn black_out(&self, ids: &[u64], reason: &str) {
        let mut current = lock(&self.current);
        if !current.projecting.is_some_and(|id| ids.contains(&id)) {
            return;
        }
        set_projector(&mut current, ProjectorState::Black);
        let _ = (self.projector).send(Frame::from(cancel_frame(None, reason)));
        self.hub.publish(display_changed(&current.display));
    }

    /// The current display.
    pub fn snapshot(&self) -> Display {
        lock(&self.current).display.clone()
    }

    /// The current display and a receiver of later command frames for `role` (kiosk or
    /// projector; other roles get `None`).
    pub fn subscribe(&self, role: ClientRole) -> (Display, Option<broadcast::Receiver<Frame>>) {
        self.subscribe_locked(&lock(&self.current), role)
    }

    fn subscribe_locked(
        &self,
        current: &Current,
        role: ClientRole,
    ) -> (Display, Option<broadcast::Receiver<Frame>>) {
        let rx = match Screen::of(role) {
            Some(Screen::Kiosk) => Some(self.kiosk.subscribe()),
            Some(Screen::Projector) => Some(self.projector.subscribe()),
            None => None,
        };
        (current.display.clone(), rx)
    }

    /// A kiosk shows `page` on its own: the state follows (and the log says so) without
    /// sending anything to display clients.
    pub fn page_shown(&self, page: String, hub: &Hub) {
        let mut current = lock(&self.current);
        if current.display.page.as_deref() == Some(page.as_str()) {
            return;
        }
        current.display.page = Some(page);
        hub.publish(display_changed(&current.display));
    }
}

/// Sets the projector state; black also forgets what was projected.
fn set_projector(current: &mut Current, now: ProjectorState) {
    let display = &mut current.display;
    display.projector_state = now;
    if now == ProjectorState::Black {
        display.projector = None;
        display.projector_kind = None;
        display.highlight = None;
        display.highlight_areas = None;
        current.projecting = None;
    }
}

/// The clock: fails commands whose screen report is overdue.
async fn run_clock(state: Weak<DisplayState>, wake: Arc<Notify>, shutdown: CancellationToken) {
    loop {
        let due = {
            let Some(state) = state.upgrade() else { return };
            let mut books = lock(&state.books);
            books.clock_at = books.next_due();
            books.clock_at
        };
        let overdue = async {
            match due {
                Some(at) => tokio::time::sleep_until(at).await,
                None => std::future::pending().await,
            }
        };
        tokio::select! {
            () = wake.notified() => continue,
            () = shutdown.cancelled() => return,
            () = overdue => {
                let Some(state) = state.upgrade() else { return };
                state.expire(Instant::now());
            }
        }
    }
}

/// The event that says what `display` now shows.
fn display_changed(display: &Display) -> EventKind {
    EventKind::DisplayChanged {
        page: display.page.clone(),
        projector: display.projector.clone(),
        highlight: display.highlight.clone(),
        projector_state: display.projector_state,
    }
}
