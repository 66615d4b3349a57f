//! The robot's side of the fleet: one MQTT connection (`docent-ID`) that publishes, under
//! `docent/ID/`, a retained `status` (`{"online": true}`, and the same topic as the last will
//! saying offline, which the broker publishes when the process dies), a retained `state`
//! (`robot_state`, re-published on change at most every [`STATE_INTERVAL`]) and every hub
//! event on `events` at QoS 1 (its corpus line); and takes commands on `cmd` (`commands`),
//! answered on `reply`. Each command's signature is checked as it arrives, in the bridge's
//! loop, and a refusal answered at once; only verified commands queue to run (one at a time),
//! so a flood of bad commands through the broker cannot push a signed Stop out of the queue. After a broker restart the link subscribes again and re-publishes
//! both retained messages. Operators learn of the link's changes as `fleet.link` events and
//! in `/api/state`'s `fleet`.

use std::net::IpAddr;
use std::sync::Arc;
use std::time::Duration;

use rumqttc::{AsyncClient, LastWill, QoS};
use serde_json::{Value, json};
use tokio::sync::broadcast::error::RecvError;
use tokio::sync::mpsc;
use tokio::time::Instant;

use super::broker::{Broker, LinkStatus, topic};
use super::commands::{self, Verified};
use super::link::{LinkNote, run_link};
use super::robot_state::{self, Battery, Identity};
use super::signed::Replays;
use crate::events::EventKind;
use crate::state::AppState;

/// The least time between two `state` publications.
pub const STATE_INTERVAL: Duration = Duration::from_millis(250);
/// Requests (publications) waiting for the link at most; more events are dropped, counted.
const REQUEST_CAPACITY: usize = 1024;
/// Verified commands waiting to run at most.
const COMMAND_QUEUE: usize = 32;
/// Messages from the link waiting for the bridge's loop at most (each is checked at once, so
/// this is headroom for a burst, beyond which the link drops messages with a warning).
const NOTES: usize = 1024;
/// How long a stopping server keeps the link to say it is going offline.
const GOODBYE: Duration = Duration::from_secs(2);

/// What a robot's bridge needs.
#[derive(Clone, Debug)]
pub struct BridgeSettings {
    /// The broker and the login.
    pub broker: Broker,
    /// Who this robot is, and where its console is.
    pub identity: Identity,
}

/// Starts the bridge for the server `state`; its link's state is kept in `state.fleet`.
pub fn start_bridge(state: &AppState, settings: BridgeSettings) -> Arc<LinkStatus> {
    let BridgeSettings { broker, identity } = settings;
    let robot = identity.robot.clone();
    let link = Arc::new(LinkStatus::new(&broker.url));
    let offline = robot_state::offline(&robot, "the robot's Docent is gone (last will)");
    let will = LastWill::new(
        topic(&robot, "status"),
        offline.to_string(),
        QoS::AtLeastOnce,
        true,
    );
    let options = broker.options(&format!("docent-{robot}"), Some(will));
    let (client, events) = AsyncClient::new(options, REQUEST_CAPACITY);
    let (notes_tx, notes) = mpsc::channel(NOTES);
    let life = &state.life;
    life.spawn(run_link(
        events,
        Arc::clone(&link),
        notes_tx,
        life.shutdown.clone(),
        GOODBYE,
    ));
    let (commands_tx, commands_rx) = mpsc::channel(COMMAND_QUEUE);
    let host = broker.url.host.clone();
    life.spawn(run_commands(
        state.clone(),
        client.clone(),
        host.clone(),
        robot.clone(),
        commands_rx,
    ));
    let bridge = Bridge {
        state: state.clone(),
        client,
        identity,
        broker_host: host,
        replays: Replays::default(),
        link: Arc::clone(&link),
        battery: None,
        published: None,
        dropped: 0,
    };
    life.spawn(bridge.run(notes, commands_tx));
    link
}

struct Bridge {
    state: AppState,
    client: AsyncClient,
    identity: Identity,
    /// The broker's host, named in the log as where refused commands came through.
    broker_host: String,
    /// The references of the commands taken (no replay).
    replays: Replays,
    link: Arc<LinkStatus>,
    battery: Option<Battery>,
    /// The state document last published since the link came up.
    published: Option<String>,
    /// Events not published since the last warning (the request queue was full).
    dropped: u64,
}

impl Bridge {
    async fn run(mut self, mut notes: mpsc::Receiver<LinkNote>, commands: mpsc::Sender<Verified>) {
        // The state's battery comes from battery reports, followed without loss: a level
        // missed under load would stand in the fleet view until the next report. The rest of
        // the events are mirrored on `events` through the bounded broadcast (drops counted).
        let mut batteries = self.state.hub.follow(robot_state::is_battery);
        let mut events = self.state.hub.subscribe();
        let shutdown = self.state.life.shutdown.clone();
        let cmd_topic = topic(&self.identity.robot, "cmd");
        let mut dirty = false;
        let mut next_state = Instant::now();
        loop {
            tokio::select! {
                () = shutdown.cancelled() => break,
                note = notes.recv() => match note {
                    Some(LinkNote::Up) => {
                        self.up(&cmd_topic);
                        dirty = true;
                        next_state = Instant::now();
                    }
                    Some(LinkNote::Down(reason)) => self.announce(Some(reason)),
                    Some(LinkNote::Message { topic, payload }) if topic == cmd_topic => {
                        self.command(&payload, &commands);
                    }
                    Some(LinkNote::Message { .. }) => {}
                    None => break,
                },
                Some(report) = batteries.recv() => {
                    if let Some(battery) = robot_state::battery_of(&report) {
                        self.battery = Some(battery);
                        dirty = true;
                    }
                }
                got = events.recv() => match got {
                    Ok(event) => {
                        self.publish_event(event.json());
                        dirty = true;
                    }
                    Err(RecvError::Lagged(missed)) => {
                        tracing::warn!(missed, "the MQTT bridge fell behind the events; {missed} were not published (the corpus has them)");
                        dirty = true;
                    }
                    Err(RecvError::Closed) => break,
                },
                () = tokio::time::sleep_until(next_state), if dirty => {
                    dirty = false;
                    next_state = Instant::now() + STATE_INTERVAL;
                    self.publish_state();
                }
            }
        }
        self.goodbye().await;
    }

    /// A command from `cmd`: refused at once, or queued to run.
    fn command(&mut self, payload: &[u8], commands: &mpsc::Sender<Verified>) {
        let from = (self.broker_host.as_str(), self.identity.robot.as_str());
        match commands::check(&self.state, from, &mut self.replays, payload) {
            Ok(verified) => match commands.try_send(verified) {
                Ok(()) => {}
                Err(mpsc::error::TrySendError::Full(verified)) => {
                    tracing::warn!(
                        "a signed MQTT command was refused: {COMMAND_QUEUE} wait to run"
                    );
                    let reply = commands::busy(&self.identity.robot, &verified, COMMAND_QUEUE);
                    let topic = topic(&self.identity.robot, "reply");
                    if (self.client)
                        .try_publish(&topic, QoS::AtLeastOnce, false, reply)
                        .is_err()
                    {
                        tracing::warn!(
                            "a signed MQTT command was neither run nor answered: the link is busy"
                        );
                    }
                }
                Err(mpsc::error::TrySendError::Closed(_)) => {
                    tracing::warn!("a signed MQTT command was not run: the server is stopping");
                }
            },
            Err(reply) => {
                let topic = topic(&self.identity.robot, "reply");
                // Not waited for: a flood of refusals must not hold up the loop.
                let sent = (self.client).try_publish(&topic, QoS::AtLeastOnce, false, reply);
                if sent.is_err() {
                    tracing::debug!("a refusal on {topic} was not sent: the link is busy");
                }
            }
        }
    }

    /// The link is up: subscribe to commands, say online, publish the state afresh.
    fn up(&mut self, cmd_topic: &str) {
        self.published = None;
        if let Err(e) = self.client.try_subscribe(cmd_topic, QoS::AtLeastOnce) {
            tracing::warn!("could not subscribe to {cmd_topic}: {e}");
        }
        let online = json!({ "online": true, "robot": self.identity.robot });
        self.publish_retained("status", &online);
        self.announce(None);
    }

    /// Tells operators (the hub: consoles, the corpus, and the broker once it is up).
    fn announce(&self, reason: Option<String>) {
        let mut view = self.link.view();
        if reason.is_some() {
            view.reason = reason;
        }
        self.state.hub.publish(EventKind::FleetLink(view));
    }

    fn publish_state(&mut self) {
        if self.link.view().state != super::LinkState::Up {
            return;
        }
        let link = self.link.view();
        let state =
            robot_state::snapshot(&self.state, &self.identity, self.battery.as_ref(), &link);
        let text = state.to_string();
        if self.published.as_deref() == Some(text.as_str()) {
            return;
        }
        self.publish_retained("state", &state);
        self.published = Some(text);
    }

    fn publish_retained(&self, leaf: &str, payload: &Value) {
        let topic = topic(&self.identity.robot, leaf);
        let bytes = payload.to_string().into_bytes();
        if let Err(e) = self
            .client
            .try_publish(&topic, QoS::AtLeastOnce, true, bytes)
        {
            tracing::warn!("could not publish {topic}: {e}");
        }
    }

    fn publish_event(&mut self, line: &str) {
        let topic = topic(&self.identity.robot, "events");
        let sent =
            self.client
                .try_publish(topic, QoS::AtLeastOnce, false, line.as_bytes().to_vec());
        match sent {
            Ok(()) if self.dropped > 0 => {
                tracing::warn!(
                    dropped = self.dropped,
                    "MQTT events were dropped while the broker link was down (the corpus has them)"
                );
                self.dropped = 0;
            }
            Ok(()) => {}
            Err(_) => self.dropped += 1,
        }
    }

    /// The server is stopping: say offline (retained) and disconnect cleanly.
    async fn goodbye(self) {
        let robot = &self.identity.robot;
        let offline = robot_state::offline(robot, "the robot's Docent stopped");
        self.publish_retained("status", &offline);
        self.publish_retained("state", &offline);
        let _ = self.client.try_disconnect();
    }
}

/// Runs verified commands one at a time and publishes their signed answers on `reply`.
async fn run_commands(
    state: AppState,
    client: AsyncClient,
    host: String,
    robot: String,
    mut commands: mpsc::Receiver<Verified>,
) {
    let reply = topic(&robot, "reply");
    let mut broker_ip: Option<IpAddr> = None;
    let shutdown = state.life.shutdown.clone();
    loop {
        let command = tokio::select! {
            () = shutdown.cancelled() => return,
            command = commands.recv() => match command {
                Some(command) => command,
                None => return,
            },
        };
        let ip = match broker_ip {
            Some(ip) => ip,
            None => {
                let found = resolve(&host).await;
                broker_ip = found;
                found.unwrap_or(IpAddr::V4(std::net::Ipv4Addr::UNSPECIFIED))
            }
        };
        for frame in commands::run(&state, (ip, &robot), command).await {
            if let Err(e) = client.publish(&reply, QoS::AtLeastOnce, false, frame).await {
                tracing::warn!("could not publish an answer on {reply}: {e}");
            }
        }
    }
}

/// The broker's address, named in the corpus as where the commands came through.
async fn resolve(host: &str) -> Option<IpAddr> {
    if let Ok(ip) = host.parse() {
        return Some(ip);
    }
    let mut found = tokio::net::lookup_host((host, 0)).await.ok()?;
    found.next().map(|a| a.ip())
}
