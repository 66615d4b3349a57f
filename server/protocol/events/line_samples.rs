//! One event of every variant, for the tests of reading lines back (`line_tests.rs`): apart
//! from them because it is as long as the enum.

use std::sync::Arc;

use super::*;
use crate::events::{
    ActRef, AttractEnd, ClientRole, Consent, CorpusFault, CorpusGap as Gap,
    CorpusRecreated as Recreated, CorpusUnwritable as Unwritable, CorpusWritable as Writable,
    FailureCode, LinkState, RecordingEvent, RobotEvent, RobotLinkEvent, SessionEnd, Source,
    StopReason, Track,
};
use crate::fleet_link::{LinkState as BrokerState, LinkView};
use crate::{ErrorCode, ProjectorState};
use docent_content::{Args, Language};

fn act() -> Arc<ActRef> {
    Arc::new(ActRef {
        trigger: 4,
        source: Source::Http,
        client: Some(2),
        reference: Some("visitor-42".into()),
        label: "GREETING".into(),
        at: "smalltalk.yaml:7".into(),
    })
}

/// One event of every variant (with `args` none and no diagnostics, the two fields that are
/// not read back), and, for each, its place in [`variant`].
pub(super) fn every_kind() -> Vec<EventKind> {
    use EventKind::*;
    let text = |s: &str| Some(s.to_owned());
    vec![
        ServerStarted {
            bundle: "/srv/tour".into(),
            bundle_hash: text("sha256:00"),
            version: "0.1.0".into(),
            seed: Some(7),
        },
        ServerStopping,
        ActTriggered {
            act: act(),
            context: "TextChild".into(),
            variant: text("Text"),
            alternative: Some(1),
            text: text("Hello"),
            language: Language::parse("de"),
            interrupt: true,
            bundle_hash: Some("sha256:00".into()),
        },
        TriggerRefused {
            source: Source::Kiosk,
            client: Some(1),
            label: "SECRET".into(),
            code: ErrorCode::NotOffered.into(),
            message: "no page offers it".into(),
        },
        CommandSent(crate::events::CommandSent {
            command: 5,
            act: act(),
            verb: "SAY".into(),
            arg: text("Hello"),
            args: Arc::new(Args::None {}),
            adapter: "espeak".into(),
        }),
        CommandStarted(crate::events::CommandStarted {
            command: 5,
            act: act(),
            verb: "SAY".into(),
        }),
        CommandDone(crate::events::CommandDone {
            command: 5,
            act: act(),
            verb: "SAY".into(),
        }),
        CommandFailed(crate::events::CommandFailed {
            command: 5,
            act: act(),
            verb: "SAY".into(),
            reason: "no sound card".into(),
        }),
        CommandCancelled(crate::events::CommandCancelled {
            command: 5,
            act: act(),
            verb: "SAY".into(),
            reason: "stop request".into(),
        }),
        DisplayChanged {
            page: text("index.html"),
            projector: text("film.mp4"),
            highlight: None,
            projector_state: ProjectorState::Playing,
        },
        PageMissing {
            page: "gone.html".into(),
            from: text("index.html"),
        },
        Pose {
            x: 1.5,
            y: -2.0,
            heading: 90.0,
            moving: true,
            frame: None,
        },
        DriveArrived { x: 1.5, y: -2.0 },
        ContextChanged {
            source: Source::Operator,
            context: "TextChild".into(),
        },
        LanguageChanged {
            source: Source::Kiosk,
            language: Language::parse("pt-br").unwrap(),
        },
        Stop {
            source: Source::Server,
            reason: "the server is shutting down".into(),
        },
        ProposalMade(crate::events::ProposalMade {
            proposal: 1,
            client: 3,
            label: "TOUR".into(),
            context: None,
            reason: text("they asked"),
        }),
        ProposalAccepted(crate::events::ProposalAccepted {
            proposal: 1,
            client: 2,
            label: "TOUR".into(),
            trigger: 9,
        }),
        ProposalDismissed(crate::events::ProposalDismissed {
            proposal: 1,
            client: 2,
            label: "TOUR".into(),
        }),
        ProposalWithdrawn(crate::events::ProposalWithdrawn {
            proposal: 1,
            client: 3,
            label: "TOUR".into(),
            reason: "the dialog manager left".into(),
        }),
        SessionStarted(crate::events::SessionStarted {
            session: 1,
            source: Source::Kiosk,
            client: Some(1),
            consent: Consent::Declined,
            page: text("index.html"),
            projector: None,
        }),
        Touch(crate::events::Touch {
            client: 1,
            page: text("index.html"),
            element: text("button#start"),
            act: text("TOUR"),
            link: None,
        }),
        AttractStarted(crate::events::AttractStarted { client: 1 }),
        AttractEnded(crate::events::AttractEnded {
            client: 1,
            by: AttractEnd::Schedule,
        }),
        Robot(RobotEvent {
            client: None,
            topic: text("/people"),
            event: "person.near".into(),
            data: serde_json::json!({"distance": 1.2}),
        }),
        TopicRefused(crate::events::TopicRefused {
            topic: "/pose".into(),
            event: None,
            reason: "no position".into(),
        }),
        ReactionFailed(crate::events::ReactionFailed {
            reaction: 2,
            event: "person.near".into(),
            act: "HELLO".into(),
            reason: "no distance".into(),
        }),
        ConsentChanged(crate::events::ConsentChanged {
            session: 1,
            consent: Consent::Withdrawn,
            source: Source::Operator,
            client: 2,
        }),
        SessionEnded(crate::events::SessionEnded {
            session: 1,
            source: Source::Server,
            client: None,
            reason: SessionEnd::Idle,
        }),
        VisitorGroup(crate::events::VisitorGroup {
            session: Some(1),
            group: "children".into(),
            context: text("TextChild"),
            source: Source::Operator,
            client: 2,
        }),
        SituationMarked(crate::events::SituationMarked {
            session: None,
            situation: "laughter".into(),
            source: Source::Dm,
            client: 3,
        }),
        NoteWritten(crate::events::NoteWritten {
            session: Some(1),
            text: "they laughed".into(),
            source: Source::Operator,
            client: 2,
        }),
        BundleReloaded(crate::events::BundleReloaded {
            bundle_hash: None,
            acts: 3,
            contexts: 2,
            page_acts: 1,
            warnings: 0,
            changed: vec!["acts.yaml".into()],
            elapsed_ms: 12,
            not_applied: vec!["server.port".into()],
        }),
        BundleRefused(crate::events::BundleRefused {
            diagnostics: Vec::new(),
            changed: vec!["acts.yaml".into()],
            elapsed_ms: 4,
        }),
        BundleWatchFailed(crate::events::BundleWatchFailed {
            code: "folder-missing".into(),
            message: "the folder is gone".into(),
        }),
        ClientRefused(crate::events::ClientRefused {
            role: ClientRole::Operator,
            code: ErrorCode::Unauthorized.into(),
            address: text("10.0.0.9"),
            unlogged: 3,
        }),
        RequestRefused(crate::events::RequestRefused {
            method: "POST".into(),
            path: "/api/stop".into(),
            code: ErrorCode::TooManyAttempts.into(),
            address: None,
            unlogged: 0,
        }),
        ClientConnected(crate::events::ClientConnected {
            client: 4,
            role: ClientRole::Adapter,
            name: text("lights"),
            verbs: vec!["LIGHTS".into()],
        }),
        ClientLeft(crate::events::ClientLeft {
            client: 4,
            role: ClientRole::Adapter,
            name: text("lights"),
            reason: "too slow: fell behind the event stream".into(),
            ended: Some(crate::events::Ended::Server),
            code: Some(1013),
        }),
        FleetLink(LinkView {
            broker: "mqtt://fleet.local".into(),
            state: BrokerState::Down,
            reason: text("refused"),
        }),
        RobotLink(RobotLinkEvent {
            state: LinkState::Up,
            url: "ws://robot.local:9090".into(),
            reason: None,
        }),
        Recording(RecordingEvent::Started {
            session: 1,
            recording: 2,
            client: 1,
            track: Track::Audio,
            file: "media/audio-2.webm".into(),
            mime: "audio/webm;codecs=opus".into(),
            start_us: 1500,
            clock_error_us: 900,
        }),
        Recording(RecordingEvent::Stopped {
            session: 1,
            recording: 2,
            file: "media/audio-2.webm".into(),
            bytes: 4096,
            chunks: 4,
            reason: StopReason::NoFinalReport,
        }),
        Recording(RecordingEvent::Failed {
            session: None,
            recording: None,
            client: 1,
            code: FailureCode::PermissionDenied,
            message: "denied".into(),
        }),
        Recording(RecordingEvent::Deleted {
            session: 1,
            files: vec!["media/audio-2.webm".into()],
            bytes: 4096,
            consent: Consent::Withdrawn,
        }),
        MediaConverted(crate::events::MediaConverted {
            file: "media/Exhibit/video.mpg".into(),
            format: "MPEG-1/2".into(),
            elapsed_ms: 812,
            bytes: 401_233,
        }),
        MediaFailed(crate::events::MediaFailed {
            file: "media/scan.tif".into(),
            reason: "ffmpeg cannot read it (Invalid data found when processing input)".into(),
        }),
        CorpusUnwritable(Unwritable {
            fault: CorpusFault::DiskFull,
            path: "/srv/corpus".into(),
            error: "No space left on device (os error 28)".into(),
            message: "The corpus disk is full (/srv/corpus): free space on it".into(),
        }),
        CorpusWritable(Writable {
            path: "/srv/corpus".into(),
            unwritable_ms: 4200,
            message: "The corpus log is written again".into(),
        }),
        CorpusGap(Gap {
            from: 20,
            to: 29,
            count: 10,
            fault: Some(CorpusFault::ReadOnly),
            reason: "64 MiB waited".into(),
        }),
        CorpusRecreated(Recreated::of("/srv/corpus/days/x.jsonl")),
    ]
}

/// The variant's place, by an exhaustive match: a new variant does not compile here until it
/// is added, and `every_variant_...` then fails until [`every_kind`] has one.
pub(super) fn variant(kind: &EventKind) -> usize {
    use EventKind::*;
    match kind {
        ServerStarted { .. } => 0,
        ServerStopping => 1,
        ActTriggered { .. } => 2,
        TriggerRefused { .. } => 3,
        CommandSent { .. } => 4,
        CommandStarted { .. } => 5,
        CommandDone { .. } => 6,
        CommandFailed { .. } => 7,
        CommandCancelled { .. } => 8,
        DisplayChanged { .. } => 9,
        PageMissing { .. } => 10,
        Pose { .. } => 11,
        DriveArrived { .. } => 12,
        ContextChanged { .. } => 13,
        LanguageChanged { .. } => 14,
        Stop { .. } => 15,
        ProposalMade { .. } => 16,
        ProposalAccepted { .. } => 17,
        ProposalDismissed { .. } => 18,
        ProposalWithdrawn { .. } => 19,
        SessionStarted { .. } => 20,
        Touch { .. } => 21,
        AttractStarted { .. } => 22,
        AttractEnded { .. } => 23,
        Robot(_) => 24,
        TopicRefused { .. } => 25,
        ReactionFailed { .. } => 26,
        ConsentChanged { .. } => 27,
        SessionEnded { .. } => 28,
        VisitorGroup { .. } => 29,
        SituationMarked { .. } => 30,
        NoteWritten { .. } => 31,
        BundleReloaded { .. } => 32,
        BundleRefused { .. } => 33,
        BundleWatchFailed { .. } => 34,
        ClientRefused { .. } => 35,
        RequestRefused { .. } => 36,
        ClientConnected { .. } => 37,
        ClientLeft { .. } => 38,
        FleetLink(_) => 39,
        RobotLink(_) => 40,
        Recording(RecordingEvent::Started { .. }) => 41,
        Recording(RecordingEvent::Stopped { .. }) => 42,
        Recording(RecordingEvent::Failed { .. }) => 43,
        Recording(RecordingEvent::Deleted { .. }) => 44,
        MediaConverted { .. } => 45,
        MediaFailed { .. } => 46,
        CorpusUnwritable(_) => 47,
        CorpusWritable(_) => 48,
        CorpusGap(_) => 49,
        CorpusRecreated(_) => 50,
    }
}
