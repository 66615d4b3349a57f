//! Site settings from a bundle's optional `docent.yaml`, in validated form. The raw YAML shape
//! and its parsing live in `config_file.rs`; this file holds what the rest of Docent reads.
//! Documented for people in `docs/CONFIG.md`.

use std::collections::BTreeMap;
use std::time::Duration;

/// Which adapter serves a verb. The route table is built from these, never from `match` arms
/// spread over the code.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AdapterKind {
    /// `espeak`: an `espeak-ng` process per utterance.
    Espeak,
    /// `log`: records the command and marks it done after an estimated duration.
    Log,
    /// `ws`: external adapter processes connected over the websocket.
    Ws,
    /// `browser`: speech by the kiosk page itself (Web Speech API); the shell connects as a
    /// websocket adapter for `SAY`.
    Browser,
    /// `display`: the server's display state, pushed to kiosk and projector clients.
    Display,
    /// `sim`: the built-in simulated drive base.
    DriveSim,
}

impl AdapterKind {
    /// The name used in `docent.yaml` and in events.
    pub fn as_str(self) -> &'static str {
        match self {
            AdapterKind::Espeak => "espeak",
            AdapterKind::Log => "log",
            AdapterKind::Ws => "ws",
            AdapterKind::Browser => "browser",
            AdapterKind::Display => "display",
            AdapterKind::DriveSim => "sim",
        }
    }
}

/// Whether a site-declared verb takes an argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArgRule {
    /// `argument: required`
    Required,
    /// `argument: optional` (the default)
    Optional,
    /// `argument: none`
    None,
}

/// A verb declared by the site under `verbs:`.
#[derive(Clone, Debug, PartialEq)]
pub struct SiteVerb {
    /// Where commands with this verb go: `ws` or `log`.
    pub adapter: AdapterKind,
    /// Whether it takes an argument.
    pub argument: ArgRule,
    /// What it does, for people (shown in the operator console later).
    pub description: Option<String>,
}

/// How the robot speaks.
#[derive(Clone, Debug, PartialEq)]
pub struct SpeechConfig {
    /// `None` means "espeak when installed, otherwise log" (decided at serve time).
    pub adapter: Option<AdapterKind>,
    /// espeak-ng voice name (`en`, `en-us`, `de`, ...).
    pub voice: String,
    /// Words per minute.
    pub rate_wpm: u32,
}

/// The rectangle of the map the drive may move in, in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// Smallest x.
    pub min_x: f64,
    /// Smallest y.
    pub min_y: f64,
    /// Largest x.
    pub max_x: f64,
    /// Largest y.
    pub max_y: f64,
}

impl Bounds {
    /// True when the point lies inside (borders included).
    pub fn contains(&self, x: f64, y: f64) -> bool {
        (self.min_x..=self.max_x).contains(&x) && (self.min_y..=self.max_y).contains(&y)
    }
}

/// How the robot drives.
#[derive(Clone, Debug, PartialEq)]
pub struct DriveConfig {
    /// `sim` (default) or `ws`.
    pub adapter: AdapterKind,
    /// Simulated speed in metres per second.
    pub speed: f64,
    /// Simulated pose updates per second.
    pub pose_hz: f64,
    /// Where waypoints may lie; `None` accepts any.
    pub bounds: Option<Bounds>,
}

/// Where display verbs (`DISPLAY_PAGE`, `PROJECT`) go.
#[derive(Clone, Debug, PartialEq)]
pub struct DisplayConfig {
    /// `display` (default, the built-in kiosk and projector pages) or `ws`.
    pub adapter: AdapterKind,
}

/// The touchscreen shell's behaviour (`kiosk:` in `docent.yaml`).
#[derive(Clone, Debug, PartialEq)]
pub struct KioskConfig {
    /// Time without touch after which the shell returns home; zero disables it.
    pub idle: Duration,
    /// Act triggered when the idle time runs out, if any (checked to exist at load time).
    pub idle_act: Option<String>,
}

/// What the projector shows once a video has ended (`projector: after_video:`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AfterVideo {
    /// Back to black (the default).
    Black,
    /// Keep the last frame on screen.
    Hold,
}

impl AfterVideo {
    /// The word used in `docent.yaml` and handed to the projector page.
    pub fn as_str(self) -> &'static str {
        match self {
            AfterVideo::Black => "black",
            AfterVideo::Hold => "hold",
        }
    }
}

/// The projector shell's behaviour (`projector:` in `docent.yaml`).
#[derive(Clone, Debug, PartialEq)]
pub struct ProjectorConfig {
    /// What stays on screen after a video.
    pub after_video: AfterVideo,
    /// The soft edge of `HIGHLIGHT` areas, as a fraction of the projected width (0 to 0.5).
    pub highlight_edge: f64,
}

/// Everything `docent.yaml` can set, with defaults filled in.
#[derive(Clone, Debug, PartialEq)]
pub struct SiteConfig {
    /// Page under `pages/` the kiosk starts on.
    pub home: String,
    /// Declared context variants (`TextGroup`, ...). Empty: any `Text...` key is accepted.
    pub contexts: Vec<String>,
    /// Speech settings.
    pub speech: SpeechConfig,
    /// Drive settings.
    pub drive: DriveConfig,
    /// Display settings.
    pub display: DisplayConfig,
    /// Touchscreen shell settings.
    pub kiosk: KioskConfig,
    /// Projector shell settings.
    pub projector: ProjectorConfig,
    /// How long a ws adapter may take to answer a command once it is its turn.
    pub adapter_timeout: Duration,
    /// Site-declared verbs, by name (upper case).
    pub verbs: BTreeMap<String, SiteVerb>,
}

impl Default for SiteConfig {
    fn default() -> Self {
        SiteConfig {
            home: "index.html".to_owned(),
            contexts: Vec::new(),
            speech: SpeechConfig {
                adapter: None,
                voice: "en".to_owned(),
                rate_wpm: 160,
            },
            drive: DriveConfig {
                adapter: AdapterKind::DriveSim,
                speed: 0.5,
                pose_hz: 5.0,
                bounds: None,
            },
            display: DisplayConfig {
                adapter: AdapterKind::Display,
            },
            kiosk: KioskConfig {
                idle: Duration::from_secs(120),
                idle_act: None,
            },
            projector: ProjectorConfig {
                after_video: AfterVideo::Black,
                highlight_edge: 0.02,
            },
            adapter_timeout: Duration::from_secs(30),
            verbs: BTreeMap::new(),
        }
    }
}
