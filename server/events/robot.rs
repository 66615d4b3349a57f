//! What the corpus says about a robot event: something the robot's own software noticed (a
//! person close by, a bumper pressed, a battery low), sent by a device adapter process that
//! declared it. The names are the site's; Docent only checks their shape, logs them, shows
//! them to operators and dialog managers, and starts a visitor session on the ones
//! `corpus.session_start_events` names.

use serde::Serialize;

/// The longest robot event name, in characters.
pub const ROBOT_EVENT_NAME_CHARS: usize = 64;

/// A robot event, as logged (`type` `robot`).
#[derive(Clone, Debug, PartialEq, Serialize)]
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

/// Why `name` cannot be a robot event's name, if it cannot: 1 to 64 characters, lower-case
/// letters, digits, `.`, `_` and `-`, starting with a letter, so that it reads the same in
/// `docent.yaml`, the log and a dialog manager's code.
pub fn robot_event_name_problem(name: &str) -> Option<String> {
    let first_is_letter = name.chars().next().is_some_and(|c| c.is_ascii_lowercase());
    let allowed = |c: char| c.is_ascii_lowercase() || c.is_ascii_digit() || ".-_".contains(c);
    if name.is_empty() || name.chars().count() > ROBOT_EVENT_NAME_CHARS {
        return Some(format!(
            "a robot event's name has 1 to {ROBOT_EVENT_NAME_CHARS} characters (got {name:?})"
        ));
    }
    if !first_is_letter || !name.chars().all(allowed) {
        return Some(format!(
            "a robot event's name starts with a lower-case letter and has only lower-case \
             letters, digits, '.', '_' and '-' (got {name:?}, e.g. \"person.near\")"
        ));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_short_lower_case_words_with_dots() {
        for good in [
            "person.near",
            "bumper",
            "battery_low",
            "asr.text-final",
            "a1",
        ] {
            assert_eq!(robot_event_name_problem(good), None, "{good}");
        }
        for bad in [
            "",
            "Person.near",
            "1person",
            "person near",
            "é",
            &"a".repeat(65),
        ] {
            assert!(robot_event_name_problem(bad).is_some(), "{bad:?}");
        }
    }
}
