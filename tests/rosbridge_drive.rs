//! Docent drives a ROS 2 robot through rosbridge: a real `rosbridge-server-rs` and a real rclpy
//! simulated base (`tests/ros/`), each test in its own ROS domain and on its own ports.

mod common;
#[path = "ros/harness.rs"]
mod ros;

use ros::{RosClient, RosSide};

#[tokio::test]
async fn the_ros_side_comes_up_and_the_base_reports_its_pose() {
    let ros = RosSide::start(1, 1.0).await;
    let pose = ros.await_pose().await;
    assert_eq!(pose["header"]["frame_id"], "map");
    let mut client = RosClient::connect(&ros.url).await.expect("connects");
    client.subscribe("/sim/log", "std_msgs/msg/String").await;
    client
        .publish(
            "/goal_pose",
            "geometry_msgs/msg/PoseStamped",
            serde_json::json!({"header": {"frame_id": "map"}, "pose": {"position": {"x": 1.0, "y": 0.0, "z": 0.0}, "orientation": {"w": 1.0}}}),
        )
        .await;
    let log = client
        .next_where("/sim/log", ros::ROS_DEADLINE, |m| {
            m["data"].as_str().is_some_and(|d| d.contains("goal"))
        })
        .await;
    assert!(log["data"].as_str().unwrap().contains("[1.0, 0.0]"), "{log}");
}
