//! The rosbridge v2 operations Docent sends (advertise, subscribe, publish, send and cancel an
//! action goal) and what it reads out of the messages it receives: a pose from a
//! `PoseWithCovarianceStamped`, `Odometry` or `PoseStamped`, a heading from a quaternion.
//! Plain JSON in and out, so that all of it is unit-tested without a robot.

use serde_json::{Value, json};

use crate::content::config::PoseMessage;

/// Nav2's action type, for `send_action_goal`.
pub const NAVIGATE_TO_POSE: &str = "nav2_msgs/action/NavigateToPose";
/// `action_msgs/msg/GoalStatus`: the goal succeeded.
pub const GOAL_SUCCEEDED: u64 = 4;

/// `advertise`: Docent will publish `kind` messages on `topic`.
pub fn advertise(topic: &str, kind: &str) -> Value {
    json!({"op": "advertise", "topic": topic, "type": kind})
}

/// `subscribe`: send Docent every message on `topic`, the latest one first when it is slow.
pub fn subscribe(topic: &str, kind: &str) -> Value {
    json!({"op": "subscribe", "topic": topic, "type": kind, "queue_length": 1})
}

/// `publish` `msg` on `topic`.
pub fn publish(topic: &str, msg: Value) -> Value {
    json!({"op": "publish", "topic": topic, "msg": msg})
}

/// A `geometry_msgs/msg/PoseStamped` at `(x, y)` facing `heading_degrees` in `frame`. The stamp
/// is zero: "the latest transform", since Docent's clock is not the robot's.
pub fn pose_stamped(frame: &str, x: f64, y: f64, heading_degrees: f64) -> Value {
    let half = heading_degrees.to_radians() / 2.0;
    json!({
        "header": {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": frame},
        "pose": {
            "position": {"x": x, "y": y, "z": 0.0},
            "orientation": {"x": 0.0, "y": 0.0, "z": half.sin(), "w": half.cos()},
        },
    })
}

/// `send_action_goal` for Nav2's `NavigateToPose` on `action`, to `pose`.
pub fn navigate_to_pose(id: &str, action: &str, pose: Value) -> Value {
    json!({
        "op": "send_action_goal",
        "id": id,
        "action": action,
        "action_type": NAVIGATE_TO_POSE,
        "args": {"pose": pose, "behavior_tree": ""},
        "feedback": false,
    })
}

/// `cancel_action_goal` for goal `id` on `action`.
pub fn cancel_action_goal(id: &str, action: &str) -> Value {
    json!({"op": "cancel_action_goal", "id": id, "action": action})
}

/// A zero `geometry_msgs/msg/Twist`: stand still.
pub fn zero_twist() -> Value {
    let zero = json!({"x": 0.0, "y": 0.0, "z": 0.0});
    json!({"linear": zero, "angular": zero})
}

/// Where a message of type `kind` says the robot is: `(x, y, heading in degrees)`.
pub fn pose_of(kind: PoseMessage, msg: &Value) -> Option<(f64, f64, f64)> {
    let pose = match kind {
        PoseMessage::PoseWithCovarianceStamped | PoseMessage::Odometry => &msg["pose"]["pose"],
        PoseMessage::PoseStamped => &msg["pose"],
    };
    let p = &pose["position"];
    let q = &pose["orientation"];
    let number = |v: &Value| v.as_f64();
    let (x, y) = (number(&p["x"])?, number(&p["y"])?);
    let [qx, qy, qz, qw] = [&q["x"], &q["y"], &q["z"], &q["w"]].map(|v| number(v).unwrap_or(0.0));
    Some((x, y, heading_degrees(qx, qy, qz, qw)))
}

/// The yaw of quaternion `(x, y, z, w)`, in degrees counter-clockwise from the x axis.
pub fn heading_degrees(x: f64, y: f64, z: f64, w: f64) -> f64 {
    let yaw = (2.0 * (w * z + x * y)).atan2(1.0 - 2.0 * (y * y + z * z));
    yaw.to_degrees()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_heading_goes_into_a_goal_and_comes_back_out_of_a_pose() {
        for heading in [0.0, 45.0, 90.0, -90.0, 179.0, -135.0] {
            let goal = pose_stamped("map", 1.5, -2.0, heading);
            assert_eq!(goal["header"]["frame_id"], "map");
            let (x, y, back) =
                pose_of(PoseMessage::PoseStamped, &goal).expect("a PoseStamped has a pose");
            assert_eq!((x, y), (1.5, -2.0));
            assert!(
                (back - heading).abs() < 1e-9,
                "{heading} came back as {back}"
            );
        }
    }

    #[test]
    fn the_pose_is_read_where_each_message_type_keeps_it() {
        let inner = pose_stamped("map", 3.0, 4.0, 90.0)["pose"].clone();
        let amcl = json!({"header": {}, "pose": {"pose": inner, "covariance": []}});
        let odom = json!({"header": {}, "child_frame_id": "base_link", "pose": {"pose": inner}});
        for (kind, msg) in [
            (PoseMessage::PoseWithCovarianceStamped, &amcl),
            (PoseMessage::Odometry, &odom),
        ] {
            let (x, y, heading) = pose_of(kind, msg).expect("pose");
            assert_eq!((x, y), (3.0, 4.0));
            assert!((heading - 90.0).abs() < 1e-9);
        }
        assert_eq!(pose_of(PoseMessage::Odometry, &json!({"data": 1})), None);
    }

    #[test]
    fn operations_follow_rosbridge_v2() {
        assert_eq!(
            advertise("/cmd_vel", "geometry_msgs/msg/Twist"),
            json!({"op": "advertise", "topic": "/cmd_vel", "type": "geometry_msgs/msg/Twist"})
        );
        let goal = navigate_to_pose("g1", "/navigate_to_pose", json!({}));
        assert_eq!(goal["op"], "send_action_goal");
        assert_eq!(goal["action_type"], NAVIGATE_TO_POSE);
        assert_eq!(
            cancel_action_goal("g1", "/navigate_to_pose"),
            json!({"op": "cancel_action_goal", "id": "g1", "action": "/navigate_to_pose"})
        );
        assert_eq!(zero_twist()["angular"]["z"], 0.0);
    }
}
