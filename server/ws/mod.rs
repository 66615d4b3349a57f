//! The websocket endpoint `/ws`: kiosk and projector pages, operators, the dialog manager and
//! external adapters all speak the same JSON protocol (`protocol`, `docs/PROTOCOL.md`).
//!
//! Each connection has a reader loop (`connection`) and a writer task (`writer`); when one ends,
//! the other stops. Outgoing frames pass through a bounded [`crate::wire::outbox::Outbox`], so a slow
//! client is dropped instead of slowing others. The reader hands each frame to the
//! connection's `session`, the one place that keeps (and changes) what the connection
//! remembers; it routes the frame to a handler, lending it the `client` (id, address, server,
//! outbox): `hello` (credentials, welcome, feeds), `triggers` (trigger, stop, context, page;
//! the kiosk rules), `initiative` (proposals and corpus marks), `signal` (WebRTC signalling
//! relay), `reports` (devices' reports on their commands) and `recording` (a kiosk's clock
//! and its recordings' reports). Handlers return what the session must remember.
//! `violation` maps a broken websocket frame to its RFC 6455 close code; `allowance` is what a
//! connection without a credential may send (frames, pings), per connection.
//! `notices` tells a client what became of its commands and kiosks who is speaking;
//! `captions` tells the screens and consoles what is being said, while it is said; `media`
//! tells operators the media being converted, and kiosks the pages whose media became ready.
//! `embedded` is the same session without a websocket, for other transports (MQTT).

mod allowance;
mod attract;
mod backlog;
mod captions;
mod client;
mod connection;
mod diagnose;
mod embedded;
mod hello;
mod initiative;
mod media;
mod notices;
pub mod protocol;
mod recording;
mod reports;
mod robot;
mod session;
mod signal;
mod triggers;
mod violation;
mod writer;

pub use allowance::{FRAME_BURST, FRAMES_PER_SECOND, PING_BURST, PINGS_PER_SECOND};
pub use captions::Captions;
pub use connection::ws_upgrade;
pub use embedded::EmbeddedSession;
pub use media::tell_media;
pub use notices::deliver as deliver_notices;
pub use robot::ROBOT_DATA_BYTES;
