//! The `rosbridge:` section of `docent.yaml`: how Docent reaches a ROS 2 robot through a
//! rosbridge v2 server (`url`), where its goals go (a `geometry_msgs/PoseStamped` topic and
//! frame, or Nav2's `NavigateToPose` action), where its pose comes from, how it is stopped,
//! when it has arrived, and which topics become robot events. Read with the generic readers;
//! `drive: adapter: rosbridge` or a `rosbridge:` section without a `url` is
//! `rosbridge-url-missing`.

use crate::DiagnosticCode;
use crate::acts_file::yaml::{Kind, Node};
use crate::config::{AdapterKind, SiteConfig};
use crate::diagnostic::Diagnostic;
use crate::names::robot_event_name_problem;

use serde_json::{Value, json};

use super::Reader;
use super::section::{Field, Limit, Section, Shape};
use crate::schema::{choice, section_schema};

/// A ROS topic, action or frame name, as [`is_ros_name`] accepts it.
const ROS_NAME: &str = r"^/?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*$";

/// The settings of `rosbridge:`.
pub(crate) const SECTION: Section = Section {
    name: "rosbridge",
    required: &[],
    fields: &[
        Field {
            key: "url",
            description: "The rosbridge server's websocket address, e.g. \
                          `ws://robot.local:9090`.",
            shape: Shape::Pattern(r"^ws://[^/\s]\S*$"),
        },
        Field {
            key: "goal_topic",
            description: "Where DRIVE_START publishes its geometry_msgs/msg/PoseStamped goal \
                          (default `/goal_pose`, which Nav2 listens to).",
            shape: Shape::Pattern(ROS_NAME),
        },
        Field {
            key: "frame",
            description: "The frame the goals are in (default `map`).",
            shape: Shape::Pattern(ROS_NAME),
        },
        Field {
            key: "action",
            description: "Nav2's NavigateToPose action (e.g. `/navigate_to_pose`): goals are \
                          sent as action goals and cancelled on a stop, instead of published \
                          on `goal_topic`.",
            shape: Shape::Pattern(ROS_NAME),
        },
        Field {
            key: "pose_topic",
            description: "Where the robot's pose comes from (default `/amcl_pose`).",
            shape: Shape::Pattern(ROS_NAME),
        },
        Field {
            key: "pose_type",
            description: "The pose topic's message type (default PoseWithCovarianceStamped).",
            shape: Shape::Custom(pose_type_schema),
        },
        Field {
            key: "stop_topic",
            description: "Where a std_msgs/msg/Empty goes on every stop, if anywhere.",
            shape: Shape::Pattern(ROS_NAME),
        },
        Field {
            key: "cmd_vel",
            description: "Where a zero geometry_msgs/msg/Twist goes on every stop (default \
                          `/cmd_vel`), or `none`.",
            shape: Shape::Custom(cmd_vel_schema),
        },
        Field {
            key: "tolerance",
            description: "How close to its waypoint the robot counts as arrived, in metres \
                          (default 0.3).",
            shape: Shape::Number {
                min: Limit::Exclusive(0.0),
                max: Limit::Inclusive(10.0),
            },
        },
        Field {
            key: "stall",
            description: "How long a drive may go without coming closer to its waypoint \
                          before it fails and the robot is told to stop (default 30s; at \
                          least 1s, or 0s: wait for ever).",
            shape: Shape::Duration,
        },
        Field {
            key: "events",
            description: "ROS topics whose messages become robot events (the message as \
                          `data`, at most 4096 bytes of JSON).",
            shape: Shape::Custom(events_schema),
        },
    ],
};

/// The settings of one entry of `rosbridge: events:`, all needed.
const EVENT: Section = Section {
    name: "a rosbridge event",
    required: &["topic", "type", "event"],
    fields: &[
        Field {
            key: "topic",
            description: "The ROS topic, e.g. `/humans/bodies/tracked`.",
            shape: Shape::Pattern(ROS_NAME),
        },
        Field {
            key: "type",
            description: "Its message type, e.g. `std_msgs/msg/String`.",
            shape: Shape::Pattern(r"^[A-Za-z][A-Za-z0-9_]*/(msg/)?[A-Za-z][A-Za-z0-9_]*$"),
        },
        Field {
            key: "event",
            description: "The robot event each message becomes, e.g. `person.near`.",
            shape: Shape::Pattern(r"^[a-z][a-z0-9._-]{0,63}$"),
        },
    ],
};

/// The pose messages Docent reads, in the order the reader offers them.
const POSE_MESSAGES: [PoseMessage; 3] = [
    PoseMessage::PoseWithCovarianceStamped,
    PoseMessage::Odometry,
    PoseMessage::PoseStamped,
];

/// One of the pose messages' type names.
fn pose_type_schema(description: &'static str) -> Value {
    choice(&POSE_MESSAGES.map(PoseMessage::type_name), description)
}

/// A ROS topic or `none`.
fn cmd_vel_schema(description: &'static str) -> Value {
    json!({
        "type": "string",
        "anyOf": [{ "pattern": ROS_NAME }, { "const": "none" }],
        "description": description,
    })
}

/// A list of topics, each becoming robot events.
fn events_schema(description: &'static str) -> Value {
    json!({
        "type": ["array", "null"],
        "items": section_schema(&EVENT, "A topic whose messages become robot events."),
        "description": description,
    })
}

const URL_USAGE: &str = "`url` is the rosbridge server's websocket address, `ws://` then host \
                         and port, e.g. `url: ws://robot.local:9090` (for wss://, run Docent \
                         on the robot's network or through a tunnel).";
const TOPIC_USAGE: &str = "A ROS topic or action name: letters, digits, `_` and `/`, starting \
                           with `/` or a letter, e.g. `/goal_pose`.";
const FRAME_USAGE: &str = "`frame` is the ROS frame the goals are in: letters, digits, `_` and \
                           `/`, e.g. `frame: map`.";
const TOLERANCE_USAGE: &str = "`tolerance` is how close to its waypoint the robot counts as \
                               arrived, in metres: above 0 and at most 10, e.g. \
                               `tolerance: 0.3`.";
const STALL_USAGE: &str = "`stall` is how long a drive may go without coming closer to its \
                           waypoint before it fails and the robot is told to stop, with its \
                           unit: at least 1s, e.g. `stall: 30s`, or `0s` to wait for ever.";
const TYPE_USAGE: &str = "A ROS message type, `package/msg/Name`, e.g. `std_msgs/msg/String`.";
const EVENTS_USAGE: &str = "`events` is a list of topics, each `{topic: /battery_state, type: \
                            sensor_msgs/msg/BatteryState, event: battery.state}`.";
const CMD_VEL_USAGE: &str = "`cmd_vel` is the velocity topic a zero `geometry_msgs/msg/Twist` \
                             goes to on every stop (default `/cmd_vel`), or `none`.";

/// The pose topic's message type; each holds the pose at its own path.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PoseMessage {
    /// `geometry_msgs/msg/PoseWithCovarianceStamped` (AMCL's `/amcl_pose`; the default).
    PoseWithCovarianceStamped,
    /// `nav_msgs/msg/Odometry` (`/odom`).
    Odometry,
    /// `geometry_msgs/msg/PoseStamped`.
    PoseStamped,
}

impl PoseMessage {
    /// The ROS type name.
    pub fn type_name(self) -> &'static str {
        match self {
            PoseMessage::PoseWithCovarianceStamped => "geometry_msgs/msg/PoseWithCovarianceStamped",
            PoseMessage::Odometry => "nav_msgs/msg/Odometry",
            PoseMessage::PoseStamped => "geometry_msgs/msg/PoseStamped",
        }
    }
}

/// A ROS topic whose messages become robot events.
#[derive(Clone, Debug, PartialEq)]
pub struct TopicEvent {
    /// The topic (`/humans/bodies/tracked`).
    pub topic: String,
    /// Its message type (`hri_msgs/msg/IdsList`).
    pub message_type: String,
    /// The robot event each message becomes (`person.near`).
    pub event: String,
}

/// `rosbridge:` in `docent.yaml`.
#[derive(Clone, Debug, PartialEq)]
pub struct RosbridgeConfig {
    /// `ws://host:port` of the rosbridge server; `None`: no link.
    pub url: Option<String>,
    /// Where `DRIVE_START` publishes its `PoseStamped` goal (`/goal_pose`).
    pub goal_topic: String,
    /// The goal's frame (`map`).
    pub frame: String,
    /// Nav2's `NavigateToPose` action (`/navigate_to_pose`), used instead of the goal topic.
    pub action: Option<String>,
    /// Where the pose comes from (`/amcl_pose`).
    pub pose_topic: String,
    /// The pose topic's type.
    pub pose_type: PoseMessage,
    /// Where a `std_msgs/msg/Empty` goes on every stop, if anywhere.
    pub stop_topic: Option<String>,
    /// Where a zero `geometry_msgs/msg/Twist` goes on every stop, if anywhere (`/cmd_vel`).
    pub cmd_vel: Option<String>,
    /// Metres from the waypoint that count as arrived.
    pub tolerance: f64,
    /// How long a drive may go without coming closer before it fails; `None`: for ever.
    pub stall: Option<std::time::Duration>,
    /// Topics that become robot events.
    pub events: Vec<TopicEvent>,
}

impl Default for RosbridgeConfig {
    fn default() -> Self {
        RosbridgeConfig {
            url: None,
            goal_topic: "/goal_pose".to_owned(),
            frame: "map".to_owned(),
            action: None,
            pose_topic: "/amcl_pose".to_owned(),
            pose_type: PoseMessage::PoseWithCovarianceStamped,
            stop_topic: None,
            cmd_vel: Some("/cmd_vel".to_owned()),
            tolerance: 0.3,
            stall: Some(std::time::Duration::from_secs(30)),
            events: Vec::new(),
        }
    }
}

fn is_ros_name(name: &str) -> bool {
    let body = name.strip_prefix('/').unwrap_or(name);
    body.starts_with(|c: char| c.is_ascii_alphabetic())
        && !body.ends_with('/')
        && !body.contains("//")
        && body
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '/')
}

fn is_message_type(name: &str) -> bool {
    let parts: Vec<&str> = name.split('/').collect();
    let word = |p: &&str| {
        p.starts_with(|c: char| c.is_ascii_alphabetic())
            && p.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    };
    match parts.as_slice() {
        [package, "msg", kind] | [package, kind] => word(package) && word(kind),
        _ => false,
    }
}

fn is_ws_url(url: &str) -> bool {
    url.strip_prefix("ws://")
        .is_some_and(|rest| !rest.is_empty() && !rest.starts_with('/'))
        && !url.chars().any(char::is_whitespace)
}

impl Reader {
    pub(super) fn rosbridge(&mut self, node: &Node, config: &mut SiteConfig) {
        let ros = &mut config.rosbridge;
        let name = |t: &str| is_ros_name(t).then(|| t.to_owned());
        for (field, value) in self.entries(node, &SECTION) {
            match field.key {
                "url" => {
                    let parse = |t: &str| is_ws_url(t).then(|| t.to_owned());
                    ros.url = self.setting(value, URL_USAGE, parse).or(ros.url.take());
                }
                "goal_topic" => {
                    if let Some(topic) = self.setting(value, TOPIC_USAGE, name) {
                        ros.goal_topic = topic;
                    }
                }
                "frame" => {
                    if let Some(frame) = self.setting(value, FRAME_USAGE, name) {
                        ros.frame = frame;
                    }
                }
                "action" => ros.action = self.setting(value, TOPIC_USAGE, name),
                "pose_topic" => {
                    if let Some(topic) = self.setting(value, TOPIC_USAGE, name) {
                        ros.pose_topic = topic;
                    }
                }
                "pose_type" => {
                    let kinds = POSE_MESSAGES.map(|k| (k.type_name(), k));
                    if let Some(kind) = self.choice(value, "pose type", &kinds) {
                        ros.pose_type = kind;
                    }
                }
                "stop_topic" => ros.stop_topic = self.setting(value, TOPIC_USAGE, name),
                "cmd_vel" => {
                    let parse = |t: &str| match t {
                        "none" => Some(None),
                        t => is_ros_name(t).then(|| Some(t.to_owned())),
                    };
                    if let Some(topic) = self.setting(value, CMD_VEL_USAGE, parse) {
                        ros.cmd_vel = topic;
                    }
                }
                "tolerance" => {
                    let parse = |t: &str| {
                        t.parse::<f64>()
                            .ok()
                            .filter(|m| m.is_finite() && *m > 0.0 && *m <= 10.0)
                    };
                    if let Some(tolerance) = self.setting(value, TOLERANCE_USAGE, parse) {
                        ros.tolerance = tolerance;
                    }
                }
                "stall" => {
                    let parse = |t: &str| match crate::parse_duration(t) {
                        Some(d) if d.is_zero() => Some(None),
                        Some(d) if d.as_secs_f64() >= 1.0 => Some(Some(d)),
                        _ => None,
                    };
                    if let Some(stall) = self.setting(value, STALL_USAGE, parse) {
                        ros.stall = stall;
                    }
                }
                _ => ros.events = self.topic_events(value),
            }
        }
        if ros.url.is_none() && !node_names_key(node, "url") {
            let message = "This `rosbridge:` section has no `url`, so Docent would never \
                           connect and none of it would happen. Add the rosbridge server's \
                           address, e.g. `url: ws://robot.local:9090`.";
            self.diagnostics.push(Diagnostic::error(
                DiagnosticCode::RosbridgeUrlMissing,
                &node.pos,
                message,
            ));
        }
    }

    fn topic_events(&mut self, node: &Node) -> Vec<TopicEvent> {
        let items = match &node.kind {
            Kind::Seq(items) => items,
            Kind::Null => return Vec::new(),
            _ => {
                self.bad(node, EVENTS_USAGE);
                return Vec::new();
            }
        };
        let mut events: Vec<TopicEvent> = Vec::new();
        for item in items {
            let (mut topic, mut message_type, mut event) = (None, None, None);
            for (field, value) in self.entries(item, &EVENT) {
                match field.key {
                    "topic" => {
                        let parse = |t: &str| is_ros_name(t).then(|| t.to_owned());
                        topic = self.setting(value, TOPIC_USAGE, parse);
                        if let Some(t) = &topic
                            && events.iter().any(|e| &e.topic == t)
                        {
                            self.bad(value, "This topic is listed twice; keep one entry.");
                            topic = None;
                        }
                    }
                    "type" => {
                        let parse = |t: &str| is_message_type(t).then(|| t.to_owned());
                        message_type = self.setting(value, TYPE_USAGE, parse);
                    }
                    _ => {
                        let parse = |t: &str| Some(t.to_owned());
                        event = self.setting(value, "An event name.", parse);
                        if let Some(problem) = event.as_deref().and_then(robot_event_name_problem) {
                            self.bad(value, &format!("Not a robot event name: {problem}."));
                            event = None;
                        }
                    }
                }
            }
            match (topic, message_type, event) {
                (Some(topic), Some(message_type), Some(event)) => events.push(TopicEvent {
                    topic,
                    message_type,
                    event,
                }),
                // A wrong value was reported already; a key left out is reported here.
                (t, m, e) if matches!(item.kind, Kind::Map(_)) => {
                    let missing: Vec<&str> = [
                        ("topic", t.is_none()),
                        ("type", m.is_none()),
                        ("event", e.is_none()),
                    ]
                    .into_iter()
                    .filter(|(key, absent)| *absent && !node_names_key(item, key))
                    .map(|(key, _)| key)
                    .collect();
                    if !missing.is_empty() {
                        let message = format!(
                            "This event lacks `{}`. {EVENTS_USAGE}",
                            missing.join("`, `")
                        );
                        self.bad(item, &message);
                    }
                }
                _ => {}
            }
        }
        events
    }

    /// After the whole file is read: a rosbridge drive needs the link's address.
    pub(super) fn rosbridge_drive_needs_url(&mut self, drive: Option<&Node>, config: &SiteConfig) {
        if config.drive.adapter != AdapterKind::Rosbridge || config.rosbridge.url.is_some() {
            return;
        }
        let Some(adapter) = drive.and_then(|d| map_value(d, "adapter")) else {
            return;
        };
        let message = "`drive: adapter: rosbridge` needs the rosbridge server's address: add \
                       a `rosbridge:` section with its `url`, e.g. `rosbridge: {url: \
                       ws://robot.local:9090}`.";
        self.diagnostics.push(Diagnostic::error(
            DiagnosticCode::RosbridgeUrlMissing,
            &adapter.pos,
            message,
        ));
    }
}

fn map_value<'n>(node: &'n Node, key: &str) -> Option<&'n Node> {
    match &node.kind {
        Kind::Map(entries) => entries
            .iter()
            .find(|(k, _)| k.as_text() == Some(key))
            .map(|(_, v)| v),
        _ => None,
    }
}

/// Whether `node` is a mapping that writes `key` (a wrong value there was reported already).
fn node_names_key(node: &Node, key: &str) -> bool {
    map_value(node, key).is_some()
}
