//! Who speaks when: the policy of each output channel for a command that arrives while another
//! runs (`channels:` in `docent.yaml`) and the priority of each trigger source
//! (`priorities:`). The dispatcher applies them (`dispatch/channels.rs`); the defaults and
//! their reasons are in `docs/CONFIG.md`.

use std::collections::BTreeMap;
use std::fmt;

use crate::Verb;

/// The longest queue a channel may be given: every queue stays small and bounded.
pub const MAX_QUEUE_LIMIT: usize = 20;
/// The highest priority a source may be given (the lowest is 1).
pub const MAX_PRIORITY: u8 = 9;

/// An output channel: the device part that does one thing at a time.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Channel {
    /// `SAY`.
    Speech,
    /// `DISPLAY_PAGE`.
    Touchscreen,
    /// `PROJECT` and `HIGHLIGHT`.
    Projector,
    /// `SET_WAYPOINT`, `DRIVE_START`, `DRIVE_STOP`.
    Drive,
    /// A site-declared verb, its own channel.
    Site(String),
}

impl Channel {
    /// The built-in channels' names in `docent.yaml`.
    pub const BUILT_IN: [&'static str; 4] = ["speech", "touchscreen", "projector", "drive"];

    /// The channel `verb` runs on; `None` for `WAIT`, the dispatcher's own.
    pub fn of(verb: &Verb) -> Option<Channel> {
        Some(match verb {
            Verb::Say => Channel::Speech,
            Verb::DisplayPage => Channel::Touchscreen,
            Verb::Project | Verb::Highlight => Channel::Projector,
            Verb::SetWaypoint | Verb::DriveStart | Verb::DriveStop => Channel::Drive,
            Verb::Wait => return None,
            Verb::Site(name) => Channel::Site(name.to_string()),
        })
    }

    /// Its name in `docent.yaml` and in messages.
    pub fn name(&self) -> &str {
        match self {
            Channel::Speech => "speech",
            Channel::Touchscreen => "touchscreen",
            Channel::Projector => "projector",
            Channel::Drive => "drive",
            Channel::Site(name) => name,
        }
    }
}

impl fmt::Display for Channel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// What a channel does with a command that arrives while another of equal priority runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WhenBusy {
    /// Wait in a bounded queue; a command arriving at a full queue is cancelled.
    Queue,
    /// Cancel what runs (and what waits) and run the new command.
    Replace,
    /// Cancel the new command; what runs goes on.
    Drop,
}

impl WhenBusy {
    /// The word in `docent.yaml`.
    pub fn as_str(self) -> &'static str {
        match self {
            WhenBusy::Queue => "queue",
            WhenBusy::Replace => "replace",
            WhenBusy::Drop => "drop",
        }
    }
}

/// One channel's policy.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChannelPolicy {
    /// What a command arriving while another runs does.
    pub when_busy: WhenBusy,
    /// How many commands may wait (queue policy), 1 to [`MAX_QUEUE_LIMIT`].
    pub queue_limit: usize,
}

impl ChannelPolicy {
    /// A queue of `limit` commands.
    pub const fn queue(limit: usize) -> Self {
        ChannelPolicy {
            when_busy: WhenBusy::Queue,
            queue_limit: limit,
        }
    }

    /// Replace what runs.
    pub const fn replace() -> Self {
        ChannelPolicy {
            when_busy: WhenBusy::Replace,
            queue_limit: 2,
        }
    }
}

/// Every channel's policy (`channels:`), defaults filled in.
#[derive(Clone, Debug, PartialEq)]
pub struct ChannelPolicies {
    /// `speech`: queue of 2 by default.
    pub speech: ChannelPolicy,
    /// `touchscreen`: replace.
    pub touchscreen: ChannelPolicy,
    /// `projector`: replace.
    pub projector: ChannelPolicy,
    /// `drive`: replace.
    pub drive: ChannelPolicy,
    /// Site verbs given a policy by name; the others queue 2.
    pub site: BTreeMap<String, ChannelPolicy>,
}

impl Default for ChannelPolicies {
    fn default() -> Self {
        ChannelPolicies {
            speech: ChannelPolicy::queue(2),
            touchscreen: ChannelPolicy::replace(),
            projector: ChannelPolicy::replace(),
            drive: ChannelPolicy::replace(),
            site: BTreeMap::new(),
        }
    }
}

impl ChannelPolicies {
    /// The policy of a site verb nobody gave one: its commands keep their order, as before.
    pub const SITE_DEFAULT: ChannelPolicy = ChannelPolicy::queue(2);

    /// The policy of `channel`.
    pub fn of(&self, channel: &Channel) -> ChannelPolicy {
        match channel {
            Channel::Speech => self.speech,
            Channel::Touchscreen => self.touchscreen,
            Channel::Projector => self.projector,
            Channel::Drive => self.drive,
            Channel::Site(name) => self.site.get(name).copied().unwrap_or(Self::SITE_DEFAULT),
        }
    }

    /// The policy of a built-in channel by its name, to be changed.
    pub fn built_in_mut(&mut self, name: &str) -> Option<&mut ChannelPolicy> {
        match name {
            "speech" => Some(&mut self.speech),
            "touchscreen" => Some(&mut self.touchscreen),
            "projector" => Some(&mut self.projector),
            "drive" => Some(&mut self.drive),
            _ => None,
        }
    }
}

/// Each trigger source's priority (`priorities:`), 1 to [`MAX_PRIORITY`]; higher wins.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Priorities {
    /// The operator console (and proposals it accepts).
    pub operator: u8,
    /// The HTTP API (its callers hold the operator's or the dialog manager's credential).
    pub http: u8,
    /// The dialog manager.
    pub dm: u8,
    /// The touchscreen: visitors' taps and page timers.
    pub kiosk: u8,
}

impl Priorities {
    /// The sources' names in `docent.yaml`.
    pub const NAMES: [&'static str; 4] = ["operator", "http", "dm", "kiosk"];

    /// The priority of a source by its name, to be changed.
    pub fn by_name_mut(&mut self, name: &str) -> Option<&mut u8> {
        match name {
            "operator" => Some(&mut self.operator),
            "http" => Some(&mut self.http),
            "dm" => Some(&mut self.dm),
            "kiosk" => Some(&mut self.kiosk),
            _ => None,
        }
    }
}

impl Default for Priorities {
    fn default() -> Self {
        Priorities {
            operator: 3,
            http: 3,
            dm: 2,
            kiosk: 1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_verb_but_wait_has_a_channel() {
        assert_eq!(Channel::of(&Verb::Say), Some(Channel::Speech));
        assert_eq!(Channel::of(&Verb::Highlight), Some(Channel::Projector));
        assert_eq!(Channel::of(&Verb::DriveStop), Some(Channel::Drive));
        assert_eq!(Channel::of(&Verb::Wait), None);
        let lights = Channel::of(&Verb::Site("LIGHTS".into()));
        assert_eq!(lights, Some(Channel::Site("LIGHTS".into())));
    }

    #[test]
    fn site_verbs_without_a_policy_queue() {
        let policies = ChannelPolicies::default();
        let lights = Channel::Site("LIGHTS".into());
        assert_eq!(policies.of(&lights), ChannelPolicies::SITE_DEFAULT);
        assert_eq!(policies.of(&Channel::Speech).when_busy, WhenBusy::Queue);
    }
}
