//! The connection to a rosbridge v2 server: one task that connects, advertises and subscribes
//! everything in its [`LinkPlan`], sends what Docent publishes and hands what arrives to the
//! adapter; and, when the connection is lost or cannot be made, says so (a `robot.link` event,
//! the [`LinkStatus`]) and tries again with [`Backoff`], re-advertising and re-subscribing
//! everything on every new connection (a client that comes back without its subscriptions is
//! rosbridge users' most frequent complaint). A silent network is noticed by pings.

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use futures_util::{SinkExt, StreamExt};
use serde::Serialize;
use serde_json::Value;
use tokio::sync::{mpsc, watch};
use tokio_tungstenite::tungstenite::Message;
use tokio_util::sync::CancellationToken;

use super::backoff::Backoff;
use super::messages;
use crate::events::{EventKind, Hub, LinkState, RobotLinkEvent};
use crate::lifecycle::Lifecycle;
use crate::sync::lock;

/// How long connecting may take before the attempt counts as failed.
const CONNECT_TIMEOUT: Duration = Duration::from_secs(3);
/// How often the link pings a quiet server.
const PING_EVERY: Duration = Duration::from_secs(2);
/// How long without any frame from the server before the link counts as lost.
const SILENCE_LIMIT: Duration = Duration::from_secs(6);
/// How many times a stop held while the link was down goes out once it is back, and how often:
/// for 5 s, as the robot's subscribers may take that long to discover the new publishers.
const HELD_REPEATS: u32 = 20;
/// The wait between two sendings of a held stop.
const HELD_REPEAT_EVERY: Duration = Duration::from_millis(250);
/// Frames waiting to go out; more means the link is stuck.
const OUTBOX_CAPACITY: usize = 256;

/// What to (re)make on every connection.
#[derive(Clone, Debug, Default)]
pub struct LinkPlan {
    /// Topics Docent publishes on, with their types.
    pub advertise: Vec<(String, String)>,
    /// Topics Docent listens to, with their types.
    pub subscribe: Vec<(String, String)>,
}

/// The link as operators see it (`/api/state`'s `robot_link`).
#[derive(Clone, Debug, Serialize)]
pub struct LinkStatus {
    /// Up or down.
    pub state: LinkState,
    /// The rosbridge server's address.
    pub url: String,
    /// Why it is down.
    pub reason: Option<String>,
    /// Counts connections made, so a drive notices a reconnect it slept through.
    #[serde(skip)]
    pub connection: u64,
}

/// What arrived from rosbridge, for the adapter.
#[derive(Debug)]
pub enum Inbound {
    /// A message on a subscribed topic.
    Message {
        /// The topic.
        topic: String,
        /// The message.
        msg: Value,
    },
    /// An action goal ended (`action_result`).
    ActionResult {
        /// The goal's id, as Docent sent it.
        id: String,
        /// `action_msgs/msg/GoalStatus` status (4 succeeded, 5 canceled, 6 aborted).
        status: u64,
    },
}

/// Sends to the link; cheap to clone.
pub struct Link {
    url: String,
    outbox: mpsc::Sender<Message>,
    status: watch::Sender<LinkStatus>,
    /// Frames to send as soon as the link is next up (a stop that found it down).
    held: Mutex<Vec<Value>>,
}

impl Link {
    /// Starts the link task for `url`; `inbound` gets every message that arrives.
    pub fn start(
        url: String,
        plan: LinkPlan,
        inbound: impl Fn(Inbound) + Send + Sync + 'static,
        hub: Hub,
        life: &Lifecycle,
    ) -> Arc<Link> {
        let (outbox, outbox_rx) = mpsc::channel(OUTBOX_CAPACITY);
        let (status, _) = watch::channel(LinkStatus {
            state: LinkState::Down,
            url: url.clone(),
            reason: Some("not connected yet".to_owned()),
            connection: 0,
        });
        let link = Arc::new(Link {
            url,
            outbox,
            status,
            held: Mutex::new(Vec::new()),
        });
        let task = Connection {
            link: Arc::clone(&link),
            plan,
            inbound: Box::new(inbound),
            hub,
            shutdown: life.shutdown.clone(),
        };
        life.spawn(task.run(outbox_rx));
        link
    }

    /// The server's address.
    pub fn url(&self) -> &str {
        &self.url
    }

    /// The current state.
    pub fn status(&self) -> LinkStatus {
        self.status.borrow().clone()
    }

    /// Learns of every change of state.
    pub fn watch(&self) -> watch::Receiver<LinkStatus> {
        self.status.subscribe()
    }

    /// Sends `op` now, or says why it cannot go out.
    pub fn send(&self, op: &Value) -> Result<(), String> {
        let status = self.status();
        if status.state == LinkState::Down {
            let reason = status.reason.unwrap_or_default();
            return Err(format!(
                "the link to rosbridge at {} is down: {reason}",
                self.url
            ));
        }
        self.outbox
            .try_send(Message::text(op.to_string()))
            .map_err(|_| format!("the link to rosbridge at {} is not keeping up", self.url))
    }

    /// Sends `ops` now, or as soon as the link is back (replacing any held before): for a
    /// stop, which must reach the robot even if it finds the link down.
    pub fn send_or_hold(&self, ops: Vec<Value>) {
        let failed = ops.iter().any(|op| self.send(op).is_err());
        if failed {
            tracing::warn!(url = %self.url, "the link to rosbridge is down: the stop goes out when it is back");
            *lock(&self.held) = ops;
        }
    }

    /// Forgets a held stop: a new goal is on its way.
    pub fn clear_held(&self) {
        lock(&self.held).clear();
    }

    /// Sets the state and tells it: the caller sets `Up` on every connection and `Down` once
    /// per loss (the first failed attempt included), not on every failed retry.
    fn set(&self, state: LinkState, reason: Option<String>, hub: &Hub) {
        self.status.send_modify(|s| {
            s.state = state;
            s.reason.clone_from(&reason);
            if state == LinkState::Up {
                s.connection += 1;
            }
        });
        hub.publish(EventKind::RobotLink(RobotLinkEvent {
            state,
            url: self.url.clone(),
            reason,
        }));
    }
}

struct Connection {
    link: Arc<Link>,
    plan: LinkPlan,
    inbound: Box<dyn Fn(Inbound) + Send + Sync>,
    hub: Hub,
    shutdown: CancellationToken,
}

type Socket =
    tokio_tungstenite::WebSocketStream<tokio_tungstenite::MaybeTlsStream<tokio::net::TcpStream>>;

impl Connection {
    async fn run(self, mut outbox: mpsc::Receiver<Message>) {
        let mut backoff = Backoff::default();
        let mut told_down = false;
        loop {
            let attempt = tokio::time::timeout(
                CONNECT_TIMEOUT,
                tokio_tungstenite::connect_async(self.link.url.as_str()),
            );
            let reason = tokio::select! {
                () = self.shutdown.cancelled() => return,
                attempt = attempt => match attempt {
                    Ok(Ok((socket, _))) => {
                        backoff.reset();
                        told_down = false;
                        match self.serve(socket, &mut outbox).await {
                            Some(reason) => reason,
                            None => return,
                        }
                    }
                    Ok(Err(e)) => format!("cannot connect: {e}"),
                    Err(_) => format!("no answer within {} s", CONNECT_TIMEOUT.as_secs()),
                },
            };
            if !told_down {
                tracing::warn!(url = %self.link.url, %reason, "the link to rosbridge is down; trying again");
                self.link.set(LinkState::Down, Some(reason), &self.hub);
                told_down = true;
            }
            tokio::select! {
                () = self.shutdown.cancelled() => return,
                () = tokio::time::sleep(backoff.next_delay()) => {}
            }
        }
    }

    /// Runs one connection until it is lost (the reason) or the server shuts down (`None`).
    async fn serve(
        &self,
        mut socket: Socket,
        outbox: &mut mpsc::Receiver<Message>,
    ) -> Option<String> {
        // Whatever was queued for the last connection is stale: goals failed when it went.
        while outbox.try_recv().is_ok() {}
        let plan = &self.plan;
        let advertise = plan
            .advertise
            .iter()
            .map(|(t, k)| messages::advertise(t, k));
        let subscribe = plan
            .subscribe
            .iter()
            .map(|(t, k)| messages::subscribe(t, k));
        for op in advertise.chain(subscribe) {
            if let Err(e) = socket.send(Message::text(op.to_string())).await {
                return Some(format!("lost while subscribing: {e}"));
            }
        }
        self.link.set(LinkState::Up, None, &self.hub);
        // A stop held while the link was down goes out now, and again a few times: the topics
        // were just advertised, and a message published before the robot's subscribers are
        // discovered is lost.
        let mut repeats = if lock(&self.link.held).is_empty() {
            0
        } else {
            HELD_REPEATS
        };
        let mut repeat = tokio::time::interval(HELD_REPEAT_EVERY);
        let mut last_heard = Instant::now();
        let mut pings = tokio::time::interval(PING_EVERY);
        loop {
            tokio::select! {
                _ = repeat.tick(), if repeats > 0 => {
                    repeats -= 1;
                    // A new goal clears it (`clear_held`): the stop must not halt that one.
                    let held = if repeats == 0 {
                        std::mem::take(&mut *lock(&self.link.held))
                    } else {
                        lock(&self.link.held).clone()
                    };
                    for op in &held {
                        if let Err(e) = socket.send(Message::text(op.to_string())).await {
                            return Some(format!("sending failed: {e}"));
                        }
                    }
                }
                () = self.shutdown.cancelled() => {
                    let _ = socket.close(None).await;
                    return None;
                }
                out = outbox.recv() => {
                    let message = out?;
                    if let Err(e) = socket.send(message).await {
                        return Some(format!("sending failed: {e}"));
                    }
                }
                frame = socket.next() => {
                    last_heard = Instant::now();
                    match frame {
                        Some(Ok(Message::Text(text))) => self.received(&text),
                        Some(Ok(Message::Close(close))) => {
                            let why = close.map(|c| c.reason.to_string()).unwrap_or_default();
                            return Some(format!("rosbridge closed the connection {why}").trim_end().to_owned());
                        }
                        Some(Ok(_)) => {}
                        Some(Err(e)) => return Some(format!("connection error: {e}")),
                        None => return Some("the connection ended".to_owned()),
                    }
                }
                _ = pings.tick() => {
                    if last_heard.elapsed() > SILENCE_LIMIT {
                        return Some(format!("no answer for {} s", SILENCE_LIMIT.as_secs()));
                    }
                    if let Err(e) = socket.send(Message::Ping(Vec::new().into())).await {
                        return Some(format!("sending failed: {e}"));
                    }
                }
            }
        }
    }

    fn received(&self, text: &str) {
        let Ok(op) = serde_json::from_str::<Value>(text) else {
            tracing::warn!(url = %self.link.url, "rosbridge sent a frame that is not JSON");
            return;
        };
        match op["op"].as_str() {
            Some("publish") => {
                if let (Some(topic), Some(msg)) = (op["topic"].as_str(), op.get("msg")) {
                    (self.inbound)(Inbound::Message {
                        topic: topic.to_owned(),
                        msg: msg.clone(),
                    });
                }
            }
            Some("action_result") => {
                if let Some(id) = op["id"].as_str() {
                    (self.inbound)(Inbound::ActionResult {
                        id: id.to_owned(),
                        status: op["status"].as_u64().unwrap_or(0),
                    });
                }
            }
            Some("status") => {
                let level = op["level"].as_str().unwrap_or("info");
                let msg = op["msg"].as_str().unwrap_or_default();
                if level == "error" || level == "warning" {
                    tracing::warn!(url = %self.link.url, level, msg, "rosbridge reports a problem");
                }
            }
            _ => {}
        }
    }
}
