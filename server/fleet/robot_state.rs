//! What a robot publishes as its retained `docent/ID/state`: online, its id, the bundle, the
//! page shown, what it is saying now, its pose, its battery where known, its console's
//! address and its broker link. Built from the server's state and the events seen.
//!
//! The battery is known from robot events only: the latest `robot` event named `battery` or
//! `battery.*` whose data has a number `percent` (0 to 100) or `percentage` (ROS
//! `sensor_msgs/BatteryState`'s 0 to 1 fraction, so multiplied by 100).

use serde::Serialize;
use serde_json::{Value, json};

use crate::events::{Event, EventKind};
use crate::state::AppState;

/// A battery level a robot event reported.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Battery {
    /// 0 to 100.
    pub percent: f64,
    /// The robot event that said so.
    pub event: String,
    /// When, in milliseconds since the Unix epoch (the event's stamp).
    pub at_ms: u64,
}

/// Whether `kind` is a battery robot event (`battery`, `battery.*`): what the bridge follows
/// without loss, at the robot's reporting pace.
pub fn is_battery(kind: &EventKind) -> bool {
    let EventKind::Robot(robot) = kind else {
        return false;
    };
    let name = robot.event.as_str();
    name == "battery" || name.starts_with("battery.")
}

/// The battery level `event` reports, if it is a battery robot event with a level.
pub fn battery_of(event: &Event) -> Option<Battery> {
    let EventKind::Robot(robot) = &event.kind else {
        return None;
    };
    if !is_battery(&event.kind) {
        return None;
    }
    let data = &robot.data;
    let percent = match (data.get("percent"), data.get("percentage")) {
        (Some(p), _) => p.as_f64()?,
        (None, Some(fraction)) => fraction.as_f64()? * 100.0,
        (None, None) => return None,
    };
    (0.0..=100.0).contains(&percent).then(|| Battery {
        percent,
        event: robot.event.as_str().to_owned(),
        at_ms: (event.time.duration_since(std::time::UNIX_EPOCH))
            .map_or(0, |d| u64::try_from(d.as_millis()).unwrap_or(u64::MAX)),
    })
}

/// The fixed parts of a robot's state.
#[derive(Clone, Debug)]
pub struct Identity {
    /// The robot id (topic level).
    pub robot: String,
    /// Its console's address, for the fleet view's link.
    pub console: String,
}

/// The state document of a running robot.
pub fn snapshot(
    state: &AppState,
    identity: &Identity,
    battery: Option<&Battery>,
    link: &super::LinkView,
) -> Value {
    let bundle = state.dispatcher.bundle();
    let bundle_name = (bundle.root.file_name())
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| bundle.root.display().to_string());
    let adapters = state.dispatcher.adapter_status();
    let speaking = (adapters.get(state.devices.speech_adapter))
        .and_then(|s| s.current.as_ref()?.spoken().map(str::to_owned));
    json!({
        "online": true,
        "robot": identity.robot,
        "bundle": bundle_name,
        "page": state.devices.display.snapshot().page,
        "speaking": speaking,
        "pose": state.devices.drive.as_ref().map(|d| d.pose()),
        "battery": battery,
        "context": state.dispatcher.context(),
        "console": identity.console,
        "link": link,
    })
}

/// The state a robot leaves when it stops on purpose (its last will says the same on a crash).
pub fn offline(robot: &str, reason: &str) -> Value {
    json!({ "online": false, "robot": robot, "reason": reason })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::events::RobotEvent;

    fn robot(name: &str, data: Value) -> Event {
        let kind = EventKind::Robot(RobotEvent {
            client: Some(1),
            topic: None,
            event: name.to_owned(),
            data,
        });
        Event::new(1, std::time::SystemTime::now(), 0, kind)
    }

    #[test]
    fn battery_levels_come_from_battery_robot_events() {
        let b = battery_of(&robot("battery", json!({"percent": 80}))).expect("a level");
        assert_eq!((b.percent, b.event.as_str()), (80.0, "battery"));
        let ros = battery_of(&robot("battery.state", json!({"percentage": 0.5}))).expect("ros");
        assert_eq!(ros.percent, 50.0);
        assert_eq!(
            battery_of(&robot("batterylow", json!({"percent": 5}))),
            None
        );
        assert_eq!(battery_of(&robot("battery", json!({"volts": 24}))), None);
        assert_eq!(battery_of(&robot("battery", json!({"percent": 180}))), None);
        assert_eq!(
            battery_of(&robot("battery", json!({"percent": "full"}))),
            None
        );
    }

    #[test]
    fn the_bridge_follows_battery_reports_and_no_other_robot_event() {
        let followed = |name: &str| is_battery(&robot(name, json!({"percent": 1})).kind);
        assert!(followed("battery") && followed("battery.state"));
        assert!(!followed("batterylow") && !followed("person.near"));
    }
}
