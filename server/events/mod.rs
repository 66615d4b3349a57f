//! Events: everything that happens (act triggered, command sent/started/done/failed, display
//! changed, pose, context changed, stop, proposals, corpus marks, clients coming and going) as one [`EventKind`] enum,
//! stamped with a sequence number and times by the [`Hub`], which hands each event to the
//! corpus writer (lossless) and to websocket subscribers (broadcast, may lag).
//!
//! The serialized form is a compatibility boundary: it is both the corpus log line and the
//! `event` frame sent to operator and dialog-manager clients (see `docs/CORPUS.md`).

mod attract;
mod hub;
mod kind;
mod logged;
mod origin;
mod recording;
mod robot;
mod robot_link;
mod session;
mod stamped;
mod touch;

pub use attract::{AttractEnd, AttractState};
pub use hub::{Committer, CorpusFeed, EVENT_CHANNEL_CAPACITY, HISTORY_LEN, Hub, Interest};
pub use kind::EventKind;
pub use logged::{LogUnwritable, Logged};
pub use origin::{ActRef, ClientRole, Source};
pub use recording::{FailureCode, RecordingEvent, StopReason, Track};
pub use robot::{ROBOT_EVENT_NAME_CHARS, RobotEvent, robot_event_name_problem};
pub use robot_link::{LinkState, RobotLinkEvent};
pub use session::{Consent, SessionEnd};
pub use stamped::Event;
pub use touch::{ELEMENT_CHARS, KioskCause, element_description};

/// Version of the event format, written into every corpus line as `v`. 2: `command.sent`
/// carries the parsed `args`. 3: a session's events are in its own log, with `session_us`;
/// `session.ended` says why, and its `client` is left out when the server ended it. 4: a
/// visitor's touch is a `touch` event; a kiosk's `act.triggered` or page change may be its
/// timer's, idle return's or script's doing, so readers no longer take them for touches.
pub const EVENT_FORMAT_VERSION: u32 = 4;
