//! `docent-protocol`: every format Docent exchanges with another program, and only those:
//! the events (each corpus line and each `event` frame, [`events`]), the websocket frames
//! clients send ([`client_frames`]) and are sent ([`server_frames`], with the [`state`] they
//! are welcomed with), the codes of `error` frames and HTTP error bodies ([`ErrorCode`]), the
//! frames adapters are sent ([`frames`]), what the projector and a fleet link report, and the
//! versions of both formats.
//! A compatibility boundary: change a shape only with a version bump (`docs/PROTOCOL.md`,
//! `docs/CORPUS.md`).
//!
//! Depends on `docent-content` (an event carries a command's parsed `Args`, a `Language`, a
//! reload's `Diagnostic`s) and on no async runtime: the corpus reads these types without one.
//!
//! Map:
//! - `events/`: [`events::EventKind`] and its parts, one file per family (`origin.rs`: who
//!   triggered; `command.rs`; `proposal.rs`; `session.rs`: a visitor session, its marks and
//!   why it ended; `recording.rs`; `robot.rs`; `robot_link.rs`; `bundle.rs`: reloads and
//!   media; `client.rs`; `corpus.rs`: the log's own faults; `touch.rs`; `attract.rs`),
//!   `stamped.rs`, the [`events::Event`] line, and `line.rs`, the same line read back
//!   ([`events::Line`]).
//! - `open`: [`Open`], a code as written by a newer Docent, read back.
//! - `client_frames`: [`client_frames::ClientFrame`], what a websocket client sends (its
//!   `hello` and `trigger` as structs of their own), and the HTTP trigger's body,
//!   [`client_frames::TriggerOptions`].
//! - `server_frames`: one function per frame Docent sends a client (`welcome`, answers,
//!   notices, `event`), and the data they carry ([`server_frames::Triggered`], also the HTTP
//!   trigger's answer).
//! - `state`: [`state::StateView`], the state a client is welcomed with, and its parts
//!   ([`state::Display`], [`state::Pose`], [`state::ReloadView`]).
//! - `documented_frames` (tests only): the frames against docs/PROTOCOL.md's examples.
//! - `error_code`: [`ErrorCode`], every code an `error` frame or an HTTP error body carries.
//! - `frames`: the `command` and `cancel` frames adapters and screens are sent.
//! - `projector`: [`ProjectorState`]; `fleet_link`: a robot's broker link as shown.
//! - `tags`: the type names of an enum tagged by `type`, asked of serde (never listed twice).

pub mod client_frames;
pub mod events;
pub mod fleet_link;
pub mod frames;
pub mod server_frames;
pub mod state;

#[cfg(test)]
mod documented_frames;
mod error_code;
mod open;
mod projector;
mod tags;

pub use error_code::ErrorCode;
pub use open::Open;
pub use projector::ProjectorState;

/// The protocol version sent in `welcome`. 4: `command` frames carry the parsed `args`.
pub const PROTOCOL_VERSION: u32 = 4;

/// Version of the event format, written into every corpus line as `v`. 2: `command.sent`
/// carries the parsed `args`. 3: a session's events are in its own log, with `session_us`;
/// `session.ended` says why, and its `client` is left out when the server ended it. 4: a
/// visitor's touch is a `touch` event; a kiosk's `act.triggered` or page change may be its
/// timer's, idle return's or script's doing, so readers no longer take them for touches.
pub const EVENT_FORMAT_VERSION: u32 = 4;
