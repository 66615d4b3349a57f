//! The runtime's side of events: the [`Hub`] that stamps each [`EventKind`] and fans it out
//! (to the corpus writer, lossless; to websocket subscribers, broadcast, may lag), and how far
//! the corpus log is written ([`Logged`]). The events themselves, their parts and their
//! format version are `docent-protocol`'s, re-exported here.

mod hub;
mod logged;
#[cfg(test)]
mod writer_tests;

pub use docent_protocol::EVENT_FORMAT_VERSION;
pub use docent_protocol::events::*;
pub use hub::{CorpusFeed, EVENT_CHANNEL_CAPACITY, HISTORY_LEN, Hub, Interest};
pub use logged::{LogUnwritable, Logged};
