//! What the corpus says about the link to the robot's ROS side (`robot.link`): up when the
//! rosbridge connection is made (again), down with the reason when it is lost or cannot be
//! made. Operators see it at once; researchers see in the log when the robot was unreachable.

use serde::{Deserialize, Serialize};

/// Whether the link works.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LinkState {
    /// Connected; subscriptions and advertisements are (re)made.
    Up,
    /// Not connected; Docent is trying again.
    Down,
}

/// A change of the link's state, as logged (`type` `robot.link`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RobotLinkEvent {
    /// The new state.
    pub state: LinkState,
    /// The rosbridge server's address (`ws://robot.local:9090`).
    pub url: String,
    /// Why it went down (absent when up).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
}
