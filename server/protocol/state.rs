//! The state a websocket client is sent on `welcome` and after falling behind (`state`
//! frames), and the plain data it is made of. The runtime keeps these values current
//! (`adapters::display`, the drives, `reload::status`); here is only their serialized shape.
//! Also the server's limits as `GET /api/state` reports them ([`LimitsView`]).

use serde::Serialize;

use docent_content::config::ServerLimits;
use docent_content::{Area, Diagnostic, Language, MediaKind};

use crate::ProjectorState;
use crate::client_frames::MAX_FRAME_BYTES;

/// The state a client gets on `welcome` and after falling behind.
#[derive(Debug, Serialize)]
pub struct StateView {
    /// What the touchscreen and projector show.
    pub display: Display,
    /// The drive's pose: the simulated base's, or the ROS robot's last reported one.
    pub pose: Option<Pose>,
    /// The current context.
    pub context: String,
    /// The visitor's language.
    pub language: Language,
    /// Live reload: a refused save's problems, a folder that cannot be watched, settings not
    /// yet in effect (the operator console's banner).
    pub reload: ReloadView,
    /// While the corpus log cannot be written: what the operator is told (the words of the
    /// last `corpus.unwritable`); left out while it can.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub corpus: Option<String>,
}

/// What the touchscreen and projector show.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Display {
    /// Page under `pages/` on the touchscreen.
    pub page: Option<String>,
    /// File under `media/` on the projector; `None` is black.
    pub projector: Option<String>,
    /// Whether the projector shows `projector` as a picture or plays it as a video.
    pub projector_kind: Option<MediaKind>,
    /// The `HIGHLIGHT` argument lit on the projector instead of a file, as written; `None`
    /// when cleared.
    pub highlight: Option<String>,
    /// The areas of `highlight`, parsed at load: what the projector draws.
    pub highlight_areas: Option<Vec<Area>>,
    /// What the projector reported about `projector` or `highlight`.
    pub projector_state: ProjectorState,
}

/// Where the base is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Pose {
    /// Metres.
    pub x: f64,
    /// Metres.
    pub y: f64,
    /// Degrees, counter-clockwise from the x axis.
    pub heading: f64,
    /// Whether it is driving.
    pub moving: bool,
}

/// The live-reload part of the state a client is welcomed with (`state.reload`).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ReloadView {
    /// The problems of the last save when it was refused; `None` once a good save is live.
    pub refused: Option<Vec<Diagnostic>>,
    /// Why the bundle folder cannot be watched (deleted, renamed, a watcher error).
    pub trouble: Option<String>,
    /// Settings changed since start-up that are not in effect yet, as sentences.
    pub not_applied: Vec<String>,
    /// Media files still converting, or that could not be converted; left out when none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub media: Vec<MediaView>,
}

/// A media file of the bundle on its way to Chromium (`state.reload.media` and the `media`
/// frame): only files not ready are listed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MediaView {
    /// The file from the bundle folder (`media/Exhibit/video.mpg`).
    pub file: String,
    /// Its format as authors know it (`MPEG-1/2`, `HEIC`).
    pub format: String,
    /// How far it is.
    pub state: MediaState,
    /// Percent converted, when known (films).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub percent: Option<u8>,
    /// Why it cannot be shown (`failed` only), with what to do.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
}

/// Where a media file is on its way to Chromium.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MediaState {
    /// Queued behind other files.
    Waiting,
    /// ffmpeg is converting it.
    Converting,
    /// It cannot be converted: showing it fails with the reason.
    Failed,
}

/// The server's limits in force (`GET /api/state`'s `limits`): `docent.yaml`'s `server:`
/// settings as Docent started with them, in the same sections, and the open-files limit they
/// need. A reload does not change them.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LimitsView {
    /// Connections one address and all clients may hold.
    pub connections: ConnectionsView,
    /// How long a request may take to arrive.
    pub timeouts: TimeoutsView,
    /// The largest websocket message and text frame.
    pub messages: MessagesView,
    /// Frames that may wait for one websocket client.
    pub queues: QueuesView,
    /// Files the process may open (its soft `RLIMIT_NOFILE`, raised at start-up); `null` when
    /// unlimited.
    pub open_files: Option<u64>,
}

/// `limits.connections`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ConnectionsView {
    /// Per client address (an IPv6 /64 counts as one).
    pub per_address: usize,
    /// In all.
    pub total: usize,
}

/// `limits.timeouts`, in milliseconds.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TimeoutsView {
    /// A request's headers.
    pub headers_ms: u64,
    /// A request's body, after its headers.
    pub body_ms: u64,
}

/// `limits.messages`, in bytes.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MessagesView {
    /// A larger message closes the connection with 1009.
    pub max_bytes: usize,
    /// A larger text frame is answered `frame-too-large` ([`MAX_FRAME_BYTES`]).
    pub max_frame_bytes: usize,
}

/// `limits.queues`, in frames.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct QueuesView {
    /// Frames waiting for one client.
    pub per_client: usize,
}

impl LimitsView {
    /// The view of `limits`, with the process's open-files limit.
    pub fn new(limits: &ServerLimits, open_files: Option<u64>) -> Self {
        LimitsView {
            connections: ConnectionsView {
                per_address: limits.per_address,
                total: limits.total,
            },
            timeouts: TimeoutsView {
                headers_ms: millis(limits.header_timeout),
                body_ms: millis(limits.body_timeout),
            },
            messages: MessagesView {
                max_bytes: limits.max_message_bytes,
                max_frame_bytes: MAX_FRAME_BYTES,
            },
            queues: QueuesView {
                per_client: limits.queue_per_client,
            },
            open_files,
        }
    }
}

/// Whole milliseconds of `duration` (at most `u64::MAX`).
fn millis(duration: std::time::Duration) -> u64 {
    u64::try_from(duration.as_millis()).unwrap_or(u64::MAX)
}
