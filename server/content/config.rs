//! Site settings from a bundle's optional `docent.yaml`, in validated form. The raw YAML shape
//! and its parsing live in `config_file.rs`; this file holds what the rest of Docent reads.
//! Documented for people in `docs/CONFIG.md`.

use std::collections::BTreeMap;
use std::fmt;
use std::time::Duration;

use crate::model::Located;

pub use crate::config_corpus::{CorpusSettings, RecordLimits, RecordTracks, SessionStart};
pub use crate::config_file::captions::CaptionSettings;
pub use crate::config_file::codebook::{Code, Codebook, CodebookTier};
pub use crate::config_file::mqtt::{MqttPassword, MqttSettings};
pub use crate::config_file::rosbridge::{PoseMessage, RosbridgeConfig, TopicEvent};
pub use crate::config_policy::{
    Channel, ChannelPolicies, ChannelPolicy, MAX_PRIORITY, MAX_QUEUE_LIMIT, Priorities, WhenBusy,
};
pub use crate::config_server::ServerLimits;
pub use crate::language::{Language, Languages};
pub use crate::reaction::Reaction;
pub use crate::schedule::Schedule;

use crate::attract::AttractLoop;

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
    /// `rosbridge`: a ROS 2 robot through a rosbridge v2 server (`rosbridge:` settings).
    Rosbridge,
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
            AdapterKind::Rosbridge => "rosbridge",
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
    /// The espeak-ng voice of each of the bundle's languages (`speech: voices:`), filled in
    /// for every language when `docent.yaml` is read: the one written, else `voice` for the
    /// default language when it was written, else the language tag itself.
    pub voices: BTreeMap<Language, String>,
    /// Words per minute.
    pub rate_wpm: u32,
    /// The longest a text may take to say (estimated from `rate_wpm`) before `docent check`
    /// warns; far above it is an error.
    pub max_seconds: u32,
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

impl SpeechConfig {
    /// The espeak-ng voice that speaks `language` (`voice` for one the map lacks).
    pub fn voice_for(&self, language: &Language) -> &str {
        self.voices
            .get(language)
            .map_or(&self.voice, String::as_str)
    }
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
    /// `sim` (default), `ws` or `rosbridge`.
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
    /// Whether leaving a page cancels the speech that page started (`leave_page_stops_speech`).
    pub leave_page_stops_speech: bool,
    /// The attract loop an unused touchscreen runs (`kiosk: attract:`), if any.
    pub attract: Option<AttractLoop>,
    /// The site's own words for the shell (`kiosk: strings:`), over the built-in ones.
    pub strings: crate::shell_strings::SiteStrings,
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

/// A secret that grants a role (the operator's or the dialog manager's token). Its `Debug`
/// prints `Credential(***)`, so settings can be logged without leaking it; read it with
/// [`Credential::expose`] only where it is compared or shown to the person starting Docent.
#[derive(Clone, Eq)]
pub struct Credential(String);

/// Why a text cannot be a credential.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum WeakCredential {
    /// Fewer than [`Credential::MIN_CHARS`] characters.
    #[error("it has {0} characters, and at least 16 are needed so it cannot be guessed")]
    TooShort(usize),
    /// A space, a control character or a character outside plain ASCII.
    #[error(
        "it may hold only letters, digits and punctuation: no spaces and no accented letters, \
         because it travels in an HTTP header"
    )]
    NotPlain,
}

impl Credential {
    /// The fewest characters a credential may have.
    pub const MIN_CHARS: usize = 16;

    /// The credential `text`: at least 16 visible ASCII characters (no whitespace).
    pub fn new(text: impl Into<String>) -> Result<Self, WeakCredential> {
        let text = text.into();
        if !text.chars().all(|c| c.is_ascii_graphic()) {
            return Err(WeakCredential::NotPlain);
        }
        if text.len() < Self::MIN_CHARS {
            return Err(WeakCredential::TooShort(text.len()));
        }
        Ok(Credential(text))
    }

    /// The secret itself.
    pub fn expose(&self) -> &str {
        &self.0
    }
}

impl PartialEq for Credential {
    /// Compares every byte whatever the first difference, so timing tells little.
    fn eq(&self, other: &Self) -> bool {
        let (a, b) = (self.0.as_bytes(), other.0.as_bytes());
        a.len() == b.len() && a.iter().zip(b).fold(0u8, |diff, (x, y)| diff | (x ^ y)) == 0
    }
}

impl fmt::Debug for Credential {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("Credential(***)")
    }
}

/// Credentials set in `docent.yaml` (`access:`). The environment variables
/// `DOCENT_OPERATOR_TOKEN` and `DOCENT_DM_TOKEN` take precedence (decided at serve time).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AccessSettings {
    /// The operator console's token (`access: operator_token:`).
    pub operator_token: Option<Credential>,
    /// The dialog manager's token (`access: dm_token:`).
    pub dm_token: Option<Credential>,
}

/// How Docent's own server is reached (`server:` in `docent.yaml`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ServerSettings {
    /// Reverse proxies whose `X-Forwarded-For` header is believed (`server: trusted_proxies:`).
    /// From any other peer the header is ignored, so a client cannot pick the address its
    /// failed credentials are counted under. Empty by default: no proxy is believed.
    pub trusted_proxies: Vec<std::net::IpAddr>,
    /// Connections, time limits, message size and outgoing queues (`server: connections`,
    /// `timeouts`, `messages`, `queues`), in force from start-up.
    pub limits: ServerLimits,
}

/// Where the operator console gets its camera picture (`operator: camera:`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Camera {
    /// `webrtc` (the default): the kiosk's own camera, over WebRTC signalled through Docent.
    #[default]
    WebRtc,
    /// `none`: no camera view.
    None,
    /// An `http://` or `https://` URL of an MJPEG stream the console shows as is.
    Url(String),
}

/// The operator console's settings (`operator:` in `docent.yaml`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OperatorConfig {
    /// The map picture, bundle-relative (`pages/images/map.png`), spanning `drive.bounds`.
    /// Checked to exist under `pages/` or `media/`; `None` when not set.
    pub map: Option<String>,
    /// The camera view.
    pub camera: Camera,
    /// Situations the operator can mark (Alt+Shift+1..9), at most 9, in written order.
    pub situations: Vec<String>,
    /// Visitor group (`single`, `group`, `children`) to the context it switches to. Groups
    /// not written get `Text`, `TextGroup`, `TextChild` when the bundle has that context.
    pub visitor_groups: BTreeMap<String, String>,
}

/// Everything `docent.yaml` can set, with defaults filled in.
#[derive(Clone, Debug, PartialEq)]
pub struct SiteConfig {
    /// Page under `pages/` the kiosk starts on.
    pub home: String,
    /// Declared context variants (`TextGroup`, ...). Empty: any `Text...` key is accepted.
    pub contexts: Vec<String>,
    /// The bundle's languages (`languages:`), the default first; one when not written.
    pub languages: Languages,
    /// Where each language of `languages:` was written (empty when it was not), for
    /// problems found later (a language no voice speaks).
    pub language_places: Vec<Located<Language>>,
    /// Where each language's voice was written in `speech: voices:` (the entry's key), for
    /// a voice `docent check` finds no installed espeak-ng voice for.
    pub voice_places: Vec<Located<Language>>,
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
    /// Visitor sessions in the corpus.
    pub corpus: CorpusSettings,
    /// `corpus: session_start_events`: the robot events that start a visitor session when
    /// none runs (beside `corpus` because that one is `Copy`).
    pub session_start_events: Vec<String>,
    /// How long a ws adapter may take to answer a command once it is its turn.
    pub adapter_timeout: Duration,
    /// Site-declared verbs, by name (upper case).
    pub verbs: BTreeMap<String, SiteVerb>,
    /// Credentials from `access:` (none by default).
    pub access: AccessSettings,
    /// Operator console settings.
    pub operator: OperatorConfig,
    /// How the server itself is reached (trusted proxies).
    pub server: ServerSettings,
    /// What each output channel does with a command that arrives while another runs.
    pub channels: ChannelPolicies,
    /// Each trigger source's priority.
    pub priorities: Priorities,
    /// The annotation tiers and codes of the `/sessions` page (`codebook:`).
    pub codebook: Codebook,
    /// The link to a ROS 2 robot (`rosbridge:`).
    pub rosbridge: RosbridgeConfig,
    /// Robot events mapped to acts (`reactions:`), in written order.
    pub reactions: Vec<Reaction>,
    /// The fleet's MQTT broker and this robot's id in it (`mqtt:`, docs/FLEET.md).
    pub mqtt: MqttSettings,
    /// Opening hours, with a home page and attract loop per range (`schedule:`); `None`:
    /// always open.
    pub schedule: Option<Schedule>,
    /// Which screens show captions of the robot's speech (`captions:`).
    pub captions: CaptionSettings,
}

impl Default for SiteConfig {
    fn default() -> Self {
        SiteConfig {
            home: "index.html".to_owned(),
            contexts: Vec::new(),
            languages: Languages::default(),
            language_places: Vec::new(),
            voice_places: Vec::new(),
            speech: SpeechConfig {
                adapter: None,
                voice: "en".to_owned(),
                voices: BTreeMap::from([(Language::english(), "en".to_owned())]),
                rate_wpm: 160,
                max_seconds: 30,
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
                leave_page_stops_speech: true,
                attract: None,
                strings: Default::default(),
            },
            projector: ProjectorConfig {
                after_video: AfterVideo::Black,
                highlight_edge: 0.02,
            },
            corpus: CorpusSettings::default(),
            session_start_events: Vec::new(),
            adapter_timeout: Duration::from_secs(30),
            verbs: BTreeMap::new(),
            access: AccessSettings::default(),
            operator: OperatorConfig::default(),
            server: ServerSettings::default(),
            channels: ChannelPolicies::default(),
            priorities: Priorities::default(),
            codebook: Codebook::default(),
            rosbridge: RosbridgeConfig::default(),
            reactions: Vec::new(),
            mqtt: MqttSettings::default(),
            schedule: None,
            captions: CaptionSettings::default(),
        }
    }
}

#[cfg(test)]
mod tests;
