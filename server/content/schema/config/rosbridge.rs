//! The schema of `rosbridge:`: the link to a ROS 2 robot through a rosbridge v2 server, its
//! goals, pose, stop and the topics that become robot events. Keys from the loader's lists in
//! `config_file/rosbridge.rs`.

use serde_json::{Value, json};

use crate::config::PoseMessage;
use crate::config_file::rosbridge::{EVENT_KEYS, KEYS};
use crate::schema::{choice, duration, section};

const ROS_NAME: &str = r"^/?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*$";

fn name(description: &str) -> Value {
    json!({ "type": "string", "pattern": ROS_NAME, "description": description })
}

pub(super) fn rosbridge() -> Value {
    section(
        KEYS,
        key,
        "The link to a ROS 2 robot through a rosbridge v2 server (docs/ROBOT.md): where goals \
         go, where the pose comes from, how the robot is stopped, which topics become robot \
         events. Needs `url`.",
    )
}

fn key(key: &str) -> Value {
    match key {
        "url" => json!({
            "type": "string",
            "pattern": r"^ws://[^/\s]\S*$",
            "description": "The rosbridge server's websocket address, e.g. `ws://robot.local:9090`.",
        }),
        "goal_topic" => name(
            "Where DRIVE_START publishes its geometry_msgs/msg/PoseStamped goal (default \
             `/goal_pose`, which Nav2 listens to).",
        ),
        "frame" => name("The frame the goals are in (default `map`)."),
        "action" => name(
            "Nav2's NavigateToPose action (e.g. `/navigate_to_pose`): goals are sent as action \
             goals and cancelled on a stop, instead of published on `goal_topic`.",
        ),
        "pose_topic" => name("Where the robot's pose comes from (default `/amcl_pose`)."),
        "pose_type" => {
            let kinds = [
                PoseMessage::PoseWithCovarianceStamped,
                PoseMessage::Odometry,
                PoseMessage::PoseStamped,
            ]
            .map(PoseMessage::type_name);
            choice(
                &kinds,
                "The pose topic's message type (default PoseWithCovarianceStamped).",
            )
        }
        "stop_topic" => name("Where a std_msgs/msg/Empty goes on every stop, if anywhere."),
        "cmd_vel" => json!({
            "type": "string",
            "anyOf": [{ "pattern": ROS_NAME }, { "const": "none" }],
            "description": "Where a zero geometry_msgs/msg/Twist goes on every stop (default \
                            `/cmd_vel`), or `none`.",
        }),
        "tolerance" => json!({
            "type": "number",
            "exclusiveMinimum": 0,
            "maximum": 10,
            "description": "How close to its waypoint the robot counts as arrived, in metres \
                            (default 0.3).",
        }),
        "stall" => duration(
            "How long a drive may go without coming closer to its waypoint before it fails and \
             the robot is told to stop (default 30s; at least 1s, or 0s: wait for ever).",
        ),
        "events" => {
            let mut event = section(
                EVENT_KEYS,
                |k| match k {
                    "topic" => name("The ROS topic, e.g. `/humans/bodies/tracked`."),
                    "type" => json!({
                        "type": "string",
                        "pattern": r"^[A-Za-z][A-Za-z0-9_]*/(msg/)?[A-Za-z][A-Za-z0-9_]*$",
                        "description": "Its message type, e.g. `std_msgs/msg/String`.",
                    }),
                    _ => json!({
                        "type": "string",
                        "pattern": r"^[a-z][a-z0-9._-]{0,63}$",
                        "description": "The robot event each message becomes, e.g. `person.near`.",
                    }),
                },
                "A topic whose messages become robot events.",
            );
            event["type"] = json!("object");
            event["required"] = json!(EVENT_KEYS);
            json!({
                "type": ["array", "null"],
                "items": event,
                "description": "ROS topics whose messages become robot events (the message as \
                                `data`, at most 4096 bytes of JSON).",
            })
        }
        _ => json!({}),
    }
}
