//! The ROS 2 side of a rosbridge test: `rosbridge-server-rs` on a free loopback port and the
//! rclpy simulated base (`tests/ros/sim_base.py`), both in the test's own `ROS_DOMAIN_ID` out
//! of `tests/ros/.venv` (made by `scripts/install-test-deps.sh`), killed when dropped. Ready
//! means rosbridge said it listens (its log line, read from its stderr) and then a pose message
//! from the base reached a websocket client through it: each awaited with a deadline, never
//! slept for.

#![allow(dead_code)] // Each rosbridge test binary uses a different part.

use std::io::{BufRead, BufReader};
use std::net::TcpListener;
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use futures_util::{SinkExt, StreamExt};
use serde_json::{Value, json};
use tokio::net::TcpStream;
use tokio::sync::oneshot;
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

/// What rosbridge-server-rs logs (on stderr) once its websocket listener is bound, followed by
/// ` address=127.0.0.1:PORT`.
const ROSBRIDGE_LISTENING: &str = "rosbridge WebSocket server listening";

/// Starts rosbridge on `port` and returns once it says it listens. Its stderr is read on a
/// thread: the lines before that one are kept for the failure message, the rest drained (and
/// dropped, as its output always was) so that it never blocks on a full pipe.
async fn spawn_rosbridge(domain: u32, port: u16) -> Child {
    let bind = format!("127.0.0.1:{port}");
    let mut child = ros_command(
        domain,
        "rosbridge-server-rs",
        &["--bind", &bind, "--no-rosapi", "--log-ansi", "false"],
    )
    .stderr(Stdio::piped())
    .spawn()
    .expect("rosbridge-server-rs starts");
    let stderr = child.stderr.take().expect("rosbridge's stderr is piped");
    let said = Arc::new(Mutex::new(Vec::new()));
    let (listening, ready) = oneshot::channel();
    let kept = Arc::clone(&said);
    std::thread::spawn(move || {
        let mut listening = Some(listening);
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            if listening.is_none() {
                continue;
            }
            if line.contains(ROSBRIDGE_LISTENING) {
                if let Some(tx) = listening.take() {
                    let _ = tx.send(());
                }
            } else if let Ok(mut kept) = kept.lock() {
                kept.push(line);
            }
        }
        // End of output: dropping an unsent `listening` tells the waiter rosbridge ended.
    });
    let outcome = tokio::time::timeout(ROS_DEADLINE, ready).await;
    let said = said
        .lock()
        .map(|lines| lines.join("\n"))
        .unwrap_or_default();
    match outcome {
        Ok(Ok(())) => child,
        Ok(Err(_)) => panic!(
            "rosbridge on port {port} ended before it logged {ROSBRIDGE_LISTENING:?}; it said:\n{said}"
        ),
        Err(_) => panic!(
            "rosbridge on port {port} did not log {ROSBRIDGE_LISTENING:?} within {ROS_DEADLINE:?}; it said:\n{said}"
        ),
    }
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
            rosbridge: Some(spawn_rosbridge(domain, port).await),
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

    /// Starts rosbridge again on the same port; returns when it says it listens.
    pub async fn restart_rosbridge(&mut self) -> Instant {
        self.rosbridge = Some(spawn_rosbridge(self.domain, self.port).await);
        Instant::now()
    }

    /// Waits until a pose from the base comes through rosbridge, which listens already (so
    /// connecting must succeed); the base may still be joining the ROS graph.
    pub async fn await_pose(&self) -> Value {
        let mut client = RosClient::connect(&self.url)
            .await
            .unwrap_or_else(|e| panic!("rosbridge said it listens at {}, yet: {e}", self.url));
        client
            .subscribe("/amcl_pose", "geometry_msgs/msg/PoseWithCovarianceStamped")
            .await;
        match tokio::time::timeout(ROS_DEADLINE, client.next_on("/amcl_pose")).await {
            Ok(Some(msg)) => msg,
            Ok(None) => panic!("rosbridge at {} closed before a pose came", self.url),
            Err(_) => panic!(
                "no pose from the simulated base through rosbridge at {} within {ROS_DEADLINE:?}",
                self.url
            ),
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
