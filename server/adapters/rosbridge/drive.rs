//! What each drive command does on a ROS 2 robot: `SET_WAYPOINT` stores the waypoint,
//! `DRIVE_START` sends the goal and waits until the reported pose is within the tolerance (or
//! Nav2's action says it succeeded), failing at once with the reason when the link is down or
//! lost, `DRIVE_STOP` publishes the stop. A drive cut short (a stop, shutdown, a lost link)
//! publishes the stop as it ends.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use super::{Shared, messages};
use crate::adapters::drive_sim::Waypoint;
use crate::adapters::worker::Task;
use crate::adapters::{Command, Outcome};
use crate::content::{Args, Verb};
use crate::events::{EventKind, LinkState};
use crate::sync::lock;

/// Goal ids within this run.
static GOALS: AtomicU64 = AtomicU64::new(1);

/// The drive's side of the worker.
pub(super) struct DriveTask {
    pub(super) shared: Arc<Shared>,
}

impl Task for DriveTask {
    async fn run(&self, command: &Command) -> Outcome {
        match command.verb {
            Verb::SetWaypoint => match *command.args {
                Args::Waypoint { x, y, heading } => {
                    lock(&self.shared.robot.state).waypoint = Some(Waypoint { x, y, heading });
                    Outcome::Done
                }
                _ => Outcome::Failed("SET_WAYPOINT came without a waypoint".into()),
            },
            Verb::DriveStart => self.drive().await,
            Verb::DriveStop => {
                self.shared.stop();
                Outcome::Done
            }
            _ => Outcome::Failed(format!(
                "the rosbridge drive cannot carry out {}",
                command.verb
            )),
        }
    }
}

impl DriveTask {
    async fn drive(&self) -> Outcome {
        let robot = &self.shared.robot;
        let link = &self.shared.link;
        let (target, from) = {
            let state = lock(&robot.state);
            (state.waypoint, state.pose)
        };
        let Some(target) = target else {
            return Outcome::Failed(
                "no waypoint is set: use SET_WAYPOINT before DRIVE_START".into(),
            );
        };
        // A replacement announced before this drive began concerned an earlier one.
        self.shared.replaced.store(false, Ordering::SeqCst);
        let mut link_watch = link.watch();
        let connection = link_watch.borrow_and_update().connection;
        // Without a heading, face the way there (Nav2 needs an orientation).
        let heading = target.heading.unwrap_or_else(|| match from {
            Some(p) => (target.y - p.y).atan2(target.x - p.x).to_degrees(),
            None => 0.0,
        });
        let config = &robot.config;
        let pose = messages::pose_stamped(&config.frame, target.x, target.y, heading);
        let mut goal_id = None;
        let op = match &config.action {
            Some(action) => {
                let id = format!("docent-goal-{}", GOALS.fetch_add(1, Ordering::Relaxed));
                goal_id = Some(id.clone());
                messages::navigate_to_pose(&id, action, pose)
            }
            None => messages::publish(&config.goal_topic, pose),
        };
        let mut poses = robot.poses.subscribe();
        let mut results = robot.results.subscribe();
        results.borrow_and_update();
        link.clear_held();
        if let Err(reason) = link.send(&op) {
            return Outcome::Failed(format!("{reason}; the robot was not sent anywhere"));
        }
        let mut halt = Halt {
            shared: &self.shared,
            armed: true,
        };
        {
            let mut state = lock(&robot.state);
            state.moving = true;
            state.goal_id.clone_from(&goal_id);
        }
        let mut progress = Progress::new(config.stall);
        loop {
            let pose = lock(&robot.state).pose;
            if let Some(p) = pose {
                let distance = (target.x - p.x).hypot(target.y - p.y);
                if distance <= config.tolerance {
                    break;
                }
                progress.at(distance);
            }
            tokio::select! {
                _ = poses.changed() => {}
                () = progress.stalled() => return Outcome::Failed(progress.reason(target)),
                _ = link_watch.changed() => {
                    let status = link_watch.borrow_and_update().clone();
                    if status.state == LinkState::Down || status.connection != connection {
                        let reason = status.reason.unwrap_or_else(|| "it reconnected".into());
                        return Outcome::Failed(format!(
                            "the link to rosbridge at {} was lost: {reason}",
                            link.url()
                        ));
                    }
                }
                _ = results.changed() => {
                    let result = results.borrow_and_update().clone();
                    if let Some((id, status)) = result
                        && Some(&id) == goal_id.as_ref()
                    {
                        if status == messages::GOAL_SUCCEEDED {
                            break;
                        }
                        lock(&robot.state).goal_id = None;
                        return Outcome::Failed(format!(
                            "Nav2 ended the goal without arriving (action status {status})"
                        ));
                    }
                }
            }
        }
        halt.armed = false;
        drop(halt);
        let at = lock(&robot.state).pose.unwrap_or_default();
        robot
            .hub
            .publish(EventKind::DriveArrived { x: at.x, y: at.y });
        Outcome::Done
    }
}

/// Whether a drive is getting anywhere: a drive that does not come [`PROGRESS_M`] closer to its
/// waypoint within `rosbridge: stall` fails (and its [`Halt`] publishes the stop), rather than
/// waiting for ever on a goal Nav2 refused or dropped without a word.
struct Progress {
    stall: Option<std::time::Duration>,
    closest: Option<f64>,
    deadline: Option<tokio::time::Instant>,
}

/// Metres closer that count as progress: less is a robot standing still with a noisy pose.
const PROGRESS_M: f64 = 0.05;

impl Progress {
    fn new(stall: Option<std::time::Duration>) -> Self {
        let deadline = stall.map(|s| tokio::time::Instant::now() + s);
        Progress {
            stall,
            closest: None,
            deadline,
        }
    }

    /// The robot is `distance` metres from its waypoint now.
    fn at(&mut self, distance: f64) {
        if self.closest.is_none_or(|c| distance < c - PROGRESS_M) {
            self.closest = Some(distance);
            self.deadline = self.stall.map(|s| tokio::time::Instant::now() + s);
        }
    }

    async fn stalled(&self) {
        match self.deadline {
            Some(deadline) => tokio::time::sleep_until(deadline).await,
            None => std::future::pending().await,
        }
    }

    fn reason(&self, target: Waypoint) -> String {
        let stall = self.stall.unwrap_or_default().as_secs_f64();
        let (x, y) = (target.x, target.y);
        match self.closest {
            Some(distance) => format!(
                "the robot came no closer to ({x}, {y}) for {stall:.0} s and is still \
                 {distance:.2} m away: Nav2 may have refused or dropped the goal, or the way \
                 is blocked; it was told to stop (`rosbridge: stall` sets how long to wait)"
            ),
            None => format!(
                "no pose arrived for {stall:.0} s while driving to ({x}, {y}): check that the \
                 robot publishes its pose topic; it was told to stop (`rosbridge: stall` sets \
                 how long to wait)"
            ),
        }
    }
}

/// Whatever ends a drive leaves it not moving; one cut short (a stop, shutdown, a lost link)
/// also publishes the stop, unless the drive channel's next command replaces it.
struct Halt<'a> {
    shared: &'a Shared,
    armed: bool,
}

impl Drop for Halt<'_> {
    fn drop(&mut self) {
        let robot = &self.shared.robot;
        let pose = {
            let mut state = lock(&robot.state);
            state.moving = false;
            if !self.armed {
                state.goal_id = None;
            }
            state.pose.map(|mut p| {
                p.moving = false;
                state.pose = Some(p);
                p
            })
        };
        if let Some(pose) = pose {
            robot.publish_pose(pose);
        }
        let replaced = self.shared.replaced.swap(false, Ordering::SeqCst);
        if self.armed && !replaced {
            self.shared.stop();
        }
    }
}
