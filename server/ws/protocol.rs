//! The websocket protocol's frames (JSON text, tagged by `type`), defined in `docent-protocol`
//! and named here for the websocket layer: what clients send
//! ([`docent_protocol::client_frames`]), what Docent sends them
//! ([`docent_protocol::server_frames`]) and the state they are welcomed with. The frames
//! adapters are sent (`command`, `cancel`) are `docent_protocol::frames`.

pub use docent_protocol::PROTOCOL_VERSION;
pub use docent_protocol::client_frames::*;
pub use docent_protocol::server_frames::*;
pub use docent_protocol::state::{LimitsView, StateView};
