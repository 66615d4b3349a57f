//! Device adapters: where commands go to be carried out. One [`Adapter`] trait; the
//! [`Router`] maps each verb to the adapter `docent.yaml` names (with embedded defaults that
//! need no hardware). Adapters queue their own commands and run them strictly in order, so
//! speech, display and drive run side by side as the paper's submodules do.
//!
//! Map:
//! - `command`: a dispatched command and its [`Reply`] (the only way outcomes are reported).
//! - `worker`: a queue that runs one command at a time and can be cancelled.
//! - `speech_log`, `speech_espeak`: speech adapters (each a `Worker` with its own task); `display`: kiosk and projector state;
//!   `drive_sim`: the simulated drive base; `external`: external adapter processes over the websocket (adapter name `ws`);
//!   `rosbridge`: a ROS 2 robot through a rosbridge v2 server.
//! - `router`: verb → adapter, built from the site configuration.

mod command;
mod display;
mod drive_sim;
pub mod external;
pub mod rosbridge;
mod router;
mod speech_espeak;
mod speech_log;
mod worker;

pub use command::{Command, Outcome, Reply};
pub use display::{Display, DisplayAdapter, DisplayState, ProjectorState, Screen, ScreenReport};
pub use drive_sim::{DriveSim, Pose};
pub use external::ExternalAdapters;
pub use rosbridge::RosbridgeDrive;
pub use router::{Devices, Router};
pub use speech_espeak::{
    SpeechOutput, espeak_adapter, espeak_available, espeak_can_play, espeak_voices,
};
pub use speech_log::log_adapter;
pub use worker::Worker;

use crate::content::Verb;

/// Which commands a cancellation concerns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CancelScope<'a> {
    /// Everything queued or running.
    All,
    /// Only commands with this verb (an interrupting trigger cancels speech).
    Verb(&'a Verb),
}

/// What an adapter is doing, for `GET /api/state`.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct AdapterStatus {
    /// Commands waiting in its queue.
    pub queued: usize,
    /// The command it is executing: `VERB argument`.
    pub current: Option<String>,
}

/// A device adapter. Implementations queue work and return at once: `submit` runs on the
/// dispatcher's hot path.
pub trait Adapter: Send + Sync {
    /// The adapter's name in `docent.yaml` and in events.
    fn name(&self) -> &'static str;

    /// Queues a command. Its outcome must be reported through `reply`.
    fn submit(&self, command: Command, reply: Reply);

    /// Drops queued commands and cuts the current one short, within `scope`.
    fn cancel(&self, scope: CancelScope<'_>, reason: &str);

    /// What it is doing now.
    fn status(&self) -> AdapterStatus;
}
