//! What the corpus says about a robot event: something the robot's own software noticed (a
//! person close by, a bumper pressed, a battery low), sent by a device adapter process that
//! declared it. The names are the site's; Docent only checks their shape, logs them, shows
//! them to operators and dialog managers, and starts a visitor session on the ones
//! `corpus.session_start_events` names.

use serde::{Deserialize, Serialize};

pub use docent_content::names::{ROBOT_EVENT_NAME_CHARS, robot_event_name_problem};

/// A robot event, as logged (`type` `robot`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RobotEvent {
    /// The adapter process that sent it (absent for a ROS topic's).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub client: Option<u64>,
    /// The ROS topic it came from, through rosbridge (absent for an adapter process's).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub topic: Option<String>,
    /// Its name (`person.near`).
    pub event: String,
    /// What the adapter said about it, as sent (`null` when nothing).
    pub data: serde_json::Value,
}
