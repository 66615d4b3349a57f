//! What the projector reports doing, as `/api/state`, `display.changed` events and operators
//! show it.

use serde::{Deserialize, Serialize};

/// What the projector is doing with what the display state names, as it reported.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ProjectorState {
    /// Nothing on screen.
    #[default]
    Black,
    /// Sent; no projector has reported it shown yet.
    Loading,
    /// A picture, or highlight areas, painted.
    Shown,
    /// A film playing.
    Playing,
    /// A film ended, its last frame held on screen.
    Held,
}
