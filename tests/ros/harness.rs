//! The ROS 2 side of a rosbridge test: `rosbridge-server-rs` on a free loopback port and the
//! rclpy simulated base (`tests/ros/sim_base.py`), both in the test's own `ROS_DOMAIN_ID` out
//! of `tests/ros/.venv` (made by `scripts/install-test-deps.sh`), killed when dropped. Ready
//! means a pose message from the base reached a websocket client through rosbridge: polled
//! with a deadline, never slept for.

#![allow(dead_code)] // Each rosbridge test binary uses a different part.

use std::net::TcpListener;
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use futures_util::{SinkExt, StreamExt};
use serde_json::{Value, json};
use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::{MaybeTlsStream, WebSocketStream, connect_async};

/// How long the ROS side may take to come up (DDS discovery included).
pub const ROS_DEADLINE: Duration = Duration::from_secs(30);

fn ros_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/ros")
}

/// A command run through `tests/ros/run.sh` (which `exec`s it: the child's id is its own).
fn ros_command(domain: u32, program: &str, args: &[&str]) -> Command {
    let run = ros_dir().join("run.sh");
    assert!(
        ros_dir().join(".venv/bin/python").exists(),
        "tests/ros/.venv is missing: run scripts/install-test-deps.sh"
    );
    let mut command = Command::new(run);
    command
        .arg(program)
        .args(args)
        .env("ROS_DOMAIN_ID", domain.to_string())
        .current_dir(ros_dir())
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null());
    command
}

/// A free loopback port (bound, read and released: rosbridge binds it next).
pub fn free_port() -> u16 {
    let listener = TcpListener::bind("127.0.0.1:0").expect("bind");
    listener.local_addr().expect("addr").port()
}

/// A ROS domain id no other test of this run uses: from the process id and a counter, within
/// ROS 2's usable 0..=101 (Fast DDS maps the id onto ports).
pub fn domain_id(test: u32) -> u32 {
    (std::process::id() * 7 + test * 13) % 100 + 1
}

/// rosbridge and the simulated base, killed on drop.
pub struct RosSide {
    /// `ws://127.0.0.1:PORT`.
    pub url: String,
    /// The bound port (kept when rosbridge restarts).
    pub port: u16,
    /// The ROS domain id.
    pub domain: u32,
    rosbridge: Option<Child>,
    base: Option<Child>,
}

/// Starts rosbridge on `port`.
fn spawn_rosbridge(domain: u32, port: u16) -> Child {
    let bind = format!("127.0.0.1:{port}");
    ros_command(
        domain,
        "rosbridge-server-rs",
        &["--bind", &bind, "--no-rosapi"],
    )
    .spawn()
    .expect("rosbridge-server-rs starts")
}

impl RosSide {
    /// rosbridge and a base publishing `/amcl_pose`, driving at `speed` m/s, ready.
    pub async fn start(test: u32, speed: f64) -> Self {
        let domain = domain_id(test);
        let port = free_port();
        let speed = speed.to_string();
        let base = ros_command(domain, "python", &["sim_base.py", "--speed", &speed])
            .spawn()
            .expect("the simulated base starts");
        let ros = RosSide {
            url: format!("ws://127.0.0.1:{port}"),
            port,
            domain,
            rosbridge: Some(spawn_rosbridge(domain, port)),
            base: Some(base),
        };
        ros.await_pose().await;
        ros
    }

    /// Kills rosbridge (as a crash would: SIGKILL), leaving the base running.
    pub fn kill_rosbridge(&mut self) {
        if let Some(mut child) = self.rosbridge.take() {
            let _ = child.kill();
            let _ = child.wait();
        }
    }

    /// Starts rosbridge again on the same port; returns when it accepts connections.
    pub async fn restart_rosbridge(&mut self) -> Instant {
        self.rosbridge = Some(spawn_rosbridge(self.domain, self.port));
        let start = Instant::now();
        while TcpStream::connect(("127.0.0.1", self.port)).await.is_err() {
            assert!(
                start.elapsed() < ROS_DEADLINE,
                "rosbridge did not come back"
            );
            tokio::task::yield_now().await;
            tokio::time::sleep(Duration::from_millis(5)).await;
        }
        Instant::now()
    }

    /// Waits until a pose from the base comes through rosbridge.
    pub async fn await_pose(&self) -> Value {
        let start = Instant::now();
        loop {
            assert!(
                start.elapsed() < ROS_DEADLINE,
                "no pose from the simulated base through rosbridge at {}",
                self.url
            );
            let Ok(mut client) = RosClient::connect(&self.url).await else {
                tokio::time::sleep(Duration::from_millis(20)).await;
                continue;
            };
            client
                .subscribe("/amcl_pose", "geometry_msgs/msg/PoseWithCovarianceStamped")
                .await;
            if let Ok(Some(msg)) =
                tokio::time::timeout(Duration::from_secs(3), client.next_on("/amcl_pose")).await
            {
                return msg;
            }
        }
    }
}

impl Drop for RosSide {
    fn drop(&mut self) {
        for child in [self.rosbridge.take(), self.base.take()]
            .into_iter()
            .flatten()
        {
            let mut child = child;
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

/// A bare rosbridge v2 client: what a test uses to see and publish on ROS topics.
pub struct RosClient {
    stream: WebSocketStream<MaybeTlsStream<TcpStream>>,
}

impl RosClient {
    /// Connects to `url`.
    pub async fn connect(url: &str) -> Result<Self, String> {
        let (stream, _) = connect_async(url).await.map_err(|e| e.to_string())?;
        Ok(RosClient { stream })
    }

    /// Sends one rosbridge operation.
    pub async fn send(&mut self, op: Value) {
        self.stream
            .send(Message::text(op.to_string()))
            .await
            .expect("send to rosbridge");
    }

    /// Subscribes to `topic`.
    pub async fn subscribe(&mut self, topic: &str, kind: &str) {
        self.send(json!({"op": "subscribe", "topic": topic, "type": kind}))
            .await;
    }

    /// Advertises `topic` and publishes `msg` on it.
    pub async fn publish(&mut self, topic: &str, kind: &str, msg: Value) {
        self.send(json!({"op": "advertise", "topic": topic, "type": kind}))
            .await;
        self.send(json!({"op": "publish", "topic": topic, "msg": msg}))
            .await;
    }

    /// The next message on `topic`; `None` when the connection ends.
    pub async fn next_on(&mut self, topic: &str) -> Option<Value> {
        while let Some(frame) = self.stream.next().await {
            let Ok(Message::Text(text)) = frame else {
                if frame.is_err() {
                    return None;
                }
                continue;
            };
            let op: Value = serde_json::from_str(&text).ok()?;
            if op["op"] == "publish" && op["topic"] == topic {
                return Some(op["msg"].clone());
            }
        }
        None
    }

    /// The next message on `topic` matching `pred`, within `deadline`.
    pub async fn next_where(
        &mut self,
        topic: &str,
        deadline: Duration,
        pred: impl Fn(&Value) -> bool,
    ) -> Value {
        tokio::time::timeout(deadline, async {
            loop {
                let msg = self
                    .next_on(topic)
                    .await
                    .expect("rosbridge connection open");
                if pred(&msg) {
                    return msg;
                }
            }
        })
        .await
        .unwrap_or_else(|_| panic!("no matching message on {topic} within {deadline:?}"))
    }
}

/// Docent serving `b` and an operator that saw the link come up.
pub async fn docent(
    b: &crate::common::TempBundle,
) -> (crate::common::TestServer, crate::common::WsClient) {
    let server = crate::common::TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let up = op.event_where(|e| e["type"] == "robot.link").await;
    assert_eq!(up["state"], "up", "{up}");
    (server, op)
}
