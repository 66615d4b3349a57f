//! What the fleet tests share: a real mosquitto on a free loopback port (killed on drop), a
//! `docent serve --mqtt` child process per robot (killed on drop), and an MQTT test client
//! whose messages are awaited with a deadline, never slept for.

#![allow(dead_code)] // Each test binary uses a different part.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use rumqttc::{AsyncClient, Event, Incoming, MqttOptions, QoS};
use serde_json::Value;
use tokio::sync::mpsc;

use crate::common::{DEADLINE, DM_TOKEN, OPERATOR_TOKEN, process};

/// A mosquitto broker on 127.0.0.1, killed when dropped.
pub struct Mosquitto {
    child: Child,
    /// Its port.
    pub port: u16,
    _dir: tempfile::TempDir,
}

impl Mosquitto {
    /// A broker on a free port.
    pub fn start() -> Self {
        let port = std::net::TcpListener::bind("127.0.0.1:0")
            .and_then(|l| l.local_addr())
            .expect("a free port")
            .port();
        Mosquitto::start_on(port)
    }

    /// A broker on `port` (again, after [`Mosquitto::kill`]), once it listens: mosquitto
    /// says so on stderr, which is awaited (with the deadline) rather than slept for.
    pub fn start_on(port: u16) -> Self {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let conf = dir.path().join("mosquitto.conf");
        let text = format!(
            "listener {port} 127.0.0.1\nallow_anonymous true\npersistence false\n\
             log_dest stderr\nlog_type all\n"
        );
        std::fs::write(&conf, text).expect("config written");
        let binary = ["/usr/sbin/mosquitto", "/usr/bin/mosquitto"]
            .into_iter()
            .find(|p| Path::new(p).exists())
            .expect("mosquitto is installed (scripts/install-test-deps.sh)");
        let mut child = Command::new(binary)
            .arg("-c")
            .arg(&conf)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("mosquitto starts");
        let stderr = child.stderr.take().expect("stderr");
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut told = false;
            for line in BufReader::new(stderr).lines().map_while(Result::ok) {
                if !told && line.contains("Opening ipv4 listen socket") {
                    told = tx.send(()).is_ok();
                }
            }
        });
        rx.recv_timeout(DEADLINE)
            .expect("mosquitto opens its listener within the deadline");
        Mosquitto {
            child,
            port,
            _dir: dir,
        }
    }

    /// The broker's address for `--mqtt`.
    pub fn url(&self) -> String {
        format!("mqtt://127.0.0.1:{}", self.port)
    }

    /// Kills it (SIGKILL) and waits for it to be gone.
    pub fn kill(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Drop for Mosquitto {
    fn drop(&mut self) {
        self.kill();
    }
}

/// A `docent serve --mqtt` process, killed when dropped.
pub struct Robot {
    child: Child,
    /// Its `host:port`.
    pub addr: String,
    /// Its corpus folder.
    pub corpus: PathBuf,
    _dir: tempfile::TempDir,
}

impl Robot {
    /// `docent serve BUNDLE --mqtt URL --robot-id ID`, guarded by the test credentials.
    pub fn start(bundle: &Path, broker: &Mosquitto, id: &str) -> Self {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let corpus = dir.path().join("corpus");
        let mut command = Command::new(env!("CARGO_BIN_EXE_docent"));
        command
            .arg("serve")
            .arg(bundle)
            .args([
                "--listen",
                "127.0.0.1:0",
                "--no-watch",
                "--corpus-sync",
                "10ms",
            ])
            .arg("--corpus")
            .arg(&corpus)
            .args(["--mqtt", &broker.url(), "--robot-id", id])
            .env("DOCENT_OPERATOR_TOKEN", OPERATOR_TOKEN)
            .env("DOCENT_DM_TOKEN", DM_TOKEN)
            .env("RUST_LOG", "docent=warn");
        let (child, addr) = process::start(command);
        Robot {
            child,
            addr,
            corpus,
            _dir: dir,
        }
    }

    /// Kills it with SIGKILL: no goodbye, only the broker's last will.
    pub fn kill_9(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }

    /// A URL on this robot's server.
    pub fn url(&self, path: &str) -> String {
        format!("http://{}{path}", self.addr)
    }
}

impl Drop for Robot {
    fn drop(&mut self) {
        self.kill_9();
    }
}

/// A message a test client received.
#[derive(Debug)]
pub struct Message {
    /// Its topic.
    pub topic: String,
    /// Its payload as JSON.
    pub json: Value,
}

/// An MQTT client of the test: subscribes to `filters` (again after each reconnection).
pub struct TestClient {
    /// Publishes.
    pub client: AsyncClient,
    messages: mpsc::UnboundedReceiver<Message>,
}

impl TestClient {
    /// Connects to `broker` as `id` and subscribes to `filters`.
    pub fn connect(broker: &Mosquitto, id: &str, filters: &[&str]) -> Self {
        let mut options = MqttOptions::new(id, "127.0.0.1", broker.port);
        options.set_keep_alive(Duration::from_secs(5));
        let (client, mut events) = AsyncClient::new(options, 64);
        let (tx, messages) = mpsc::unbounded_channel();
        let filters: Vec<String> = filters.iter().map(|f| (*f).to_owned()).collect();
        let subscriber = client.clone();
        tokio::spawn(async move {
            loop {
                match events.poll().await {
                    Ok(Event::Incoming(Incoming::ConnAck(_))) => {
                        for filter in &filters {
                            let _ = subscriber.subscribe(filter, QoS::AtLeastOnce).await;
                        }
                    }
                    Ok(Event::Incoming(Incoming::Publish(p))) => {
                        let json = serde_json::from_slice(&p.payload).unwrap_or(Value::Null);
                        if tx
                            .send(Message {
                                topic: p.topic,
                                json,
                            })
                            .is_err()
                        {
                            return;
                        }
                    }
                    Ok(_) => {}
                    // The broker is down: rumqttc reconnects at the next poll; a breath first.
                    Err(_) => tokio::time::sleep(Duration::from_millis(50)).await,
                }
            }
        });
        TestClient { client, messages }
    }

    /// The next message on `topic` that `wanted` accepts, within the deadline.
    pub async fn next(&mut self, topic: &str, wanted: impl Fn(&Value) -> bool) -> Value {
        let found = tokio::time::timeout(DEADLINE, async {
            loop {
                let message = self.messages.recv().await.expect("the client runs");
                if message.topic == topic && wanted(&message.json) {
                    return message.json;
                }
            }
        })
        .await;
        found.unwrap_or_else(|_| panic!("no wanted message on {topic} within the deadline"))
    }

    /// Publishes `command` on robot `robot`'s `cmd` topic.
    pub async fn command(&self, robot: &str, command: Value) {
        (self.client)
            .publish(
                format!("docent/{robot}/cmd"),
                QoS::AtLeastOnce,
                false,
                command.to_string(),
            )
            .await
            .expect("published");
    }

    /// Publishes `command` on `robot`'s `cmd` and returns its answer with `reference`.
    pub async fn ask(&mut self, robot: &str, reference: &str, command: Value) -> Value {
        self.command(robot, command).await;
        let topic = format!("docent/{robot}/reply");
        self.next(&topic, |answer| answer["ref"] == reference).await
    }
}

/// The corpus lines of `corpus` (every day log and session log) of `type`.
pub fn logged(corpus: &Path, kind: &str) -> Vec<Value> {
    crate::common::read_corpus(corpus)
        .into_iter()
        .filter(|e| e["type"] == kind)
        .collect()
}
