//! The fleet view's model: its own MQTT connection subscribed to every robot's `state`,
//! `status` and `reply` (`docent/+/...`), the robots as last heard of, the link's state, and
//! Stop. Each change goes to the page's live streams as one JSON update ([`FleetView::watch`]);
//! a Stop is published on the robot's `cmd` signed with this server's operator credential
//! (`signed`; the credential itself never goes to the broker) under a fresh random `ref`, and
//! resolved only by an answer bound to it: on `docent/ROBOT/reply` of the robot asked, with
//! that `ref`, naming that robot and signed with the same credential. Anything else (another
//! topic, another robot, an unsigned or badly signed answer) is ignored, so a forged `stopped`
//! is never taken for a stop; without a bound answer the Stop fails clearly (link down, no
//! answer in time): the page never shows a stop that did not happen.

use std::collections::{BTreeMap, HashMap};
use std::sync::Arc;
use std::sync::Mutex;
use std::time::Duration;

use rumqttc::{AsyncClient, QoS};
use serde_json::{Value, json};
use tokio::sync::{broadcast, mpsc, oneshot};

use super::broker::{Broker, LinkState, LinkStatus, LinkView, TOPIC_ROOT, split_topic, topic};
use super::link::{LinkNote, run_link};
use super::signed::{self, SignedCommand, SignedReply};
use crate::access::Secret;
use crate::lifecycle::Lifecycle;
use crate::sync::lock;

/// How long a Stop waits for the robot's answer.
pub const STOP_DEADLINE: Duration = Duration::from_secs(5);
/// Updates a slow page may fall behind by before it must reload its snapshot.
const UPDATES: usize = 256;
/// Robots listed at most (retained states from a misbehaving publisher stop there).
const MAX_ROBOTS: usize = 1000;

/// One robot as the fleet view last heard of it.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct RobotEntry {
    /// Its id.
    pub robot: String,
    /// Whether it is online: its `status` (the last will says false when its Docent dies).
    pub online: bool,
    /// Its last `state` document.
    pub state: Value,
}

/// Why a Stop did not happen.
#[derive(Debug, thiserror::Error)]
pub enum StopFailed {
    /// The fleet view's broker link is down: nothing was sent.
    #[error("the fleet view's broker link is down, so the stop was not sent: {0}")]
    LinkDown(String),
    /// The robot did not answer within [`STOP_DEADLINE`].
    #[error(
        "{0} did not confirm the stop within 5 s: it may be offline or not reachable; stop it at its console or on the robot"
    )]
    NoAnswer(String),
    /// No answer bound to the Stop within [`STOP_DEADLINE`], but one that could not be taken
    /// was heard (unsigned, badly signed, from another robot or topic).
    #[error(
        "{robot} did not confirm the stop within 5 s; an answer not signed with this view's operator credential was heard{hint} (a forgery, a robot with another operator credential, or clocks more than 30 s apart): stop it at its console or on the robot"
    )]
    Unbound {
        /// The robot.
        robot: String,
        /// What an unsigned answer from the robot's topic said, if one did.
        hint: String,
    },
    /// The robot answered with an `error` frame.
    #[error("{robot} refused the stop: {message} ({code})")]
    Refused {
        /// The robot.
        robot: String,
        /// The error code.
        code: String,
        /// Its message.
        message: String,
    },
    /// No such robot has been heard of.
    #[error("no robot {0} is known to this fleet view")]
    Unknown(String),
    /// This fleet view has no operator credential to sign with (an `--open` server).
    #[error(
        "this fleet view has no operator credential to sign the stop with (an --open server): start it with DOCENT_OPERATOR_TOKEN set to the fleet's operator credential"
    )]
    NoCredential,
}

/// A Stop waiting for its answer.
struct Waiting {
    /// The robot asked: only its `reply` topic may answer.
    robot: String,
    /// Gets the answer frame.
    answer: oneshot::Sender<Value>,
    /// Whether an answer that could not be taken was logged already (once per Stop).
    warned: bool,
    /// The `code` of an unsigned `error` heard on the asked robot's topic: not taken (anyone
    /// may have sent it), but told as a hint (`stale-command`: the clocks differ).
    hint: Option<String>,
}

/// The fleet as heard over the broker.
pub struct FleetView {
    robots: Mutex<BTreeMap<String, RobotEntry>>,
    updates: broadcast::Sender<String>,
    link: Arc<LinkStatus>,
    client: AsyncClient,
    /// Stops waiting for their answer, by `ref`.
    waiting: Mutex<HashMap<String, Waiting>>,
    /// The credential a Stop is signed with: this server's operator credential (`None` on
    /// `--open`).
    token: Option<Secret>,
}

impl FleetView {
    /// Connects to `broker` as `client_id` and follows the fleet until `life` shuts down.
    pub fn start(
        broker: &Broker,
        client_id: &str,
        token: Option<Secret>,
        life: &Lifecycle,
    ) -> Arc<Self> {
        let options = broker.options(client_id, None);
        let (client, events) = AsyncClient::new(options, 64);
        let link = Arc::new(LinkStatus::new(&broker.url));
        let (notes_tx, notes) = mpsc::channel(UPDATES);
        life.spawn(run_link(
            events,
            Arc::clone(&link),
            notes_tx,
            life.shutdown.clone(),
            Duration::from_millis(500),
        ));
        let view = Arc::new(FleetView {
            robots: Mutex::default(),
            updates: broadcast::channel(UPDATES).0,
            link,
            client,
            waiting: Mutex::default(),
            token,
        });
        life.spawn(Arc::clone(&view).follow(notes, life.shutdown.clone()));
        view
    }

    /// The link and every robot, and the stream of updates after them (subscribed first, so
    /// nothing falls between).
    pub fn watch(&self) -> (Value, broadcast::Receiver<String>) {
        let updates = self.updates.subscribe();
        (self.snapshot(), updates)
    }

    /// The link and every robot.
    pub fn snapshot(&self) -> Value {
        let robots: Vec<RobotEntry> = lock(&self.robots).values().cloned().collect();
        json!({ "link": self.link.view(), "robots": robots })
    }

    /// The link's state.
    pub fn link(&self) -> LinkView {
        self.link.view()
    }

    async fn follow(
        self: Arc<Self>,
        mut notes: mpsc::Receiver<LinkNote>,
        stop: tokio_util::sync::CancellationToken,
    ) {
        loop {
            let note = tokio::select! {
                () = stop.cancelled() => break,
                note = notes.recv() => match note { Some(note) => note, None => break },
            };
            match note {
                LinkNote::Up => {
                    for leaf in ["state", "status", "reply"] {
                        let filter = format!("{TOPIC_ROOT}/+/{leaf}");
                        if let Err(e) = self.client.try_subscribe(&filter, QoS::AtLeastOnce) {
                            tracing::warn!("could not subscribe to {filter}: {e}");
                        }
                    }
                    self.send_link();
                }
                LinkNote::Down(_) => self.send_link(),
                LinkNote::Message { topic, payload } => self.heard(&topic, &payload),
            }
        }
        let _ = self.client.try_disconnect();
    }

    fn send_link(&self) {
        let update = json!({ "link": self.link.view() });
        let _ = self.updates.send(update.to_string());
    }

    /// A message from a robot's topic.
    fn heard(&self, topic: &str, payload: &[u8]) {
        let Some((robot, leaf)) = split_topic(topic) else {
            return;
        };
        // An empty retained message clears the topic: the robot is forgotten.
        let value = if payload.is_empty() {
            Value::Null
        } else {
            match serde_json::from_slice::<Value>(payload) {
                Ok(value) => value,
                Err(e) => {
                    tracing::warn!(topic, "a robot published something that is not JSON: {e}");
                    return;
                }
            }
        };
        if leaf == "reply" {
            self.answered(robot, value);
            return;
        }
        let entry = {
            let mut robots = lock(&self.robots);
            if value.is_null() && leaf == "state" {
                robots.remove(robot);
                None
            } else if robots.len() >= MAX_ROBOTS && !robots.contains_key(robot) {
                tracing::warn!(robot, "more than {MAX_ROBOTS} robots: not listed");
                return;
            } else {
                let entry = robots
                    .entry(robot.to_owned())
                    .or_insert_with(|| RobotEntry {
                        robot: robot.to_owned(),
                        ..RobotEntry::default()
                    });
                let online = value
                    .get("online")
                    .and_then(Value::as_bool)
                    .unwrap_or(false);
                match leaf {
                    "status" => entry.online = online,
                    "state" => {
                        // A robot that says it stopped is offline whatever its status said.
                        if !online {
                            entry.online = false;
                        }
                        entry.state = value;
                    }
                    _ => return,
                }
                Some(entry.clone())
            }
        };
        let update = match entry {
            Some(entry) => json!({ "robot": entry }),
            None => json!({ "gone": robot }),
        };
        let _ = self.updates.send(update.to_string());
    }

    /// An answer on `robot`'s `reply` topic: taken only when it is bound to a waiting Stop.
    fn answered(&self, robot: &str, value: Value) {
        let Ok(reply) = serde_json::from_value::<SignedReply>(value) else {
            return;
        };
        let Some(reference) = reply.reference.as_deref() else {
            return;
        };
        let mut waiting = lock(&self.waiting);
        let Some(entry) = waiting.get_mut(reference) else {
            return;
        };
        let text = signed::reply_text(&reply.robot, reference, &reply.frame);
        let bound = entry.robot == robot
            && reply.robot == robot
            && (reply.mac.as_deref())
                .zip(self.token.as_ref())
                .is_some_and(|(mac, key)| signed::verifies(key, &text, mac));
        let frame = serde_json::from_str::<Value>(&reply.frame);
        if let Ok(frame) = &frame
            && !bound
            && entry.robot == robot
            && reply.robot == robot
            && let Some(code) = frame.get("code").and_then(Value::as_str)
        {
            entry.hint = Some(code.chars().take(64).collect());
        }
        match frame {
            Ok(frame) if bound => {
                if let Some(entry) = waiting.remove(reference) {
                    let _ = entry.answer.send(frame);
                }
            }
            _ if !entry.warned => {
                entry.warned = true;
                tracing::warn!(
                    topic_robot = robot,
                    asked = entry.robot,
                    "an answer to a fleet stop was not taken: not signed with the operator \
                     credential, or not from the robot asked (a forgery, or robots that do \
                     not share this credential)"
                );
            }
            _ => {}
        }
    }

    /// Stops robot `robot`: publishes `stop` on its `cmd` and waits for its answer.
    pub async fn stop(&self, robot: &str) -> Result<Value, StopFailed> {
        if !lock(&self.robots).contains_key(robot) {
            return Err(StopFailed::Unknown(robot.to_owned()));
        }
        let Some(key) = &self.token else {
            return Err(StopFailed::NoCredential);
        };
        let link = self.link.view();
        if link.state != LinkState::Up {
            let reason = link.reason.unwrap_or_else(|| "not connected yet".into());
            return Err(StopFailed::LinkDown(reason));
        }
        let reference = signed::fresh_reference();
        let (tx, rx) = oneshot::channel();
        let waiting = Waiting {
            robot: robot.to_owned(),
            answer: tx,
            warned: false,
            hint: None,
        };
        lock(&self.waiting).insert(reference.clone(), waiting);
        let command = signed_stop(key, robot, &reference);
        let sent = self
            .client
            .publish(topic(robot, "cmd"), QoS::AtLeastOnce, false, command)
            .await;
        if let Err(e) = sent {
            lock(&self.waiting).remove(&reference);
            return Err(StopFailed::LinkDown(e.to_string()));
        }
        let answer = tokio::time::timeout(STOP_DEADLINE, rx).await;
        let left = lock(&self.waiting).remove(&reference);
        let Ok(Ok(answer)) = answer else {
            return Err(match left {
                Some(entry) if entry.warned => StopFailed::Unbound {
                    robot: robot.to_owned(),
                    hint: (entry.hint)
                        .map(|code| format!(" (an unsigned one said {code})"))
                        .unwrap_or_default(),
                },
                _ => StopFailed::NoAnswer(robot.to_owned()),
            });
        };
        if answer.get("type").and_then(Value::as_str) == Some("error") {
            let text = |key: &str| {
                answer
                    .get(key)
                    .and_then(Value::as_str)
                    .unwrap_or_default()
                    .to_owned()
            };
            return Err(StopFailed::Refused {
                robot: robot.to_owned(),
                code: text("code"),
                message: text("message"),
            });
        }
        Ok(answer)
    }
}

/// The signed envelope of a `stop` for `robot`.
fn signed_stop(key: &crate::access::Secret, robot: &str, reference: &str) -> String {
    let frame = json!({ "type": "stop" }).to_string();
    let (role, ts) = ("operator", signed::now_ms());
    let text = signed::command_text(robot, role, reference, ts, &frame);
    let command = SignedCommand {
        robot: robot.to_owned(),
        role: role.to_owned(),
        reference: reference.to_owned(),
        ts,
        mac: signed::mac(key, &text),
        frame,
    };
    serde_json::to_string(&command).unwrap_or_else(|_| unreachable!("strings serialize"))
}
