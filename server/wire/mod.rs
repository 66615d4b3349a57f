//! What goes on the wire to a client, shared by the websocket layer (`ws`) and the adapters
//! that send to screens and external adapter processes, so neither imports the other.
//!
//! - `outbox`: a client's bounded outgoing queue and the [`outbox::Frame`] it carries.
//! - `linger`: notices that wait up to 2 ms to ride along with a client's next frames.
//!
//! The frames themselves and [`ErrorCode`] are `docent-protocol`'s ([`ErrorCode`] re-exported).

pub mod linger;
pub mod outbox;

pub use docent_protocol::ErrorCode;
