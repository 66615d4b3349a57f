//! What the corpus says about the kiosk's attract loop: that it started, and what ended it.
//! The loop is the screen's own doing, never a visitor's: its pages and act start no session;
//! only the touch that ends it does, as any first touch.

use serde::{Deserialize, Serialize};

/// A kiosk's report on its attract loop (the `attract` frame's `state`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AttractState {
    /// The loop began (after the idle time without a touch).
    Started,
    /// The loop ended.
    Ended,
}

/// What ended an attract loop.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AttractEnd {
    /// A visitor touched the screen (logged as a `touch` too; it may start a session).
    Touch,
    /// Docent showed a page (`DISPLAY_PAGE`): the robot took over the screen.
    Robot,
    /// The schedule closed the kiosk or changed the loop.
    Schedule,
}

/// The fields of a `attract.started` event ([`super::EventKind::AttractStarted`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct AttractStarted {
    /// The kiosk.
    pub client: u64,
}

/// The fields of a `attract.ended` event ([`super::EventKind::AttractEnded`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct AttractEnded {
    /// The kiosk.
    pub client: u64,
    /// What ended it.
    pub by: AttractEnd,
}
