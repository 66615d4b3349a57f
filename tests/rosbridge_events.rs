//! ROS topics become robot events through rosbridge: a real `rosbridge-server-rs` (`tests/ros/`),
//! each test in its own ROS domain and on its own port. A topic's message is a `robot` event
//! with its `topic` in the corpus; one too large is told once as `topic.refused`; and the
//! site's `reactions:` trigger the act a topic's message is mapped to.

use crate::common;
use crate::ros;

use std::time::Duration;

use common::TempBundle;
use ros::{ROS_DEADLINE, RosClient, RosSide, docent};
use serde_json::json;

const ACTS: &str = "\
- Label: HALT
  Text: [Wait here.]
  Cmds: [DRIVE_STOP]
";

#[tokio::test]
async fn a_ros_topic_message_becomes_a_robot_event_in_the_corpus() {
    let ros = RosSide::start(4, 1.0).await;
    let yaml = format!(
        "speech: {{adapter: log}}\nrosbridge:\n  url: {}\n  events:\n    - {{topic: \
         /asr/text, type: std_msgs/msg/String, event: asr.text}}\n",
        ros.url
    );
    let b = TempBundle::new(ACTS).with_file("docent.yaml", &yaml);
    let (server, mut op) = docent(&b).await;
    let mut asr = RosClient::connect(&ros.url).await.expect("connects");
    let event = tokio::time::timeout(ROS_DEADLINE, async {
        loop {
            let msg = json!({"data": "where is the exit"});
            asr.publish("/asr/text", "std_msgs/msg/String", msg).await;
            let seen = tokio::time::timeout(Duration::from_millis(500), op.event("robot")).await;
            if let Ok(event) = seen {
                return event;
            }
        }
    })
    .await
    .expect("the recogniser's message arrives");
    assert_eq!(event["event"], "asr.text");
    // A message too large for a robot event is told to operators, once for the topic.
    let huge = json!({"data": "x".repeat(5000)});
    for _ in 0..2 {
        asr.publish("/asr/text", "std_msgs/msg/String", huge.clone())
            .await;
    }
    let refused = op.event("topic.refused").await;
    assert_eq!(
        (&refused["topic"], &refused["event"]),
        (&json!("/asr/text"), &json!("asr.text"))
    );
    let reason = refused["reason"].as_str().unwrap();
    assert!(
        reason.contains("5011 bytes of JSON, over the 4096"),
        "{reason}"
    );
    let after = json!({"data": "thank you"});
    asr.publish("/asr/text", "std_msgs/msg/String", after).await;
    op.event_where(|e| e["type"] == "robot" && e["data"]["data"] == "thank you")
        .await;
    let all = server.stop().await;
    let told = all.iter().filter(|e| e["type"] == "topic.refused").count();
    assert_eq!(told, 1, "once per topic, not per message");
    let logged = all
        .iter()
        .find(|e| e["type"] == "robot")
        .expect("a robot event in the corpus");
    assert_eq!(logged["topic"], "/asr/text");
    assert_eq!(logged["event"], "asr.text");
    assert_eq!(logged["data"], json!({"data": "where is the exit"}));
    assert!(logged.get("client").is_none());
}

#[tokio::test]
async fn a_ros_topic_message_triggers_the_act_the_site_maps_it_to() {
    // A speech recogniser's std_msgs/String, through `rosbridge: events` and `reactions:`.
    let ros = RosSide::start(6, 1.0).await;
    let yaml = format!(
        "speech: {{adapter: log}}\nrosbridge:\n  url: {}\n  events:\n    - {{topic: /asr/text, \
         type: std_msgs/msg/String, event: asr.text}}\nreactions:\n  - {{event: asr.text, if: \
         data == \"goodbye\", act: HALT, cooldown: 1m}}\n",
        ros.url
    );
    let b = TempBundle::new(ACTS).with_file("docent.yaml", &yaml);
    let (_server, mut op) = docent(&b).await;
    let mut asr = RosClient::connect(&ros.url).await.expect("connects");
    let triggered = tokio::time::timeout(ROS_DEADLINE, async {
        loop {
            let msg = json!({"data": "goodbye"});
            asr.publish("/asr/text", "std_msgs/msg/String", msg).await;
            let seen = tokio::time::timeout(
                Duration::from_millis(500),
                op.event_where(|e| e["type"] == "act.triggered"),
            )
            .await;
            if let Ok(event) = seen {
                return event;
            }
        }
    })
    .await
    .expect("the reaction triggers its act");
    assert_eq!(
        (&triggered["label"], &triggered["source"]),
        (&json!("HALT"), &json!("robot"))
    );
}
