//! The `rosbridge` drive: Docent drives a ROS 2 robot and hears its sensors through a
//! rosbridge v2 server (`rosbridge:` in `docent.yaml`). `SET_WAYPOINT` stores the waypoint;
//! `DRIVE_START` publishes it as a `geometry_msgs/msg/PoseStamped` goal (Nav2's `/goal_pose`)
//! or sends it as a `NavigateToPose` action goal, and is done when the pose the robot reports
//! is within the arrival tolerance; `DRIVE_STOP`, a stop and a cut-short drive publish the
//! configured stop (a zero `Twist`, an `Empty` on a stop topic, an action cancel), held for the
//! next connection when the link is down. The pose topic becomes `pose` events; topics the
//! site lists become robot events through the [`RobotInbox`].
//!
//! Map:
//! - `mod.rs`: [`RosbridgeDrive`], the adapter, and the state its parts share.
//! - `link.rs`: the connection, its reconnection and its state (`robot.link` events).
//! - `backoff.rs`: the waits between attempts, exponential with jitter.
//! - `messages.rs`: rosbridge operations out, poses in.
//! - `drive.rs`: what each drive command does.
//! - `inbound.rs`: what each arriving message becomes (a pose, a robot event).

mod backoff;
mod drive;
mod inbound;
mod link;
mod messages;
#[cfg(test)]
mod tests;

use std::collections::HashSet;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;

use serde_json::Value;
use tokio::sync::watch;

use crate::adapters::drive_sim::{Pose, Waypoint};
use crate::adapters::worker::Worker;
use crate::adapters::{Adapter, AdapterStatus, CancelScope, Command, Reply};
use crate::content::Verb;
use crate::content::config::RosbridgeConfig;
use crate::events::{EventKind, Hub};
use crate::lifecycle::Lifecycle;
use crate::robot::RobotInbox;
use crate::sync::lock;

pub use link::LinkStatus;
use link::{Link, LinkPlan};

/// What the robot last told and what Docent asked of it.
#[derive(Default)]
struct RobotState {
    /// The last pose reported, if any yet.
    pose: Option<Pose>,
    /// The stored waypoint.
    waypoint: Option<Waypoint>,
    /// Whether a drive command runs.
    moving: bool,
    /// When the last `pose` event went out (thinned to `inbound::POSE_EVENT_GAP`).
    last_pose_event: Option<Instant>,
    /// The running `NavigateToPose` goal's id, to cancel it.
    goal_id: Option<String>,
    /// Topics whose problem (a message too large, a pose without a position) was told already.
    refusals_told: HashSet<String>,
}

/// What the link's inbound handler and the drive share.
struct Robot {
    config: RosbridgeConfig,
    hub: Hub,
    inbox: RobotInbox,
    state: Mutex<RobotState>,
    /// Bumped on every pose, so a drive wakes to judge arrival.
    poses: watch::Sender<u64>,
    /// The last action result: goal id and status.
    results: watch::Sender<Option<(String, u64)>>,
}

impl Robot {
    fn publish_pose(&self, pose: Pose) {
        let Pose {
            x,
            y,
            heading,
            moving,
        } = pose;
        self.hub.publish(EventKind::Pose {
            x,
            y,
            heading,
            moving,
            frame: None,
        });
    }
}

/// The adapter and the link under it.
struct Shared {
    robot: Arc<Robot>,
    link: Arc<Link>,
    /// The running drive is being replaced by the drive channel's next command (its policy or
    /// a higher priority): the next goal preempts it, and a stop published now could reach the
    /// robot after that goal (another topic) and halt it there.
    replaced: AtomicBool,
}

impl Shared {
    /// Publishes every configured stop; held for the next connection when the link is down.
    fn stop(&self) {
        let config = &self.robot.config;
        let mut ops: Vec<Value> = Vec::new();
        if let Some(topic) = &config.cmd_vel {
            ops.push(messages::publish(topic, messages::zero_twist()));
        }
        if let Some(topic) = &config.stop_topic {
            ops.push(messages::publish(topic, serde_json::json!({})));
        }
        let goal = lock(&self.robot.state).goal_id.take();
        if let (Some(action), Some(id)) = (&config.action, goal) {
            ops.push(messages::cancel_action_goal(&id, action));
        }
        if ops.is_empty() {
            tracing::warn!(
                "a stop was asked for, but `rosbridge:` sets no cmd_vel, stop_topic or action to send it on"
            );
            return;
        }
        self.link.send_or_hold(ops);
    }
}

/// The `rosbridge` drive adapter (also the link that brings topic events when the drive is
/// another adapter).
pub struct RosbridgeDrive {
    worker: Worker,
    shared: Arc<Shared>,
}

impl RosbridgeDrive {
    /// Starts the link to `config.url` (which the config check made sure of) and the drive.
    pub fn start(
        config: &RosbridgeConfig,
        url: String,
        hub: Hub,
        inbox: RobotInbox,
        life: &Lifecycle,
    ) -> Self {
        let robot = Arc::new(Robot {
            config: config.clone(),
            hub: hub.clone(),
            inbox,
            state: Mutex::new(RobotState::default()),
            poses: watch::channel(0).0,
            results: watch::channel(None).0,
        });
        let link = Link::start(
            url,
            plan(config),
            inbound::handler(Arc::clone(&robot)),
            hub,
            life,
        );
        let shared = Arc::new(Shared {
            robot,
            link,
            replaced: AtomicBool::new(false),
        });
        let task = drive::DriveTask {
            shared: Arc::clone(&shared),
        };
        RosbridgeDrive {
            worker: Worker::start("rosbridge", task, life),
            shared,
        }
    }

    /// The robot's last reported pose.
    pub fn pose(&self) -> Option<Pose> {
        lock(&self.shared.robot.state).pose
    }

    /// The stored waypoint.
    pub fn waypoint(&self) -> Option<Waypoint> {
        lock(&self.shared.robot.state).waypoint
    }

    /// The link's state.
    pub fn link_status(&self) -> LinkStatus {
        self.shared.link.status()
    }
}

/// What the link (re)makes on every connection.
fn plan(config: &RosbridgeConfig) -> LinkPlan {
    let mut plan = LinkPlan::default();
    if config.action.is_none() {
        plan.advertise.push((
            config.goal_topic.clone(),
            "geometry_msgs/msg/PoseStamped".into(),
        ));
    }
    if let Some(topic) = &config.cmd_vel {
        plan.advertise
            .push((topic.clone(), "geometry_msgs/msg/Twist".into()));
    }
    if let Some(topic) = &config.stop_topic {
        plan.advertise
            .push((topic.clone(), "std_msgs/msg/Empty".into()));
    }
    plan.subscribe.push((
        config.pose_topic.clone(),
        config.pose_type.type_name().into(),
    ));
    for event in &config.events {
        if event.topic != config.pose_topic {
            plan.subscribe
                .push((event.topic.clone(), event.message_type.clone()));
        }
    }
    plan
}

impl Adapter for RosbridgeDrive {
    fn name(&self) -> &'static str {
        "rosbridge"
    }

    fn submit(&self, command: Command, reply: Reply) {
        self.worker.submit(command, reply);
    }

    /// Cancels. A stop (everything cancelled: Stop, `DRIVE_STOP`) publishes the stop whether
    /// or not a drive was running, as the robot may be moving on a goal Docent no longer knows
    /// about; a drive cancelled alone is being replaced by the drive channel's next command,
    /// whose goal preempts it.
    fn cancel(&self, scope: CancelScope<'_>, reason: &str) {
        match scope {
            CancelScope::All => {
                self.worker.cancel(scope, reason);
                self.shared.stop();
            }
            CancelScope::Verb(verb) => {
                if *verb == Verb::DriveStart {
                    self.shared.replaced.store(true, Ordering::SeqCst);
                }
                self.worker.cancel(scope, reason);
            }
        }
    }

    fn status(&self) -> AdapterStatus {
        self.worker.status()
    }
}
