//! The `sim` drive: a simulated base that moves in a straight line toward its waypoint at the
//! configured speed, publishes its pose a few times a second, reports arrival and stops when
//! its command is cancelled (a `DRIVE_STOP` or a global stop). A tour runs without a robot.

use std::sync::{Arc, Mutex};
use std::time::Duration;

use serde::Serialize;

use crate::adapters::worker::{Task, Worker};
use crate::adapters::{Adapter, AdapterStatus, CancelScope, Command, Outcome, Reply};
use crate::content::config::DriveConfig;
use crate::content::{Args, Verb};
use crate::events::{EventKind, Hub};
use crate::lifecycle::Lifecycle;
use crate::sync::lock;
pub use docent_protocol::state::Pose;

/// A waypoint: position and optional final heading.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Waypoint {
    /// Metres.
    pub x: f64,
    /// Metres.
    pub y: f64,
    /// Degrees; keep the travel heading when absent.
    pub heading: Option<f64>,
}

#[derive(Default)]
struct DriveState {
    pose: Pose,
    waypoint: Option<Waypoint>,
}

/// The simulated drive base.
pub struct DriveSim {
    worker: Worker,
    state: Arc<Mutex<DriveState>>,
}

impl DriveSim {
    /// A base at the origin (or the bounds' lower corner), driving as `config` says.
    pub fn new(config: &DriveConfig, hub: Hub, life: &Lifecycle) -> Self {
        let mut start = DriveState::default();
        if let Some(b) = config.bounds.filter(|b| !b.contains(0.0, 0.0)) {
            (start.pose.x, start.pose.y) = (b.min_x, b.min_y);
        }
        let state = Arc::new(Mutex::new(start));
        let task = Base {
            state: Arc::clone(&state),
            hub,
            speed: config.speed,
            tick: Duration::from_secs_f64(1.0 / config.pose_hz),
        };
        DriveSim {
            worker: Worker::start("sim", task, life),
            state,
        }
    }

    /// The current pose.
    pub fn pose(&self) -> Pose {
        lock(&self.state).pose
    }

    /// The current waypoint.
    pub fn waypoint(&self) -> Option<Waypoint> {
        lock(&self.state).waypoint
    }
}

struct Base {
    state: Arc<Mutex<DriveState>>,
    hub: Hub,
    speed: f64,
    tick: Duration,
}

impl Base {
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

    async fn drive(&self) -> Outcome {
        let Some(target) = lock(&self.state).waypoint else {
            return Outcome::Failed(
                "no waypoint is set: use SET_WAYPOINT before DRIVE_START".into(),
            );
        };
        // Whatever ends this future (arrival, a stop, shutdown) leaves the base standing.
        let _halt = Halt { base: self };
        let step = self.speed * self.tick.as_secs_f64();
        let mut ticks = tokio::time::interval(self.tick);
        ticks.tick().await;
        loop {
            ticks.tick().await;
            let pose = {
                let mut state = lock(&self.state);
                let p = &mut state.pose;
                let (dx, dy) = (target.x - p.x, target.y - p.y);
                let distance = dx.hypot(dy);
                p.moving = distance > step;
                if p.moving {
                    p.heading = dy.atan2(dx).to_degrees();
                    p.x += dx / distance * step;
                    p.y += dy / distance * step;
                } else {
                    (p.x, p.y) = (target.x, target.y);
                    p.heading = target.heading.unwrap_or(p.heading);
                }
                *p
            };
            self.publish_pose(pose);
            if !pose.moving {
                self.hub.publish(EventKind::DriveArrived {
                    x: pose.x,
                    y: pose.y,
                });
                return Outcome::Done;
            }
        }
    }
}

struct Halt<'a> {
    base: &'a Base,
}

impl Drop for Halt<'_> {
    fn drop(&mut self) {
        let pose = {
            let mut state = lock(&self.base.state);
            let was_moving = state.pose.moving;
            state.pose.moving = false;
            was_moving.then_some(state.pose)
        };
        if let Some(pose) = pose {
            self.base.publish_pose(pose);
        }
    }
}

impl Task for Base {
    async fn run(&self, command: &Command) -> Outcome {
        match command.verb {
            Verb::SetWaypoint => match *command.args {
                Args::Waypoint { x, y, heading } => {
                    lock(&self.state).waypoint = Some(Waypoint { x, y, heading });
                    Outcome::Done
                }
                _ => Outcome::Failed("SET_WAYPOINT came without a waypoint".into()),
            },
            Verb::DriveStart => self.drive().await,
            // The dispatcher cancels any running drive before a DRIVE_STOP gets here.
            Verb::DriveStop => Outcome::Done,
            _ => Outcome::Failed(format!("the drive cannot carry out {}", command.verb)),
        }
    }
}

impl Adapter for DriveSim {
    fn name(&self) -> &'static str {
        "sim"
    }

    fn submit(&self, command: Command, reply: Reply) {
        self.worker.submit(command, reply);
    }

    fn cancel(&self, scope: CancelScope<'_>, reason: &str) {
        self.worker.cancel(scope, reason);
    }

    fn status(&self) -> AdapterStatus {
        self.worker.status()
    }
}
