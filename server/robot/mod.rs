//! Robot events, whatever brought them: an adapter process's `robot` frame (`ws::robot`) or a
//! ROS topic the rosbridge link subscribes to (`adapters::rosbridge`). Every one goes through
//! [`notice`]: it may start a visitor session (`corpus: session_start_events`), it is logged
//! and shown to operators and dialog managers, and the site's `reactions:` may trigger an act.
//!
//! Map:
//! - `mod.rs`: [`RobotNotice`], [`RobotInbox`] (how an adapter without the server's state
//!   hands its notices in) and [`notice`], the one intake.
//! - `reactions`: [`Reactions`], the site's `reactions:` carried out (condition, cool-down).

mod reactions;

pub use reactions::{Reacted, Reactions};

use serde_json::Value;
use tokio::sync::mpsc;

use crate::events::{EventKind, RobotEvent};
use crate::state::AppState;

/// Notices waiting for the intake task; a sensor faster than this is told (see
/// [`RobotInbox::send`]).
const INBOX_CAPACITY: usize = 256;

/// Where a robot event came from.
#[derive(Clone, Debug, PartialEq)]
pub enum RobotOrigin {
    /// An adapter process connected over the websocket, by its client id.
    Adapter {
        /// The connection's id.
        client: u64,
    },
    /// A ROS topic, through rosbridge.
    Topic {
        /// The topic's name (`/humans/bodies/tracked`).
        topic: String,
    },
}

/// Something the robot noticed, checked already: its name has the shape
/// `events::robot_event_name_problem` accepts, and its data is at most
/// `ws::ROBOT_DATA_BYTES` of JSON.
#[derive(Clone, Debug, PartialEq)]
pub struct RobotNotice {
    /// Its name (`person.near`).
    pub event: String,
    /// Its reading (`null` when nothing).
    pub data: Value,
    /// Who brought it.
    pub origin: RobotOrigin,
}

/// The inbox full: the notice was not taken.
#[derive(Debug, thiserror::Error)]
#[error(
    "robot event {event:?} was dropped: {INBOX_CAPACITY} robot events were already waiting to \
     be logged (a topic publishing faster than Docent can log; throttle it on the robot)"
)]
pub struct InboxFull {
    /// The dropped event's name.
    pub event: String,
}

/// Hands robot notices to the intake task ([`run_intake`]); cheap to clone. What adapters built
/// before the server's state hold.
#[derive(Clone, Debug)]
pub struct RobotInbox {
    sender: mpsc::Sender<RobotNotice>,
}

/// The intake task's end of a [`RobotInbox`].
pub struct RobotIntake {
    receiver: mpsc::Receiver<RobotNotice>,
}

impl RobotInbox {
    /// An inbox and the intake that empties it.
    pub fn channel() -> (RobotInbox, RobotIntake) {
        let (sender, receiver) = mpsc::channel(INBOX_CAPACITY);
        (RobotInbox { sender }, RobotIntake { receiver })
    }

    /// Hands `notice` in without waiting; when the inbox is full it is not taken, and the
    /// caller says so where its users look (never dropped without a word).
    pub fn send(&self, notice: RobotNotice) -> Result<(), InboxFull> {
        self.sender.try_send(notice).map_err(|e| {
            let notice = match e {
                mpsc::error::TrySendError::Full(n) | mpsc::error::TrySendError::Closed(n) => n,
            };
            InboxFull {
                event: notice.event,
            }
        })
    }
}

/// Takes every notice handed to the inbox through [`notice`] until the server shuts down.
pub async fn run_intake(state: AppState, mut intake: RobotIntake) {
    let shutdown = state.life.shutdown.clone();
    loop {
        tokio::select! {
            received = intake.receiver.recv() => match received {
                Some(n) => notice(&state, n),
                None => return,
            },
            () = shutdown.cancelled() => return,
        }
    }
}

/// The one intake of a robot event: a visitor session it starts, its line in the log (seen by
/// operators and dialog managers), and the reactions the site maps it to.
pub fn notice(state: &AppState, notice: RobotNotice) {
    let bundle = state.dispatcher.bundle();
    let config = &bundle.config;
    let client = match &notice.origin {
        RobotOrigin::Adapter { client } => Some(*client),
        RobotOrigin::Topic { .. } => None,
    };
    state.visits.robot_noticed(
        &config.corpus,
        &config.session_start_events,
        client,
        &notice.event,
    );
    let topic = match notice.origin {
        RobotOrigin::Topic { topic } => Some(topic),
        RobotOrigin::Adapter { .. } => None,
    };
    state.hub.publish(EventKind::Robot(RobotEvent {
        client,
        topic,
        event: notice.event.clone(),
        data: notice.data.clone(),
    }));
    // After the event's own line, so that the log reads cause before effect.
    let on = (notice.event.as_str(), &notice.data);
    (state.reactions).react(&config.reactions, on, &state.dispatcher, &state.hub);
}
