//! The `NavigateToPose` action path against a stand-in rosbridge (a websocket server in the
//! test speaking the few rosbridge v2 operations involved): Nav2's `nav2_msgs` cannot be
//! installed on the test machines, so the real rosbridge cannot carry this action there. A
//! goal is sent as `send_action_goal`, its `action_result` ends the command (succeeded: done;
//! aborted: failed with the status), and a stop cancels the running goal.

use std::sync::Arc;

use futures_util::{SinkExt, StreamExt};
use serde_json::{Value, json};
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::oneshot;
use tokio_tungstenite::WebSocketStream;
use tokio_tungstenite::tungstenite::Message;

use super::RosbridgeDrive;
use crate::adapters::{Adapter, CancelScope, Command, Outcome, Reply};
use crate::content::config::RosbridgeConfig;
use crate::content::{Args, Verb};
use crate::events::{ActRef, Hub, LinkState, Source};
use crate::lifecycle::Lifecycle;
use crate::robot::RobotInbox;

const WAIT: std::time::Duration = std::time::Duration::from_secs(10);

fn command(id: u64, verb: Verb, args: Args) -> Command {
    let act = ActRef {
        trigger: id,
        source: Source::Http,
        client: None,
        reference: None,
        label: "TOUR".into(),
        at: "acts.yaml:1".into(),
    };
    Command {
        id,
        act: Arc::new(act),
        verb,
        arg: None,
        args: Arc::new(args),
    }
}

fn submit(drive: &RosbridgeDrive, hub: &Hub, command: Command) -> oneshot::Receiver<Outcome> {
    let (tx, rx) = oneshot::channel();
    drive.submit(command.clone(), Reply::new(hub.clone(), command, Some(tx)));
    rx
}

async fn outcome(rx: oneshot::Receiver<Outcome>) -> Outcome {
    tokio::time::timeout(WAIT, rx)
        .await
        .expect("in time")
        .expect("answered")
}

/// The next operation `op` the adapter sent, skipping others.
async fn next_op(ws: &mut WebSocketStream<TcpStream>, op: &str) -> Value {
    loop {
        let frame = tokio::time::timeout(WAIT, ws.next())
            .await
            .expect("in time");
        let Some(Ok(Message::Text(text))) = frame else {
            continue;
        };
        let value: Value = serde_json::from_str(&text).expect("JSON");
        if value["op"] == op {
            return value;
        }
    }
}

async fn result(ws: &mut WebSocketStream<TcpStream>, id: &Value, status: u64) {
    let op = json!({"op": "action_result", "action": "/navigate_to_pose", "id": id,
        "values": {}, "status": status, "result": status == 4});
    ws.send(Message::text(op.to_string())).await.expect("send");
}

#[tokio::test]
async fn a_navigate_to_pose_goal_ends_with_nav2s_result_and_a_stop_cancels_it() {
    let listener = TcpListener::bind("127.0.0.1:0").await.expect("bind");
    let url = format!("ws://{}", listener.local_addr().expect("addr"));
    let config = RosbridgeConfig {
        url: Some(url.clone()),
        action: Some("/navigate_to_pose".into()),
        cmd_vel: None,
        ..RosbridgeConfig::default()
    };
    let (hub, _feed) = Hub::new();
    let life = Lifecycle::new();
    let drive = RosbridgeDrive::start(&config, url, hub.clone(), RobotInbox::channel().0, &life);
    let (socket, _) = listener.accept().await.expect("the link connects");
    let mut ws = tokio_tungstenite::accept_async(socket)
        .await
        .expect("handshake");
    let subscribed = next_op(&mut ws, "subscribe").await;
    assert_eq!(subscribed["topic"], "/amcl_pose");
    let mut link = drive.shared.link.watch();
    link.wait_for(|s| s.state == LinkState::Up)
        .await
        .expect("up");

    let waypoint = Args::Waypoint {
        x: 3.0,
        y: 4.0,
        heading: Some(90.0),
    };
    let set = submit(&drive, &hub, command(1, Verb::SetWaypoint, waypoint));
    assert_eq!(outcome(set).await, Outcome::Done);

    // Succeeded: done.
    let done = submit(&drive, &hub, command(2, Verb::DriveStart, Args::None {}));
    let goal = next_op(&mut ws, "send_action_goal").await;
    assert_eq!(goal["action"], "/navigate_to_pose");
    assert_eq!(goal["action_type"], "nav2_msgs/action/NavigateToPose");
    let pose = &goal["args"]["pose"];
    assert_eq!(pose["header"]["frame_id"], "map");
    assert_eq!(
        pose["pose"]["position"],
        json!({"x": 3.0, "y": 4.0, "z": 0.0})
    );
    result(&mut ws, &goal["id"], 4).await;
    assert_eq!(outcome(done).await, Outcome::Done);

    // Aborted: failed, saying so.
    let aborted = submit(&drive, &hub, command(3, Verb::DriveStart, Args::None {}));
    let goal = next_op(&mut ws, "send_action_goal").await;
    result(&mut ws, &goal["id"], 6).await;
    assert_eq!(
        outcome(aborted).await,
        Outcome::Failed("Nav2 ended the goal without arriving (action status 6)".into())
    );

    // A stop cancels the running goal by its id.
    let stopped = submit(&drive, &hub, command(4, Verb::DriveStart, Args::None {}));
    let goal = next_op(&mut ws, "send_action_goal").await;
    drive.cancel(CancelScope::All, "stopped by the operator");
    assert_eq!(
        outcome(stopped).await,
        Outcome::Cancelled("stopped by the operator".into())
    );
    let cancel = next_op(&mut ws, "cancel_action_goal").await;
    assert_eq!(
        (&cancel["id"], &cancel["action"]),
        (&goal["id"], &json!("/navigate_to_pose"))
    );
    life.shutdown.cancel();
}
