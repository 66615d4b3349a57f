//! Docent drives a ROS 2 robot through rosbridge: a real `rosbridge-server-rs` and a real rclpy
//! simulated base (`tests/ros/`), each test in its own ROS domain and on its own ports. A tour
//! act drives the base to its waypoint and goes on when it arrives; `DRIVE_STOP` and Stop halt
//! it; killing rosbridge fails the drive with the reason, and the link comes back by itself
//! with its subscriptions; a drive that gets nowhere fails (`rosbridge_events.rs` has the topics).
//! Run with `--nocapture` to see the measured times.

use crate::common;
use crate::ros;

use std::time::{Duration, Instant};

use common::load::{each_once, keep_triggering};
use common::{TempBundle, TestServer, WsClient};
use ros::{ROS_DEADLINE, RosClient, RosSide, docent};
use serde_json::{Value, json};
use tokio_util::sync::CancellationToken;

const ACTS: &str = "\
- Label: TOUR
  Text: [Follow me.]
  Cmds: [SET_WAYPOINT 2 1, DRIVE_START, WAIT, SAY Here we are.]
- Label: HOME
  Text: [Back.]
  Cmds: [SET_WAYPOINT 0 0, DRIVE_START]
- Label: FAR
  Text: [A long way.]
  Cmds: [SET_WAYPOINT 40 0, DRIVE_START]
- Label: HALT
  Text: [Wait here.]
  Cmds: [DRIVE_STOP]
- Label: CHAT
  Text: [Nice weather.]
";

fn bundle(ros: &RosSide, extra: &str) -> TempBundle {
    let yaml = format!(
        "speech: {{adapter: log}}\ndrive: {{adapter: rosbridge}}\nrosbridge:\n  url: {}\n  \
         stop_topic: /docent/stop\n  tolerance: 0.05\n{extra}",
        ros.url
    );
    TempBundle::new(ACTS).with_file("docent.yaml", &yaml)
}

/// A client of the test's own on `/sim/log`, where the base tells each goal and stop; matched
/// (the base's heartbeat arrived) before it is returned, as a fresh ROS subscription misses
/// what is published before discovery matches it.
async fn sim_log(ros: &RosSide) -> RosClient {
    let mut client = RosClient::connect(&ros.url).await.expect("connects");
    client.subscribe("/sim/log", "std_msgs/msg/String").await;
    log_entry(&mut client, "alive").await;
    client
}

async fn log_entry(log: &mut RosClient, key: &str) -> Value {
    let msg = log
        .next_where("/sim/log", ROS_DEADLINE, |m| {
            serde_json::from_str::<Value>(m["data"].as_str().unwrap_or("{}"))
                .is_ok_and(|e| e.get(key).is_some())
        })
        .await;
    serde_json::from_str(msg["data"].as_str().expect("text")).expect("JSON")
}

/// Waits until the base reports the same position `n` times running: it stands still.
async fn stands_still(ros: &RosSide, n: usize) -> (f64, f64) {
    let mut client = RosClient::connect(&ros.url).await.expect("connects");
    let kind = "geometry_msgs/msg/PoseWithCovarianceStamped";
    client.subscribe("/amcl_pose", kind).await;
    let (mut last, mut same) = ((f64::NAN, f64::NAN), 0);
    tokio::time::timeout(ROS_DEADLINE, async {
        loop {
            let msg = client.next_on("/amcl_pose").await.expect("open");
            let p = &msg["pose"]["pose"]["position"];
            let at = (p["x"].as_f64().unwrap(), p["y"].as_f64().unwrap());
            same = if at == last { same + 1 } else { 0 };
            last = at;
            if same >= n {
                return at;
            }
        }
    })
    .await
    .expect("the base stands still")
}

/// The first event matching each predicate, in whatever order they come.
async fn all_of<const N: usize>(
    op: &mut WsClient,
    preds: [&dyn Fn(&Value) -> bool; N],
) -> [Value; N] {
    let mut found: [Option<Value>; N] = std::array::from_fn(|_| None);
    while found.iter().any(Option::is_none) {
        let event = op.recv_type("event").await["event"].clone();
        for (pred, slot) in preds.iter().zip(found.iter_mut()) {
            if slot.is_none() && pred(&event) {
                *slot = Some(event.clone());
            }
        }
    }
    found.map(|f| f.expect("found"))
}

fn percentiles(ms: &[f64]) -> String {
    let mut ms = ms.to_vec();
    ms.sort_by(f64::total_cmp);
    format!(
        "p50 {:.1} ms, max {:.1} ms over {} runs",
        ms[ms.len() / 2],
        ms[ms.len() - 1],
        ms.len()
    )
}

#[tokio::test]
async fn a_tour_act_drives_the_base_to_its_waypoint_and_goes_on_when_it_arrives() {
    let ros = RosSide::start(1, 2.0).await;
    let b = bundle(&ros, "");
    let (server, mut op) = docent(&b).await;
    let mut goals = RosClient::connect(&ros.url).await.expect("connects");
    goals
        .subscribe("/goal_pose", "geometry_msgs/msg/PoseStamped")
        .await;
    let mut latencies = Vec::new();
    for leg in 0..4 {
        // Back and forth between (2, 1) and the origin, timing each goal's way to ROS.
        let label = if leg % 2 == 0 { "TOUR" } else { "HOME" };
        let asked = Instant::now();
        server.trigger(label, json!({})).await;
        let goal = goals.next_where("/goal_pose", ROS_DEADLINE, |_| true).await;
        latencies.push(asked.elapsed().as_secs_f64() * 1000.0);
        assert_eq!(goal["header"]["frame_id"], "map");
        let arrived = op.event("drive.arrived").await;
        let want = if label == "TOUR" {
            (2.0, 1.0)
        } else {
            (0.0, 0.0)
        };
        assert!(
            (arrived["x"].as_f64().unwrap() - want.0).abs() < 0.05
                && (arrived["y"].as_f64().unwrap() - want.1).abs() < 0.05,
            "{arrived}"
        );
        if label == "TOUR" {
            let done = op
                .event_where(|e| e["type"] == "command.done" && e["verb"] == "DRIVE_START")
                .await;
            assert_eq!(done["label"], "TOUR");
            // After the WAIT: the act's next step starts only now.
            let say = op
                .event_where(|e| e["type"] == "command.sent" && e["verb"] == "SAY")
                .await;
            assert_eq!(say["arg"], "Here we are.");
            assert!(say["seq"].as_u64() > done["seq"].as_u64());
        }
    }
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["robot_link"]["state"], "up");
    assert_eq!(state["pose"]["moving"], false);
    eprintln!(
        "SET_WAYPOINT + DRIVE_START to the goal on /goal_pose: {}",
        percentiles(&latencies)
    );
}

#[tokio::test]
async fn drive_stop_and_stop_halt_the_base() {
    let ros = RosSide::start(2, 1.0).await;
    let b = bundle(&ros, "");
    let (server, mut op) = docent(&b).await;
    let mut log = sim_log(&ros).await;
    for how in ["DRIVE_STOP", "Stop"] {
        server.trigger("FAR", json!({})).await;
        log_entry(&mut log, "goal").await;
        // On its way: moving, and past where it started (a busy machine can report the
        // start before the first step).
        op.event_where(|e| {
            e["type"] == "pose" && e["moving"] == true && e["x"].as_f64().is_some_and(|x| x > 0.0)
        })
        .await;
        if how == "DRIVE_STOP" {
            server.trigger("HALT", json!({})).await;
        } else {
            let (status, body) = server.post("/api/stop", None).await;
            assert!(status < 300, "{status} {body}");
        }
        let cancelled = op
            .event_where(|e| e["type"] == "command.cancelled" && e["verb"] == "DRIVE_START")
            .await;
        assert_eq!(cancelled["label"], "FAR", "{how}");
        let stop = log_entry(&mut log, "stop").await;
        assert!(["stop", "cmd_vel"].contains(&stop["stop"].as_str().unwrap()));
        let (x, _) = stands_still(&ros, 10).await;
        assert!(x > 0.0 && x < 39.0, "{how}: halted on the way, at x {x}");
        let halted = op
            .event_where(|e| e["type"] == "pose" && e["moving"] == false)
            .await;
        assert!(halted["x"].as_f64().unwrap() > 0.0);
    }
}

#[tokio::test]
async fn a_drive_replaced_by_another_acts_drive_goes_to_the_new_waypoint() {
    let ros = RosSide::start(5, 2.0).await;
    let b = bundle(&ros, "");
    let (server, mut op) = docent(&b).await;
    let mut log = sim_log(&ros).await;
    server.trigger("FAR", json!({})).await;
    log_entry(&mut log, "goal").await;
    // The drive channel replaces: FAR's drive ends, and TOUR's goal preempts it without a stop
    // that could overtake the new goal on its way to the robot.
    server.trigger("TOUR", json!({})).await;
    let cancelled = op
        .event_where(|e| e["type"] == "command.cancelled" && e["verb"] == "DRIVE_START")
        .await;
    assert_eq!(cancelled["label"], "FAR");
    let goal = log_entry(&mut log, "goal").await;
    assert_eq!(goal["goal"], json!([2.0, 1.0]));
    let done = op
        .event_where(|e| e["type"] == "command.done" && e["verb"] == "DRIVE_START")
        .await;
    assert_eq!(done["label"], "TOUR");
}

#[tokio::test]
async fn a_lost_link_fails_the_drive_and_comes_back_with_its_subscriptions() {
    let mut ros = RosSide::start(3, 1.0).await;
    let b = bundle(
        &ros,
        "  events: [{topic: /bumper, type: std_msgs/msg/String, event: bumper}]\n",
    );
    let (server, mut op) = docent(&b).await;
    let (mut linked, mut back) = (Vec::new(), Vec::new());
    // A dialog manager keeps triggering all along: nothing it was answered may be lost.
    let stop_load = CancellationToken::new();
    let load = tokio::spawn(keep_triggering(
        server.addr.to_string(),
        "CHAT",
        stop_load.clone(),
    ));
    for run in 0..3 {
        let mut log = sim_log(&ros).await;
        server.trigger("FAR", json!({})).await;
        log_entry(&mut log, "goal").await;
        ros.kill_rosbridge();
        // Both are told, in whichever order the link and the drive get to it.
        let [failed, down] = all_of(
            &mut op,
            [
                &|e: &Value| e["type"] == "command.failed" && e["verb"] == "DRIVE_START",
                &|e: &Value| e["type"] == "robot.link" && e["state"] == "down",
            ],
        )
        .await;
        let reason = failed["reason"].as_str().unwrap();
        let lost = format!("the link to rosbridge at {} was lost: ", ros.url);
        assert!(reason.starts_with(&lost), "{reason}");
        assert_eq!(down["url"], json!(ros.url));
        assert!(down["reason"].as_str().is_some_and(|r| !r.is_empty()));
        let (_, state) = server.get("/api/state").await;
        assert_eq!(state["robot_link"]["state"], "down");
        // Rosbridge returns on its port: the link is back by itself, its subscriptions too.
        let returned = ros.restart_rosbridge().await;
        op.event_where(|e| e["type"] == "robot.link" && e["state"] == "up")
            .await;
        linked.push(returned.elapsed().as_secs_f64() * 1000.0);
        op.event("pose").await;
        back.push(returned.elapsed().as_secs_f64() * 1000.0);
        // The stop held while the link was down reached the base: it stands.
        stands_still(&ros, 10).await;
        // A message published after the restart arrives as a robot event.
        let mut bumper = RosClient::connect(&ros.url).await.expect("connects");
        let text = format!("hit {run}");
        let event = tokio::time::timeout(ROS_DEADLINE, async {
            loop {
                let msg = json!({"data": text});
                bumper.publish("/bumper", "std_msgs/msg/String", msg).await;
                let seen = tokio::time::timeout(
                    Duration::from_millis(500),
                    op.event_where(|e| e["type"] == "robot" && e["data"]["data"] == text),
                )
                .await;
                if let Ok(event) = seen {
                    return event;
                }
            }
        })
        .await
        .expect("the bumper's message arrives");
        assert_eq!(event["topic"], "/bumper");
    }
    stop_load.cancel();
    let answered = load.await.expect("the load ran");
    eprintln!(
        "{} triggers answered through three rosbridge restarts",
        answered.len()
    );
    each_once(&answered, &server.stop().await);
    eprintln!(
        "rosbridge back on its port to the link up again: {}",
        percentiles(&linked)
    );
    eprintln!(
        "rosbridge back on its port to live subscriptions (a pose reached the console): {}",
        percentiles(&back)
    );
    // Docent's part: the link is back within the aim of 5 s. The first message through the
    // new subscriptions also waits for the restarted rosbridge's ROS side (type support, DDS
    // discovery), 2.5 to 3.4 s here: bounded loosely, so that a loaded machine does not fail it.
    assert!(linked.iter().all(|ms| *ms < 5000.0), "{linked:?}");
    assert!(back.iter().all(|ms| *ms < 10_000.0), "{back:?}");
}

#[tokio::test]
async fn a_drive_while_rosbridge_is_unreachable_fails_at_once_with_the_reason() {
    // Nothing listens on this port: the link is down from the start, and says why.
    let url = format!("ws://127.0.0.1:{}", ros::free_port());
    let yaml = format!(
        "speech: {{adapter: log}}\ndrive: {{adapter: rosbridge}}\nrosbridge: {{url: \"{url}\"}}\n"
    );
    let b = TempBundle::new(ACTS).with_file("docent.yaml", &yaml);
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let down = op.event("robot.link").await;
    assert_eq!(
        (&down["state"], &down["url"]),
        (&json!("down"), &json!(url))
    );
    assert!(
        down["reason"]
            .as_str()
            .unwrap()
            .starts_with("cannot connect: "),
        "{down}"
    );
    server.trigger("FAR", json!({})).await;
    let failed = op
        .event_where(|e| e["type"] == "command.failed" && e["verb"] == "DRIVE_START")
        .await;
    let reason = failed["reason"].as_str().unwrap();
    assert!(
        reason.starts_with(&format!(
            "the link to rosbridge at {url} is down: cannot connect: "
        )) && reason.ends_with("; the robot was not sent anywhere"),
        "{reason}"
    );
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["robot_link"]["state"], "down");
    assert_eq!(
        state["pose"],
        Value::Null,
        "no pose before the robot's first"
    );
}

#[tokio::test]
async fn a_drive_that_gets_nowhere_fails_after_the_stall_time_and_stops_the_robot() {
    // The goal goes to a topic no base listens to, as when Nav2 drops a goal without a word:
    // the robot never comes closer, and the drive must not wait for ever.
    let ros = RosSide::start(7, 1.0).await;
    let b = bundle(&ros, "  goal_topic: /nobody_listens\n  stall: 1s\n");
    let (server, mut op) = docent(&b).await;
    let mut log = sim_log(&ros).await;
    let started = Instant::now();
    server.trigger("FAR", json!({})).await;
    let failed = op
        .event_where(|e| e["type"] == "command.failed" && e["verb"] == "DRIVE_START")
        .await;
    let waited = started.elapsed();
    let reason = failed["reason"].as_str().unwrap();
    assert!(
        reason.starts_with("the robot came no closer to (40, 0) for 1 s and is still 40.00 m away")
            && reason.contains("it was told to stop"),
        "{reason}"
    );
    assert!(waited >= Duration::from_secs(1), "{waited:?}");
    let stop = log_entry(&mut log, "stop").await;
    assert!(["stop", "cmd_vel"].contains(&stop["stop"].as_str().unwrap()));
    server.stop().await;
}
