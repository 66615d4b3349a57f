//! The built-in `display` adapter: turns `DISPLAY_PAGE`, `PROJECT` and `HIGHLIGHT` into the
//! display state's changes and frames to the screens, and books each command until a screen
//! reports it (the rules are in the parent module's doc).

use std::sync::Arc;

use tokio::time::Instant;

use crate::adapters::display::books::{Awaiting, Showing};
use crate::adapters::display::{
    Current, DisplayState, ProjectorState, Screen, display_changed, set_projector,
};
use crate::adapters::{Adapter, AdapterStatus, CancelScope, Command, Outcome, Reply};
use crate::content::{Args, MediaKind, Verb};
use crate::sync::lock;
use crate::wire::outbox::Frame;

/// The built-in display adapter.
pub struct DisplayAdapter {
    state: Arc<DisplayState>,
}

impl DisplayAdapter {
    /// A display adapter over `state` (which logs to its own hub).
    pub fn new(state: Arc<DisplayState>) -> Self {
        DisplayAdapter { state }
    }
}

/// What `command` asks a screen to show, if it is a display command.
fn showing(command: &Command) -> Option<Showing> {
    match (&command.verb, &*command.args) {
        (Verb::DisplayPage, _) => Some(Showing::Page),
        (Verb::Project, Args::Project { kind, .. }) => Some(match kind {
            MediaKind::Video => Showing::Film,
            _ => Showing::Picture,
        }),
        (Verb::Highlight, Args::Highlight { .. }) => Some(Showing::Highlight),
        _ => None,
    }
}

impl DisplayState {
    /// Changes the state for `command` and sends it to the screens that will report on it;
    /// with none connected it fails at once.
    fn show(&self, command: Command, reply: Reply, showing: Showing) {
        let screen = showing.screen();
        let mut current = lock(&self.current);
        let recipients = lock(&self.books).connected(screen);
        if recipients.is_empty() {
            let before = current.display.clone();
            match showing {
                // The kiosk's state stays the tour's page: a touchscreen that connects shows it.
                Showing::Page => {
                    current.display.page = command.arg.as_deref().map(str::to_owned);
                    current.page_commanded_unseen = true;
                }
                // A projection nobody showed must not appear later (a film least of all).
                _ => set_projector(&mut current, ProjectorState::Black),
            }
            if current.display != before {
                self.hub.publish(display_changed(&current.display));
            }
            drop(current);
            return reply.finish(Outcome::Failed(format!("no {} connected", screen.name())));
        }
        apply(&mut current, &command);
        if showing != Showing::Film {
            reply.started();
        }
        // On the books before the frame goes out, so that a fast report finds it.
        let replaced = {
            let mut books = lock(&self.books);
            let replaced = books.take(|entry| entry.showing.screen() == screen);
            let due = Instant::now() + self.timeout;
            let entry = Awaiting {
                reply,
                showing,
                recipients,
                due: Some(due),
            };
            books.awaiting.insert(command.id, entry);
            // A clock with a deadline wakes by then and finds this one, due later: one wake-up
            // per timeout at most, not one per command.
            if books.clock_at.is_none() {
                books.clock_at = Some(due);
                self.wake.notify_one();
            }
            replaced
        };
        let channel = match screen {
            Screen::Kiosk => &self.kiosk,
            Screen::Projector => &self.projector,
        };
        // No client may be listening at this instant (one just left): its leaving fails it.
        let _ = channel.send(Frame::from(command.frame()));
        // Logged under the display lock, so the log's order of changes is the clients' order.
        self.hub.publish(display_changed(&current.display));
        drop(current);
        let reason = format!("replaced by a later {}", command.verb);
        for (_, earlier) in replaced {
            earlier.reply.finish(Outcome::Cancelled(reason.clone()));
        }
    }
}

/// The state `command` asks for, before any screen reported on it.
fn apply(current: &mut Current, command: &Command) {
    let arg = command.arg.as_deref().map(str::to_owned);
    let display = &mut current.display;
    match &*command.args {
        // The projector shows a file or highlights, never both: each replaces the other.
        Args::Highlight { areas } => {
            display.highlight = arg;
            display.highlight_areas = Some(areas.clone());
            display.projector = None;
            display.projector_kind = None;
        }
        Args::Project { kind, .. } => {
            display.projector = arg;
            display.projector_kind = Some(*kind);
            display.highlight = None;
            display.highlight_areas = None;
        }
        _ => {
            display.page = arg;
            return;
        }
    }
    display.projector_state = ProjectorState::Loading;
    current.projecting = Some(command.id);
}

impl Adapter for DisplayAdapter {
    fn name(&self) -> &'static str {
        "display"
    }

    fn submit(&self, command: Command, reply: Reply) {
        match showing(&command) {
            Some(showing) => self.state.show(command, reply, showing),
            None => {
                let reason = format!("the display cannot carry out {}", command.verb);
                reply.finish(Outcome::Failed(reason));
            }
        }
    }

    fn cancel(&self, scope: CancelScope<'_>, reason: &str) {
        self.state.cancel_where(
            |entry| match scope {
                CancelScope::All => true,
                CancelScope::Verb(verb) => &entry.reply.command().verb == verb,
            },
            reason,
        );
    }

    fn status(&self) -> AdapterStatus {
        let books = lock(&self.state.books);
        AdapterStatus {
            queued: books.awaiting.len(),
            current: (books.awaiting.values().next()).map(|e| e.reply.command().current()),
        }
    }
}
