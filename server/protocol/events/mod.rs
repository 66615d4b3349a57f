//! Events: everything that happens (act triggered, command sent/started/done/failed, display
//! changed, pose, context changed, stop, proposals, corpus marks, clients coming and going) as
//! one [`EventKind`] enum, and the [`Event`] the runtime's hub stamps it into.
//!
//! The serialized form is a compatibility boundary: it is both the corpus log line and the
//! `event` frame sent to operator and dialog-manager clients (see `docs/CORPUS.md`). The
//! corpus reads its lines back through the same types ([`Line`]).

mod attract;
mod bundle;
mod client;
mod command;
mod corpus;
mod kind;
mod line;
mod origin;
mod proposal;
mod recording;
mod robot;
mod robot_link;
mod session;
mod stamped;
mod touch;

pub use attract::{AttractEnd, AttractEnded, AttractStarted, AttractState};
pub use bundle::{BundleRefused, BundleReloaded, BundleWatchFailed, MediaConverted, MediaFailed};
pub use client::{ClientConnected, ClientLeft, ClientRefused, RequestRefused};
pub use command::{CommandCancelled, CommandDone, CommandFailed, CommandSent, CommandStarted};
pub use corpus::{CorpusFault, CorpusGap, CorpusRecreated, CorpusUnwritable, CorpusWritable};
pub use kind::EventKind;
pub use line::{Head, Line, LineEvent, is_event_type, is_pose};
pub use origin::{ActRef, ClientRole, Ended, Source};
pub use proposal::{ProposalAccepted, ProposalDismissed, ProposalMade, ProposalWithdrawn};
pub use recording::{FailureCode, RecordingEvent, StopReason, Track};
pub use robot::{
    ROBOT_EVENT_NAME_CHARS, ReactionFailed, RobotEvent, TopicRefused, robot_event_name_problem,
};
pub use robot_link::{LinkState, RobotLinkEvent};
pub use session::{
    Consent, ConsentChanged, NoteWritten, SessionEnd, SessionEnded, SessionStarted,
    SituationMarked, VisitorGroup,
};
pub use stamped::Event;
pub use touch::{ELEMENT_CHARS, KioskCause, Touch, element_description};
