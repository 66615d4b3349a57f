//! What the fleet tests share: a real mosquitto on a free loopback port (killed on drop), a
//! `docent serve --mqtt` child process per robot (killed on drop), an MQTT test client
//! whose messages are awaited with a deadline, never slept for (nor does it sleep while the
//! broker is down: it awaits the broker's coming back), and the signing of fleet
//! commands written from docs/FLEET.md (HMAC-SHA256 with the `hmac` crate, not Docent's code),
//! so that the format as documented is what the robots take.

#![allow(dead_code)] // Each test binary uses a different part.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use rumqttc::{AsyncClient, Event, Incoming, MqttOptions, QoS};
use serde_json::Value;
use tokio::sync::{mpsc, watch};

use crate::common::{DEADLINE, DM_TOKEN, OPERATOR_TOKEN, process};

mod signing;
mod view;

// Each test binary uses a different part (as `dead_code` above).
#[allow(unused_imports)]
pub use signing::*;
#[allow(unused_imports)]
pub use view::*;

/// A mosquitto broker on 127.0.0.1, killed when dropped.
pub struct Mosquitto {
    child: Child,
    /// Its port.
    pub port: u16,
    /// How many times it has come up (listening): what a [`TestClient`] whose connection
    /// broke awaits a change of, instead of polling a broker that is down.
    up: watch::Sender<u64>,
    /// Its configuration file (in `_dir`), for [`Mosquitto::restart`].
    conf: PathBuf,
    _dir: tempfile::TempDir,
    /// The test CA and the TLS listener's certificate, if it has one.
    certs: Option<tempfile::TempDir>,
}

/// A loopback port that was free a moment ago.
fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .expect("a free port")
        .port()
}

impl Mosquitto {
    /// A broker on a free port, once it listens.
    pub fn start() -> Self {
        Mosquitto::start_with(free_port(), "")
    }

    /// A broker on a free port and, on a second one, a TLS listener whose certificate (for
    /// `localhost` and 127.0.0.1) a fresh CA signed: the port and the CA's PEM file.
    pub fn start_with_tls() -> (Self, u16, PathBuf) {
        let certs = tempfile::tempdir().expect("a temporary folder");
        let dir = certs.path();
        let openssl = |args: &[&str]| {
            let status = Command::new("openssl")
                .args(args)
                .current_dir(dir)
                .stderr(Stdio::null())
                .status()
                .expect("openssl runs");
            assert!(status.success(), "openssl {args:?}");
        };
        openssl(&[
            "req",
            "-x509",
            "-newkey",
            "rsa:2048",
            "-nodes",
            "-days",
            "2",
            "-subj",
            "/CN=Docent test CA",
            "-keyout",
            "ca.key",
            "-out",
            "ca.pem",
        ]);
        openssl(&[
            "req",
            "-newkey",
            "rsa:2048",
            "-nodes",
            "-subj",
            "/CN=localhost",
            "-keyout",
            "server.key",
            "-out",
            "server.csr",
        ]);
        std::fs::write(
            dir.join("san.ext"),
            "subjectAltName=DNS:localhost,IP:127.0.0.1\n",
        )
        .expect("written");
        openssl(&[
            "x509",
            "-req",
            "-in",
            "server.csr",
            "-CA",
            "ca.pem",
            "-CAkey",
            "ca.key",
            "-CAcreateserial",
            "-days",
            "2",
            "-extfile",
            "san.ext",
            "-out",
            "server.pem",
        ]);
        // mosquitto started as root reads its certificates as the `mosquitto` user.
        use std::os::unix::fs::PermissionsExt;
        let readable = std::fs::Permissions::from_mode(0o755);
        std::fs::set_permissions(dir, readable.clone()).expect("folder readable");
        std::fs::set_permissions(dir.join("server.key"), readable).expect("key readable");
        let tls_port = free_port();
        let tls = format!(
            "listener {tls_port} 127.0.0.1\ncafile {0}/ca.pem\ncertfile {0}/server.pem\nkeyfile {0}/server.key\n",
            dir.display()
        );
        let mut broker = Mosquitto::start_with(free_port(), &tls);
        let ca = dir.join("ca.pem");
        broker.certs = Some(certs);
        (broker, tls_port, ca)
    }

    /// mosquitto with a plain listener on `port` and `more` configuration, once it listens.
    fn start_with(port: u16, more: &str) -> Self {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let conf = dir.path().join("mosquitto.conf");
        let text = format!(
            "allow_anonymous true\npersistence false\nlog_dest stderr\nlog_type all\n\
             listener {port} 127.0.0.1\n{more}"
        );
        std::fs::write(&conf, text).expect("config written");
        Mosquitto {
            child: spawn_listening(&conf),
            port,
            up: watch::channel(1).0,
            conf,
            _dir: dir,
            certs: None,
        }
    }

    /// Starts it again on its port (after [`Mosquitto::kill`]) and returns once it listens,
    /// having told its test clients that it is up again.
    pub fn restart(&mut self) {
        self.child = spawn_listening(&self.conf);
        self.up.send_modify(|times| *times += 1);
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

/// mosquitto with the configuration `conf`, once all its listeners listen: it says so on stderr
/// (`mosquitto version 2.0.11 running`, logged after it has bound them all; its earlier
/// `Opening ipv4 listen socket on port N.` comes before the bind, so a client connecting then
/// can be refused), which is awaited (with the deadline) rather than slept for. The rest of its
/// output is drained, so that it never blocks on a full pipe.
fn spawn_listening(conf: &Path) -> Child {
    let binary = ["/usr/sbin/mosquitto", "/usr/bin/mosquitto"]
        .into_iter()
        .find(|p| Path::new(p).exists())
        .expect("mosquitto is installed (scripts/install-test-deps.sh)");
    let mut child = Command::new(binary)
        .arg("-c")
        .arg(conf)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("mosquitto starts");
    let stderr = child.stderr.take().expect("stderr");
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let mut said = Vec::new();
        let mut running = Some(tx);
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            let Some(tx) = &running else {
                continue; // Drained.
            };
            if is_running(&line) {
                let _ = tx.send(Ok(()));
                running = None;
            } else {
                said.push(line);
            }
        }
        // It ended before it was running: what it said is the reason.
        if let Some(tx) = running {
            let _ = tx.send(Err(said.join("\n")));
        }
    });
    match rx.recv_timeout(DEADLINE) {
        Ok(Ok(())) => child,
        Ok(Err(said)) => panic!("mosquitto ended before it was running; it said:\n{said}"),
        Err(_) => {
            panic!("mosquitto did not log `mosquitto version ... running` within {DEADLINE:?}")
        }
    }
}

/// Whether `line` is mosquitto's `mosquitto version X running`.
fn is_running(line: &str) -> bool {
    line.contains("mosquitto version") && line.ends_with(" running")
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
        Robot::start_at(bundle, &broker.url(), id, &[])
    }

    /// As [`Robot::start`], with the broker at `url` and `more` arguments.
    pub fn start_at(bundle: &Path, url: &str, id: &str, more: &[&str]) -> Self {
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
            .args(["--mqtt", url, "--robot-id", id])
            .args(more)
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

    /// Asks it to stop (SIGTERM) and waits until it has: a graceful goodbye.
    pub fn terminate(&mut self) {
        let status = Command::new("kill")
            .args(["-TERM", &self.child.id().to_string()])
            .status()
            .expect("kill runs");
        assert!(status.success());
        let _ = self.child.wait();
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
    /// Its payload as JSON (null if it is not).
    pub json: Value,
    /// Its payload as text (bytes not UTF-8 replaced).
    pub text: String,
}

/// An MQTT client of the test: subscribes to `filters` (again after each reconnection).
pub struct TestClient {
    /// Publishes.
    pub client: AsyncClient,
    messages: mpsc::UnboundedReceiver<Message>,
}

impl TestClient {
    /// Connects to `broker` as `id` and subscribes to `filters`. When the connection breaks
    /// (the broker was killed), the client waits until the broker says it is up again (at once
    /// if it already has) before rumqttc reconnects; it ends with the broker.
    pub fn connect(broker: &Mosquitto, id: &str, filters: &[&str]) -> Self {
        let mut options = MqttOptions::new(id, "127.0.0.1", broker.port);
        options.set_keep_alive(Duration::from_secs(5));
        let (client, mut events) = AsyncClient::new(options, 64);
        let (tx, messages) = mpsc::unbounded_channel();
        let filters: Vec<String> = filters.iter().map(|f| (*f).to_owned()).collect();
        let subscriber = client.clone();
        let mut up = broker.up.subscribe();
        let id = id.to_owned();
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
                        let text = String::from_utf8_lossy(&p.payload).into_owned();
                        let message = Message {
                            topic: p.topic,
                            json,
                            text,
                        };
                        if tx.send(message).is_err() {
                            return;
                        }
                    }
                    Ok(_) => {}
                    // The broker is down: rumqttc reconnects at the next poll, once it is up.
                    Err(error) => {
                        eprintln!("test client {id}: {error}; awaiting the broker");
                        if up.changed().await.is_err() {
                            return;
                        }
                    }
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

    /// The next message on any topic, within the deadline.
    pub async fn recv(&mut self) -> Message {
        let message = tokio::time::timeout(DEADLINE, self.messages.recv()).await;
        let message = message.expect("a message within the deadline");
        message.expect("the client runs")
    }

    /// Publishes `command` on robot `robot`'s `cmd` topic.
    pub async fn command(&self, robot: &str, command: Value) {
        self.publish(&format!("docent/{robot}/cmd"), &command).await;
    }

    /// Publishes `payload` on `topic`.
    pub async fn publish(&self, topic: &str, payload: &Value) {
        (self.client)
            .publish(topic, QoS::AtLeastOnce, false, payload.to_string())
            .await
            .expect("published");
    }

    /// Publishes the envelope `command` (whose `ref` is `reference`) on `robot`'s `cmd` and
    /// returns the reply envelope with that `ref`, as it came.
    pub async fn ask_envelope(&mut self, robot: &str, reference: &str, command: Value) -> Value {
        self.command(robot, command).await;
        let topic = format!("docent/{robot}/reply");
        self.next(&topic, |answer| answer["ref"] == reference).await
    }

    /// Sends `frame` to `robot` signed with the operator credential and returns the answer
    /// frame, after checking the reply is signed too.
    pub async fn ask(&mut self, robot: &str, frame: Value) -> Value {
        let reference = fresh_ref();
        let command = signed(robot, ("operator", OPERATOR_TOKEN), &reference, &frame);
        let reply = self.ask_envelope(robot, &reference, command).await;
        assert!(reply_signed(&reply, OPERATOR_TOKEN), "{reply}");
        assert_eq!(reply["robot"], robot);
        reply_frame(&reply)
    }
}

/// The corpus lines of `corpus` (every day log and session log) of `type`.
pub fn logged(corpus: &Path, kind: &str) -> Vec<Value> {
    crate::common::read_corpus(corpus)
        .into_iter()
        .filter(|e| e["type"] == kind)
        .collect()
}

/// `GET url` with the operator credential, as JSON.
pub async fn operator_get(url: &str) -> Value {
    reqwest::Client::new()
        .get(url)
        .bearer_auth(OPERATOR_TOKEN)
        .send()
        .await
        .expect("answers")
        .json()
        .await
        .expect("JSON")
}
