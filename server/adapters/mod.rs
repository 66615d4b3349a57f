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
mod speech_choice;
mod speech_espeak;
mod speech_log;
mod worker;

pub use command::{Command, CurrentCommand, Outcome, Reply};
pub use display::{Display, DisplayAdapter, DisplayState, ProjectorState, Screen, ScreenReport};
pub use drive_sim::{DriveSim, Pose};
pub use external::ExternalAdapters;
pub use rosbridge::RosbridgeDrive;
pub use router::{Devices, Router};
pub use speech_choice::speech_adapter;
pub use speech_espeak::{
    HANG_GRACE, SpeechOutput, espeak_adapter, espeak_available, espeak_can_play, espeak_voices,
    hang_limit,
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
#[derive(Clone, Debug, Default)]
pub struct AdapterStatus {
    /// Commands waiting in its queue.
    pub queued: usize,
    /// The command it is executing.
    pub current: Option<CurrentCommand>,
}

/// Serialized as `GET /api/state` has always sent it (`queued`, and `current` as the text
/// `VERB argument`), plus `current_verb` while a command runs, so that the console reads the
/// verb instead of splitting the text.
impl serde::Serialize for AdapterStatus {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let fields = if self.current.is_some() { 3 } else { 2 };
        let mut s = serializer.serialize_struct("AdapterStatus", fields)?;
        s.serialize_field("queued", &self.queued)?;
        s.serialize_field("current", &self.current.as_ref().map(|c| c.to_string()))?;
        if let Some(current) = &self.current {
            s.serialize_field("current_verb", current.verb.as_str())?;
        }
        s.end()
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn a_status_is_sent_as_verb_and_argument_text_with_the_verb_beside_it() {
        let status = AdapterStatus {
            queued: 2,
            current: Some(CurrentCommand {
                verb: Verb::DisplayPage,
                arg: Some("Welcome/Welcome.html".into()),
            }),
        };
        assert_eq!(
            serde_json::to_value(&status).ok(),
            Some(json!({
                "queued": 2,
                "current": "DISPLAY_PAGE Welcome/Welcome.html",
                "current_verb": "DISPLAY_PAGE",
            }))
        );
    }

    #[test]
    fn an_idle_status_is_sent_as_before() {
        let text = serde_json::to_string(&AdapterStatus::default()).ok();
        assert_eq!(text.as_deref(), Some(r#"{"queued":0,"current":null}"#));
    }

    #[test]
    fn only_a_say_with_text_is_spoken() {
        let say = |arg: Option<&str>| CurrentCommand {
            verb: Verb::Say,
            arg: arg.map(Into::into),
        };
        assert_eq!(say(Some("Hello there")).spoken(), Some("Hello there"));
        assert_eq!(say(None).spoken(), None);
        let site = CurrentCommand {
            verb: Verb::Site("SAY_LOUD".into()),
            arg: Some("Hello".into()),
        };
        assert_eq!(site.spoken(), None);
    }
}
