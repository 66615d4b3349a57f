//! The event types: [`EventKind`], one variant per thing that happens. Field names here and
//! in the families' files are the corpus format; change them only with a version bump. The
//! fields of the larger families are structs in their own files (`command.rs`,
//! `proposal.rs`, `session.rs`, `touch.rs`, `attract.rs`, `robot.rs`, `bundle.rs`,
//! `client.rs`, `corpus.rs`, `recording.rs`), serialized as the variant's own fields would be.
//! Who asked (`origin.rs`) and the hub's stamps (`stamped.rs`) live beside it, so that these
//! files are the format alone.
//!
//! The same enum reads the lines back (`line.rs`): every field a format version before the
//! newest lacks has its default beside it, said there. Two fields are not read back, because
//! no reader needs them and their types are the content model's, which only writes them: a
//! `command.sent`'s parsed `args` (read as none) and a `bundle.refused`'s `diagnostics` (read
//! as empty). Every other field reads back as written (`line_tests.rs` writes and reads every
//! variant).

use std::borrow::Cow;
use std::sync::Arc;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::origin::{ActRef, Source};
use super::recording::RecordingEvent;
use crate::{ErrorCode, Open};
use docent_content::Language;

/// One thing that happened. Serialized with `type` as the tag.
///
/// (Serde derives its tagged variants as the inherent `EventKind::serialize` and
/// `EventKind::deserialize`, `remote = "Self"`; the trait impls below add `Recording`, whose
/// four types carry their own tag. A derived untagged variant would read every damaged line
/// of another type as "matches no variant", losing which field is wrong. So read through
/// the trait, `<EventKind as Deserialize>::deserialize`, or `serde_json::from_str`: the
/// inherent one does not know recordings.)
#[derive(Debug, Serialize, Deserialize)]
#[serde(tag = "type", remote = "Self")]
pub enum EventKind {
    /// Docent started serving a bundle.
    #[serde(rename = "server.started")]
    ServerStarted {
        /// Bundle folder.
        bundle: String,
        /// The bundle's content, `sha256:…` (`content::bundle_fingerprint`); `None` when a
        /// file could not be read for it (the reason is in Docent's output).
        bundle_hash: Option<String>,
        /// Docent's version.
        version: Cow<'static, str>,
        /// The random seed, when reproducible runs were asked for.
        #[serde(skip_serializing_if = "Option::is_none")]
        seed: Option<u64>,
    },
    /// Docent is shutting down.
    #[serde(rename = "server.stopping")]
    ServerStopping,
    /// An act was triggered and resolved into commands.
    #[serde(rename = "act.triggered")]
    ActTriggered {
        /// The trigger and act.
        #[serde(flatten)]
        act: Arc<ActRef>,
        /// The context asked for (explicitly or the current one).
        context: String,
        /// The variant whose text was used (`Text` on fallback); absent when the act has no text.
        variant: Option<String>,
        /// Index of the chosen alternative within the variant.
        alternative: Option<usize>,
        /// The exact text chosen.
        text: Option<String>,
        /// The language the text is in: the visitor's language, or the bundle's default
        /// when the act has no translation into it (format 3); absent when the act has no
        /// text.
        #[serde(skip_serializing_if = "Option::is_none")]
        language: Option<Language>,
        /// Whether the trigger interrupted current speech.
        interrupt: bool,
        /// The fingerprint of the bundle the act was resolved in (the `bundle_hash` of
        /// `server.started` or of the `bundle.reloaded` that put it live): a trigger racing a
        /// live reload names its bundle itself, which the order of the lines cannot (a
        /// kiosk's tap checked against the old bundle is resolved in it after the reload).
        /// Absent when the fingerprint could not be made, and in older logs.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        bundle_hash: Option<Arc<str>>,
    },
    /// A trigger was refused (unknown act or context, not allowed).
    #[serde(rename = "trigger.refused")]
    TriggerRefused {
        /// Who triggered.
        source: Source,
        /// The client, if any.
        #[serde(skip_serializing_if = "Option::is_none")]
        client: Option<u64>,
        /// The label asked for.
        label: String,
        /// The error code (as written when a newer Docent's).
        code: Open<ErrorCode>,
        /// Why.
        message: String,
    },
    /// A command was handed to its adapter.
    #[serde(rename = "command.sent")]
    CommandSent(super::CommandSent),
    /// An adapter started executing a command.
    #[serde(rename = "command.started")]
    CommandStarted(super::CommandStarted),
    /// A command finished.
    #[serde(rename = "command.done")]
    CommandDone(super::CommandDone),
    /// A command failed.
    #[serde(rename = "command.failed")]
    CommandFailed(super::CommandFailed),
    /// A command was dropped or cut short by a stop, `DRIVE_STOP` or an interrupting trigger.
    #[serde(rename = "command.cancelled")]
    CommandCancelled(super::CommandCancelled),
    /// What the touchscreen or projector shows changed.
    #[serde(rename = "display.changed")]
    DisplayChanged {
        /// Page under `pages/` on the touchscreen.
        page: Option<String>,
        /// File under `media/` on the projector.
        projector: Option<String>,
        /// The `HIGHLIGHT` areas lit on the projector, as written; `None` when cleared.
        highlight: Option<String>,
        /// What the projector reported about `projector` or `highlight` (added within format
        /// 2: older lines read as `black`).
        #[serde(default)]
        projector_state: crate::ProjectorState,
    },
    /// A browser asked for a page that is not in the bundle (a broken link or `DISPLAY_PAGE`);
    /// it was shown the friendly "not available" page.
    #[serde(rename = "page.missing")]
    PageMissing {
        /// The page asked for, relative to `pages/`, as requested.
        page: String,
        /// Where the request came from (its `Referer`): the page under `pages/` that linked
        /// to it, or the path of another page of this server (`/`: the kiosk shell); `None`
        /// when the browser did not say.
        from: Option<String>,
    },
    /// The drive base's pose. A line without its numbers (or with another value there)
    /// reads them as NaN, which no line holds (JSON has none): the export that draws poses,
    /// MCAP, calls that line damaged, and the others pass it over as before.
    #[serde(rename = "pose")]
    Pose {
        /// Metres.
        #[serde(deserialize_with = "number", default = "not_a_number")]
        x: f64,
        /// Metres.
        #[serde(deserialize_with = "number", default = "not_a_number")]
        y: f64,
        /// Degrees, counter-clockwise from the x axis.
        #[serde(deserialize_with = "number", default = "not_a_number")]
        heading: f64,
        /// Whether it is driving.
        moving: bool,
        /// The frame `x`, `y` and `heading` are in, when a line names one (the MCAP export
        /// reads it, `map` when absent); Docent's own drives write none.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        frame: Option<String>,
    },
    /// The drive reached its waypoint.
    #[serde(rename = "drive.arrived")]
    DriveArrived {
        /// Metres.
        x: f64,
        /// Metres.
        y: f64,
    },
    /// The current context changed.
    #[serde(rename = "context.changed")]
    ContextChanged {
        /// Who changed it.
        source: Source,
        /// The new context.
        context: String,
    },
    /// The visitor's language changed (a kiosk's language button, an operator, a dialog
    /// manager, or the server: back to the default when a visitor session ends).
    #[serde(rename = "language.changed")]
    LanguageChanged {
        /// Who changed it.
        source: Source,
        /// The new language.
        language: Language,
    },
    /// Everything was stopped (global stop or `DRIVE_STOP`).
    #[serde(rename = "stop")]
    Stop {
        /// Who stopped.
        source: Source,
        /// Why, e.g. `stop request` or `DRIVE_STOP in act GOODBYE`.
        reason: String,
    },
    /// A dialog manager proposed an act for the operator to accept or dismiss.
    #[serde(rename = "proposal.made")]
    ProposalMade(super::ProposalMade),
    /// An operator accepted a proposal; the act was triggered as `trigger`.
    #[serde(rename = "proposal.accepted")]
    ProposalAccepted(super::ProposalAccepted),
    /// An operator dismissed a proposal; nothing was triggered.
    #[serde(rename = "proposal.dismissed")]
    ProposalDismissed(super::ProposalDismissed),
    /// A proposal was taken back before anyone answered it (its dialog manager left).
    #[serde(rename = "proposal.withdrawn")]
    ProposalWithdrawn(super::ProposalWithdrawn),
    /// A visitor session began (marked by an operator).
    #[serde(rename = "session.started")]
    SessionStarted(super::SessionStarted),
    /// A visitor touched the kiosk: a `data-act` element (its trigger follows) or a link (the
    /// page change follows).
    #[serde(rename = "touch")]
    Touch(super::Touch),
    /// A kiosk's attract loop began: its pages and act are the screen's own doing.
    #[serde(rename = "attract.started")]
    AttractStarted(super::AttractStarted),
    /// A kiosk's attract loop ended (a touch's own `touch` event follows it).
    #[serde(rename = "attract.ended")]
    AttractEnded(super::AttractEnded),
    /// The robot's software noticed something (an adapter process sent it).
    #[serde(rename = "robot")]
    Robot(super::RobotEvent),
    /// A message on a ROS topic could not be used (told once per topic and problem).
    #[serde(rename = "topic.refused")]
    TopicRefused(super::TopicRefused),
    /// A reaction's condition could not be decided on a robot event's data.
    #[serde(rename = "reaction.failed")]
    ReactionFailed(super::ReactionFailed),
    /// An operator noted what the session's visitors agreed to.
    #[serde(rename = "consent.changed")]
    ConsentChanged(super::ConsentChanged),
    /// A visitor session ended.
    #[serde(rename = "session.ended")]
    SessionEnded(super::SessionEnded),
    /// The operator noted who the visitors are.
    #[serde(rename = "visitor.group")]
    VisitorGroup(super::VisitorGroup),
    /// The operator marked a dialog situation (`question`, `laughter`, ... as the site lists).
    #[serde(rename = "situation.marked")]
    SituationMarked(super::SituationMarked),
    /// An operator wrote a note about the moment, in their own words.
    #[serde(rename = "note.written")]
    NoteWritten(super::NoteWritten),
    /// A saved bundle without errors went live in place of the running one.
    #[serde(rename = "bundle.reloaded")]
    BundleReloaded(super::BundleReloaded),
    /// A saved bundle had errors: it was refused and the last good one keeps running.
    #[serde(rename = "bundle.refused")]
    BundleRefused(super::BundleRefused),
    /// The bundle folder cannot be watched or read any more (deleted, renamed, a watcher
    /// error); the last good bundle keeps running.
    #[serde(rename = "bundle.watch-failed")]
    BundleWatchFailed(super::BundleWatchFailed),
    /// A media file Chromium cannot show as it is was converted for it (into the media
    /// cache; the file itself is unchanged). Not logged when the result was already cached.
    #[serde(rename = "media.converted")]
    MediaConverted(super::MediaConverted),
    /// A media file could not be converted: showing it fails with this reason until the file
    /// is replaced (or the missing converter installed and Docent restarted).
    #[serde(rename = "media.failed")]
    MediaFailed(super::MediaFailed),
    /// A websocket client's credential was refused (the connection was closed), or a command
    /// over MQTT was badly signed.
    #[serde(rename = "client.refused")]
    ClientRefused(super::ClientRefused),
    /// An HTTP request's credential was refused (`401`, or the `429` that made its address
    /// wait).
    #[serde(rename = "request.refused")]
    RequestRefused(super::RequestRefused),
    /// A websocket client said hello.
    #[serde(rename = "client.connected")]
    ClientConnected(super::ClientConnected),
    /// A websocket client left or was dropped.
    #[serde(rename = "client.left")]
    ClientLeft(super::ClientLeft),
    /// The robot's link to the fleet's MQTT broker came up or went down (`docs/FLEET.md`).
    #[serde(rename = "fleet.link")]
    FleetLink(crate::fleet_link::LinkView),
    /// The link to the robot's rosbridge server went up or down.
    #[serde(rename = "robot.link")]
    RobotLink(super::RobotLinkEvent),
    /// The corpus log cannot be written (a full disk, a read-only one): events wait in
    /// memory and new triggers are refused until it can (`docs/CORPUS.md`).
    #[serde(rename = "corpus.unwritable")]
    CorpusUnwritable(super::CorpusUnwritable),
    /// The corpus log can be written again; the events kept meanwhile are in it, before this.
    #[serde(rename = "corpus.writable")]
    CorpusWritable(super::CorpusWritable),
    /// Events lost while the log could not be written: their `seq`s are missing.
    #[serde(rename = "corpus.gap")]
    CorpusGap(super::CorpusGap),
    /// A corpus log file was removed under the running server and made again.
    #[serde(rename = "corpus.recreated")]
    CorpusRecreated(super::CorpusRecreated),
    /// A recording started, stopped, failed or was deleted (`recording.*`, its own tag;
    /// written and read by the trait impls below).
    #[serde(skip)]
    Recording(RecordingEvent),
}

impl Serialize for EventKind {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            EventKind::Recording(recording) => recording.serialize(serializer),
            kind => EventKind::serialize(kind, serializer),
        }
    }
}

impl<'de> Deserialize<'de> for EventKind {
    /// An event of a type this Docent knows; a line of another type is an error (a corpus
    /// line's reader, `line.rs`, passes those over first).
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        // The line is read once into a value, to learn its type before choosing the enum.
        let line = serde_json::Value::deserialize(deserializer)?;
        let name = line.get("type").and_then(serde_json::Value::as_str);
        let kind = match name {
            Some(name) if super::line::has_type::<RecordingEvent>(name) => {
                RecordingEvent::deserialize(line).map(EventKind::Recording)
            }
            _ => EventKind::deserialize(line),
        };
        kind.map_err(D::Error::custom)
    }
}

/// A pose's number, or NaN for any other value.
fn number<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f64, D::Error> {
    let value = serde_json::Value::deserialize(deserializer)?;
    Ok(value.as_f64().unwrap_or(f64::NAN))
}

/// What a pose without a number reads as.
fn not_a_number() -> f64 {
    f64::NAN
}

impl EventKind {
    /// Whether an operator or dialog manager joining later should see this event again (the
    /// console's history, pending proposals and marks).
    pub fn is_history(&self) -> bool {
        matches!(
            self,
            EventKind::ActTriggered { .. }
                | EventKind::ContextChanged { .. }
                | EventKind::LanguageChanged { .. }
                | EventKind::ProposalMade { .. }
                | EventKind::ProposalAccepted { .. }
                | EventKind::ProposalDismissed { .. }
                | EventKind::ProposalWithdrawn { .. }
                | EventKind::SessionStarted { .. }
                | EventKind::SessionEnded { .. }
                | EventKind::ConsentChanged { .. }
                | EventKind::VisitorGroup { .. }
                | EventKind::SituationMarked { .. }
                | EventKind::NoteWritten { .. }
                | EventKind::Recording(_)
                | EventKind::RobotLink(_)
        )
    }
}
