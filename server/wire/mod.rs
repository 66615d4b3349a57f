//! What goes on the wire to a client, shared by the websocket layer (`ws`) and the adapters
//! that send to screens and external adapter processes, so neither imports the other.
//!
//! - `outbox`: a client's bounded outgoing queue and the [`outbox::Frame`] it carries.
//! - `linger`: notices that wait up to 2 ms to ride along with a client's next frames.
//! - `frames`: the server→client frames adapters send (`command`, `cancel`).
//! - `error_code`: [`ErrorCode`], every code an `error` frame or an HTTP error body carries.

mod error_code;
pub mod frames;
pub mod linger;
pub mod outbox;

pub use error_code::ErrorCode;
