//! The display's books: which kiosks and projectors are connected, and the commands each
//! screen still owes a report for, with the time each report is due. Plain data, used under
//! the display state's `books` lock; `DisplayState` finishes the replies outside it.

use std::collections::{BTreeMap, HashSet};

use tokio::time::Instant;

use crate::adapters::Reply;
use crate::adapters::display::Screen;

/// What a screen was asked to show, which says what its `done` means.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Showing {
    /// A page on the touchscreen: done when it is revealed.
    Page,
    /// A picture: done once decoded and painted.
    Picture,
    /// A film: `started` when it plays, done when it ends.
    Film,
    /// `HIGHLIGHT` areas: done once painted.
    Highlight,
}

impl Showing {
    /// The screen that shows it.
    pub(super) fn screen(self) -> Screen {
        match self {
            Showing::Page => Screen::Kiosk,
            Showing::Picture | Showing::Film | Showing::Highlight => Screen::Projector,
        }
    }
}

/// A command waiting for a screen's report.
pub(super) struct Awaiting {
    pub(super) reply: Reply,
    pub(super) showing: Showing,
    /// The clients it went to that have not failed or left; the first report settles it.
    pub(super) recipients: Vec<u64>,
    /// When a missing report fails it; `None` once a film reported that it plays (its end
    /// may be far off: a dead projector is then caught by the websocket's ping timeout).
    pub(super) due: Option<Instant>,
}

/// Connected screens and the reports they owe.
#[derive(Default)]
pub(super) struct Books {
    kiosks: HashSet<u64>,
    projectors: HashSet<u64>,
    pub(super) awaiting: BTreeMap<u64, Awaiting>,
    /// The deadline the clock sleeps until; `None` while it waits for one.
    pub(super) clock_at: Option<Instant>,
}

impl Books {
    fn clients(&mut self, screen: Screen) -> &mut HashSet<u64> {
        match screen {
            Screen::Kiosk => &mut self.kiosks,
            Screen::Projector => &mut self.projectors,
        }
    }

    /// The clients connected as `screen`, in id order.
    pub(super) fn connected(&mut self, screen: Screen) -> Vec<u64> {
        let mut clients: Vec<u64> = self.clients(screen).iter().copied().collect();
        clients.sort_unstable();
        clients
    }

    pub(super) fn join(&mut self, screen: Screen, client: u64) {
        self.clients(screen).insert(client);
    }

    /// Forgets `client`; returns the ids of commands nobody is left to report on.
    pub(super) fn leave(&mut self, screen: Screen, client: u64) -> Vec<u64> {
        self.clients(screen).remove(&client);
        let mut orphans = Vec::new();
        for (&id, entry) in &mut self.awaiting {
            if entry.showing.screen() != screen {
                continue;
            }
            entry.recipients.retain(|&c| c != client);
            if entry.recipients.is_empty() {
                orphans.push(id);
            }
        }
        orphans
    }

    /// The entry for `id` if `client` is one it waits on.
    pub(super) fn owed_by(&mut self, id: u64, client: u64) -> Option<&mut Awaiting> {
        (self.awaiting.get_mut(&id)).filter(|entry| entry.recipients.contains(&client))
    }

    /// Takes every entry `pick` chooses, in dispatch order.
    pub(super) fn take(&mut self, pick: impl Fn(&Awaiting) -> bool) -> Vec<(u64, Awaiting)> {
        let ids: Vec<u64> = (self.awaiting.iter())
            .filter(|(_, entry)| pick(entry))
            .map(|(&id, _)| id)
            .collect();
        (ids.into_iter())
            .filter_map(|id| self.awaiting.remove(&id).map(|entry| (id, entry)))
            .collect()
    }

    /// The earliest time a report is due.
    pub(super) fn next_due(&self) -> Option<Instant> {
        self.awaiting.values().filter_map(|entry| entry.due).min()
    }
}
