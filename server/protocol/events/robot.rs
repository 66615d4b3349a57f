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

/// The fields of a `topic.refused` event ([`super::EventKind::TopicRefused`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct TopicRefused {
    /// The topic.
    pub topic: String,
    /// The robot event it would have been, if any (not for the pose topic).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub event: Option<String>,
    /// Why, and what to change.
    pub reason: String,
}

/// The fields of a `reaction.failed` event ([`super::EventKind::ReactionFailed`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct ReactionFailed {
    /// The reaction's place in `reactions:`, from 1.
    pub reaction: usize,
    /// The robot event.
    pub event: String,
    /// The act it would have triggered.
    pub act: String,
    /// Why, and what to fix.
    pub reason: String,
}
