//! What visitors may do to speech: stop the speech visitors started (the kiosk's "Stop
//! speaking"), and leave a page (by a link, or by an act that shows a page or drives), which
//! ends the speech that touchscreen started before. Each
//! cancel running and waiting speech at once, and cut off the speech such acts have not sent
//! yet (an act waiting at a `WAIT`): a trigger older than the cut never speaks.

use std::collections::BTreeMap;
use std::sync::Arc;

use crate::adapters::Command;
use crate::content::Verb;
use crate::content::config::Channel;
use crate::dispatch::Dispatcher;
use crate::dispatch::state::Turn;
use crate::events::{ActRef, EventKind, Source};

/// How many touchscreens' page cuts are remembered; the oldest connections are forgotten
/// first (their acts ended long ago).
const REMEMBERED_KIOSKS: usize = 1024;

/// Trigger ids below which visitors' unsent speech is dropped.
#[derive(Default)]
pub(crate) struct VisitorCuts {
    /// A visitor's stop: every kiosk trigger before it.
    all: u64,
    /// A page left: this kiosk connection's triggers before it, by client id.
    by_client: BTreeMap<u64, (u64, String)>,
}

impl VisitorCuts {
    /// Drops touchscreen `client`'s triggers before `since`; a later cut already made stays.
    fn cut(&mut self, client: u64, since: u64, reason: &str) {
        let newer = self.by_client.get(&client).is_some_and(|(s, _)| *s > since);
        if !newer {
            self.by_client.insert(client, (since, reason.to_owned()));
        }
        while self.by_client.len() > REMEMBERED_KIOSKS {
            self.by_client.pop_first();
        }
    }

    /// Why speech of `act` may no longer be said (a visitor stopped speech or left the page
    /// since it was triggered), if so.
    pub(crate) fn cut_off(&self, act: &ActRef) -> Option<String> {
        if act.source != Source::Kiosk {
            return None;
        }
        if act.trigger < self.all {
            return Some(STOPPED.to_owned());
        }
        let (since, reason) = self.by_client.get(&act.client?)?;
        (act.trigger < *since).then(|| reason.clone())
    }
}

impl Dispatcher {
    /// Cancels the speech visitors started at the touchscreen (running, waiting, and not yet
    /// sent), never anyone else's: the kiosk's "Stop speaking" button.
    pub fn stop_visitor_speech(self: &Arc<Self>, client: u64) {
        let mut turn = self.turn();
        self.hub.publish(EventKind::Stop {
            source: Source::Kiosk,
            reason: format!("a visitor stopped the speech (touchscreen {client})"),
        });
        turn.state.visitor_cuts.all = self.next_id();
        let visitors = |c: &Command, _: u8| c.act.source == Source::Kiosk;
        self.cancel_where(&mut turn, Some(&Channel::Speech), visitors, STOPPED);
    }

    /// A touchscreen left its page for `page`: the speech it started there ends (when the
    /// bundle wants it, the default).
    pub fn page_left(self: &Arc<Self>, client: u64, page: &str) {
        let mut turn = self.turn();
        if !turn.bundle.config.kiosk.leave_page_stops_speech {
            return;
        }
        let reason = format!("the visitor left the page for {page}");
        self.end_earlier_speech(&mut turn, client, self.next_id(), &reason);
    }

    /// A visitor's act takes the touchscreen to another page or sets the robot off
    /// ([`moves_on`]): as with leaving the page by a link, the speech that touchscreen started
    /// before ends (when the bundle wants it), never the act's own.
    pub(super) fn visitor_moved_on(self: &Arc<Self>, turn: &mut Turn, act: &ActRef) {
        let Some(client) = act.client else {
            return;
        };
        if !turn.bundle.config.kiosk.leave_page_stops_speech {
            return;
        }
        let reason = format!("the visitor moved on (act {})", act.label);
        self.end_earlier_speech(turn, client, act.trigger, &reason);
    }

    /// Ends the speech touchscreen `client` triggered before trigger id `since`: running,
    /// waiting, and not yet sent (the cut).
    fn end_earlier_speech(
        self: &Arc<Self>,
        turn: &mut Turn,
        client: u64,
        since: u64,
        reason: &str,
    ) {
        turn.state.visitor_cuts.cut(client, since, reason);
        let earlier = |c: &Command, _: u8| {
            c.act.source == Source::Kiosk && c.act.client == Some(client) && c.act.trigger < since
        };
        self.cancel_where(turn, Some(&Channel::Speech), earlier, reason);
    }
}

/// Whether a visitor's act with this command moves the visit on: it shows a page or drives.
pub(super) fn moves_on(verb: &Verb) -> bool {
    matches!(verb, Verb::DisplayPage | Verb::DriveStart)
}

const STOPPED: &str = "a visitor stopped the speech at the touchscreen";
