//! What visitors may do to speech: stop the speech visitors started (the kiosk's "Stop
//! speaking"), and leave a page, which ends the speech that touchscreen started there. Both
//! cancel running and waiting speech at once, and cut off the speech such acts have not sent
//! yet (an act waiting at a `WAIT`): a trigger older than the cut never speaks.

use std::collections::BTreeMap;
use std::sync::Arc;

use crate::adapters::Command;
use crate::content::config::Channel;
use crate::dispatch::Dispatcher;
use crate::events::{ActRef, EventKind, Source};
use crate::sync::lock;

/// How many touchscreens' page cuts are remembered; the oldest connections are forgotten
/// first (their acts ended long ago).
const REMEMBERED_KIOSKS: usize = 1024;

/// Trigger ids below which visitors' unsent speech is dropped.
#[derive(Default)]
pub(super) struct VisitorCuts {
    /// A visitor's stop: every kiosk trigger before it.
    all: u64,
    /// A page left: this kiosk connection's triggers before it, by client id.
    by_client: BTreeMap<u64, (u64, String)>,
}

impl Dispatcher {
    /// Cancels the speech visitors started at the touchscreen (running, waiting, and not yet
    /// sent), never anyone else's: the kiosk's "Stop speaking" button.
    pub fn stop_visitor_speech(self: &Arc<Self>, client: u64) {
        self.hub.publish(EventKind::Stop {
            source: Source::Kiosk,
            reason: format!("a visitor stopped the speech (touchscreen {client})"),
        });
        lock(&self.visitor_cuts).all = self.next_id();
        let visitors = |c: &Command, _: u8| c.act.source == Source::Kiosk;
        self.cancel_where(Some(&Channel::Speech), visitors, STOPPED);
    }

    /// A touchscreen left its page for `page`: the speech it started there ends (when the
    /// bundle wants it, the default).
    pub fn page_left(self: &Arc<Self>, client: u64, page: &str) {
        if !self.bundle.load().config.kiosk.leave_page_stops_speech {
            return;
        }
        let reason = format!("the visitor left the page for {page}");
        {
            let mut cuts = lock(&self.visitor_cuts);
            cuts.by_client
                .insert(client, (self.next_id(), reason.clone()));
            while cuts.by_client.len() > REMEMBERED_KIOSKS {
                cuts.by_client.pop_first();
            }
        }
        let theirs =
            |c: &Command, _: u8| c.act.source == Source::Kiosk && c.act.client == Some(client);
        self.cancel_where(Some(&Channel::Speech), theirs, &reason);
    }

    /// Why speech of `act` may no longer be said (a visitor stopped speech or left the page
    /// since it was triggered), if so.
    pub(crate) fn visitor_cut_off(&self, act: &ActRef) -> Option<String> {
        if act.source != Source::Kiosk {
            return None;
        }
        let cuts = lock(&self.visitor_cuts);
        if act.trigger < cuts.all {
            return Some(STOPPED.to_owned());
        }
        let (since, reason) = cuts.by_client.get(&act.client?)?;
        (act.trigger < *since).then(|| reason.clone())
    }
}

const STOPPED: &str = "a visitor stopped the speech at the touchscreen";
