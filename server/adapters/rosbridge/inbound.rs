//! What each message from rosbridge becomes: the pose topic's messages the robot's pose (every
//! one judged for arrival, `pose` events thinned to one per [`POSE_EVENT_GAP`] unless moving
//! changes), a listed topic's messages robot events handed to the [`RobotInbox`], an action's
//! result the drive's. A message that cannot be used (larger than a robot event may be, a
//! pose without a position, an inbox full) is told to operators once per topic as
//! `topic.refused`.

use std::sync::Arc;
use std::time::{Duration, Instant};

use serde_json::Value;

use super::link::Inbound;
use super::{Robot, messages};
use crate::adapters::drive_sim::Pose;
use crate::events::{EventKind, TopicRefused};
use crate::robot::{RobotNotice, RobotOrigin};
use crate::sync::lock;
use crate::ws::ROBOT_DATA_BYTES;

/// The shortest time between two `pose` events: a 50 Hz `/odom` would flood the log.
pub(super) const POSE_EVENT_GAP: Duration = Duration::from_millis(100);

/// The link's handler for everything arriving.
pub(super) fn handler(robot: Arc<Robot>) -> impl Fn(Inbound) + Send + Sync + 'static {
    move |inbound| match inbound {
        Inbound::Message { topic, msg } => {
            if topic == robot.config.pose_topic {
                pose(&robot, &msg);
            }
            let event = robot.config.events.iter().find(|e| e.topic == topic);
            if let Some(event) = event {
                robot_event(&robot, &topic, &event.event, msg);
            }
        }
        Inbound::ActionResult { id, status } => {
            robot.results.send_replace(Some((id, status)));
        }
    }
}

fn pose(robot: &Robot, msg: &Value) {
    let Some((x, y, heading)) = messages::pose_of(robot.config.pose_type, msg) else {
        let topic = &robot.config.pose_topic;
        let kind = robot.config.pose_type.type_name();
        let reason = format!(
            "a message on the pose topic has no position where a {kind} has it, so the \
             robot's pose is unknown and drives cannot arrive: check `rosbridge: pose_type` \
             against the topic's type (`ros2 topic info {topic}`)"
        );
        refused(robot, topic, None, reason);
        return;
    };
    let event = {
        let mut state = lock(&robot.state);
        let moving = state.moving;
        let pose = Pose {
            x,
            y,
            heading,
            moving,
        };
        let changed = state.pose.is_none_or(|p| p.moving != moving);
        let due = state
            .last_pose_event
            .is_none_or(|t| t.elapsed() >= POSE_EVENT_GAP);
        state.pose = Some(pose);
        (changed || due).then(|| {
            state.last_pose_event = Some(Instant::now());
            pose
        })
    };
    robot.poses.send_modify(|n| *n += 1);
    if let Some(pose) = event {
        robot.publish_pose(pose);
    }
}

/// The notice a message on `topic` becomes, or its size in bytes when it is too large to be a
/// robot event's `data`.
fn notice_for(topic: &str, event: &str, data: Value) -> Result<RobotNotice, usize> {
    let size = serde_json::to_vec(&data).map_or(usize::MAX, |v| v.len());
    if size > ROBOT_DATA_BYTES {
        return Err(size);
    }
    Ok(RobotNotice {
        event: event.to_owned(),
        data,
        origin: RobotOrigin::Topic {
            topic: topic.to_owned(),
        },
    })
}

fn robot_event(robot: &Robot, topic: &str, event: &str, data: Value) {
    let notice = match notice_for(topic, event, data) {
        Ok(notice) => notice,
        Err(size) => {
            let reason = format!(
                "a message on this topic is {size} bytes of JSON, over the {ROBOT_DATA_BYTES} a \
                 robot event may carry; it is not logged (nor are later ones, without another \
                 word): map a smaller topic, or republish a summary of it on the robot"
            );
            return refused(robot, topic, Some(event), reason);
        }
    };
    if let Err(full) = robot.inbox.send(notice) {
        refused(robot, topic, Some(event), full.to_string());
    }
}

/// Tells operators (a `topic.refused` event, in the corpus and the console's history) and the
/// server log that messages on `topic` cannot be used, once per topic and event: a sensor
/// mapped wrongly must not go quiet without a word, nor flood the log at its own rate.
fn refused(robot: &Robot, topic: &str, event: Option<&str>, reason: String) {
    let key = format!("{topic} {}", event.unwrap_or("pose"));
    if !lock(&robot.state).refusals_told.insert(key) {
        return;
    }
    tracing::warn!(topic, event, "{reason}");
    robot.hub.publish(EventKind::TopicRefused(TopicRefused {
        topic: topic.to_owned(),
        event: event.map(str::to_owned),
        reason,
    }));
}

#[cfg(test)]
mod tests {
    use serde_json::json;

    use super::*;

    #[test]
    fn a_message_becomes_a_notice_from_its_topic_unless_it_is_too_large() {
        let small = json!({"data": "where is the exit"});
        let notice = notice_for("/asr/text", "asr.text", small.clone()).expect("small enough");
        assert_eq!(notice.event, "asr.text");
        assert_eq!(notice.data, small);
        assert_eq!(
            notice.origin,
            RobotOrigin::Topic {
                topic: "/asr/text".into()
            }
        );
        // `{"data":"…"}` is 11 bytes around the text.
        let fits = json!({"data": "x".repeat(ROBOT_DATA_BYTES - 11)});
        assert!(notice_for("/t", "e", fits).is_ok());
        let over = json!({"data": "x".repeat(ROBOT_DATA_BYTES - 10)});
        assert_eq!(
            notice_for("/t", "e", over).err(),
            Some(ROBOT_DATA_BYTES + 1)
        );
    }
}
