//! Channel policies and source priorities through the whole dispatcher, with the `log` speech
//! adapter and a paused tokio clock: speech takes its estimated time in virtual seconds, so
//! what waits, what is cut short and when things start are exact and the tests never sleep.

use std::sync::Arc;
use std::time::Duration;

use tokio::sync::broadcast;
use tokio::time::Instant;

use crate::content::{Bundle, load_bundle, speaking_time};
use crate::dispatch::{Dispatcher, TriggerError, TriggerRequest};
use crate::events::{
    CommandCancelled, CommandDone, CommandFailed, CommandStarted, Event, EventKind, Hub, Source,
};

const LONG: &str = "one two three four five six seven eight nine ten eleven twelve thirteen \
                    fourteen fifteen sixteen seventeen eighteen nineteen twenty";

fn bundle(config: &str) -> (tempfile::TempDir, Bundle) {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut acts = String::new();
    for label in ["A", "B", "C", "D", "E"] {
        acts.push_str(&format!("- Label: {label}\n  Text: [\"{LONG}\"]\n"));
    }
    acts.push_str("- Label: LATER\n  Cmds: [WAIT 2s, SAY Later]\n");
    acts.push_str(
        "- Label: GO1\n  Cmds: [SET_WAYPOINT 10 0, DRIVE_START, WAIT, SAY At stop one]\n",
    );
    acts.push_str("- Label: GO2\n  Cmds: [SET_WAYPOINT 0 10, DRIVE_START]\n");
    std::fs::write(dir.path().join("acts.yaml"), acts).expect("acts");
    std::fs::create_dir_all(dir.path().join("pages")).expect("pages");
    std::fs::write(
        dir.path().join("pages/index.html"),
        "<!doctype html><title>x</title>",
    )
    .expect("home");
    std::fs::write(dir.path().join("docent.yaml"), config).expect("config");
    let report = load_bundle(dir.path());
    let bundle = report
        .bundle
        .unwrap_or_else(|| panic!("{:#?}", report.diagnostics));
    (dir, bundle)
}

struct Rig {
    dispatcher: Arc<Dispatcher>,
    events: broadcast::Receiver<Arc<Event>>,
    _dir: tempfile::TempDir,
}

fn rig(config: &str) -> Rig {
    let (dir, bundle) = bundle(config);
    let (hub, _corpus) = Hub::new();
    let events = hub.subscribe();
    let dispatcher = super::log_dispatcher(bundle, &hub);
    Rig {
        dispatcher,
        events,
        _dir: dir,
    }
}

impl Rig {
    fn trigger(&self, label: &str, source: Source, interrupt: bool) -> u64 {
        let mut request = TriggerRequest::new(label, source);
        request.interrupt = interrupt;
        let triggered = self.dispatcher.trigger(request).expect("triggered");
        triggered.commands[0].id
    }

    /// The id of the last command a kiosk client's trigger of `label` resolved to.
    fn trigger_from(&self, label: &str, client: u64) -> u64 {
        let mut request = TriggerRequest::new(label, Source::Kiosk);
        request.client = Some(client);
        let triggered = self.dispatcher.trigger(request).expect("triggered");
        triggered.commands.last().expect("a command").id
    }

    /// The next outcome or start of `command`, with the virtual time it came at.
    async fn next_of(&mut self, command: u64) -> (&'static str, String, Instant) {
        loop {
            let event = self.events.recv().await.expect("events");
            let (kind, id, reason) = match &event.kind {
                EventKind::CommandStarted(CommandStarted { command, .. }) => {
                    ("started", *command, String::new())
                }
                EventKind::CommandDone(CommandDone { command, .. }) => {
                    ("done", *command, String::new())
                }
                EventKind::CommandCancelled(CommandCancelled {
                    command, reason, ..
                }) => ("cancelled", *command, reason.clone()),
                EventKind::CommandFailed(CommandFailed {
                    command, reason, ..
                }) => ("failed", *command, reason.clone()),
                _ => continue,
            };
            if id == command {
                return (kind, reason, Instant::now());
            }
        }
    }
}

fn say_time() -> Duration {
    speaking_time(LONG, 160)
}

#[tokio::test(start_paused = true)]
async fn a_kiosk_interrupt_waits_behind_the_operator_and_speaks_right_after() {
    let mut rig = rig("speech: {adapter: log}\n");
    let start = Instant::now();
    let operator = rig.trigger("A", Source::Operator, false);
    let visitor = rig.trigger("B", Source::Kiosk, true);
    assert_eq!(rig.next_of(operator).await.0, "started");
    let (outcome, _, at) = rig.next_of(operator).await;
    assert_eq!((outcome, at - start), ("done", say_time()));
    let (started, _, at) = rig.next_of(visitor).await;
    assert_eq!((started, at - start), ("started", say_time()));
}

#[tokio::test(start_paused = true)]
async fn the_speech_queue_holds_two_and_refuses_the_rest_at_once() {
    let mut rig = rig("speech: {adapter: log}\n");
    let start = Instant::now();
    let ids: Vec<u64> = ["A", "B", "C", "D", "E"]
        .iter()
        .map(|label| rig.trigger(label, Source::Dm, false))
        .collect();
    for &refused in &ids[3..] {
        let (outcome, reason, at) = rig.next_of(refused).await;
        assert_eq!((outcome, at - start), ("cancelled", Duration::ZERO));
        assert!(
            reason.contains("speech queue was full (2 waiting)"),
            "{reason}"
        );
    }
    let (_, _, last) = loop {
        let next = rig.next_of(ids[2]).await;
        if next.0 == "done" {
            break next;
        }
    };
    assert_eq!(
        last - start,
        say_time() * 3,
        "three texts, one after another"
    );
}

#[tokio::test(start_paused = true)]
async fn replace_cuts_equal_priority_speech_short_and_never_higher() {
    let mut rig = rig("speech: {adapter: log}\nchannels: {speech: {when_busy: replace}}\n");
    let start = Instant::now();
    let first = rig.trigger("A", Source::Dm, false);
    assert_eq!(rig.next_of(first).await.0, "started");
    let second = rig.trigger("B", Source::Dm, false);
    let (outcome, reason, at) = rig.next_of(first).await;
    assert_eq!((outcome, at - start), ("cancelled", Duration::ZERO));
    assert_eq!(reason, "replaced by act B from the dialog manager");
    assert_eq!(rig.next_of(second).await.0, "started");
    let kiosk = rig.trigger("C", Source::Kiosk, false);
    let (outcome, reason, _) = rig.next_of(kiosk).await;
    assert_eq!(outcome, "cancelled");
    assert!(reason.contains("busy with SAY"), "{reason}");
    let (outcome, _, at) = rig.next_of(second).await;
    assert_eq!((outcome, at - start), ("done", say_time()));
}

#[tokio::test(start_paused = true)]
async fn a_kiosk_tap_on_an_act_already_speaking_is_refused() {
    let rig = rig("speech: {adapter: log}\n");
    rig.trigger("A", Source::Kiosk, false);
    let again = rig
        .dispatcher
        .trigger(TriggerRequest::new("A", Source::Kiosk));
    let expected = TriggerError::AlreadySpeaking { label: "A".into() };
    assert_eq!(again.err(), Some(expected));
    // Another source asking for it is not a visitor's double tap.
    assert!(
        rig.dispatcher
            .trigger(TriggerRequest::new("A", Source::Operator))
            .is_ok()
    );
}

#[tokio::test(start_paused = true)]
async fn site_priorities_decide_who_interrupts() {
    let mut rig = rig("speech: {adapter: log}\npriorities: {kiosk: 5}\n");
    let operator = rig.trigger("A", Source::Operator, false);
    assert_eq!(rig.next_of(operator).await.0, "started");
    rig.trigger("B", Source::Kiosk, false);
    let (outcome, reason, _) = rig.next_of(operator).await;
    assert_eq!(
        (outcome, reason.as_str()),
        ("cancelled", "the touchscreen took over the speech")
    );
}

#[tokio::test(start_paused = true)]
async fn speech_an_act_has_not_sent_yet_is_dropped_when_its_visitor_leaves_the_page() {
    let mut rig = rig("speech: {adapter: log}\n");
    let later = rig.trigger_from("LATER", 7);
    let other_kiosk = rig.trigger_from("LATER", 8);
    rig.dispatcher.page_left(7, "map.html");
    let (outcome, reason, _) = rig.next_of(later).await;
    assert_eq!(outcome, "cancelled");
    assert_eq!(reason, "the visitor left the page for map.html");
    assert_eq!(
        rig.next_of(other_kiosk).await.0,
        "started",
        "another kiosk's act goes on"
    );
}

#[tokio::test(start_paused = true)]
async fn a_visitors_stop_drops_visitors_unsent_speech_and_leaves_the_operators() {
    let mut rig = rig("speech: {adapter: log}\n");
    let start = Instant::now();
    let visitor = rig.trigger_from("LATER", 7);
    let operator = rig.trigger("A", Source::Operator, false);
    rig.dispatcher.stop_visitor_speech(7);
    let (outcome, reason, _) = rig.next_of(visitor).await;
    assert_eq!(outcome, "cancelled");
    assert_eq!(reason, "a visitor stopped the speech at the touchscreen");
    // Its start went by while the visitor's act waited; it ends done, in full.
    let (outcome, _, at) = rig.next_of(operator).await;
    assert_eq!((outcome, at - start), ("done", say_time()));
}

#[tokio::test(start_paused = true)]
async fn a_drive_replaced_by_another_act_ends_the_rest_of_its_act() {
    let mut rig = rig("speech: {adapter: log}\n");
    let stop_one = rig.trigger_from("GO1", 1);
    rig.trigger("GO2", Source::Operator, false);
    let (outcome, reason, _) = rig.next_of(stop_one).await;
    assert_eq!(
        outcome, "cancelled",
        "nothing is said about the wrong exhibit"
    );
    assert!(reason.starts_with("not sent: an earlier"), "{reason}");
    assert!(
        reason.contains("the operator took over the drive"),
        "{reason}"
    );
}

#[tokio::test(start_paused = true)]
async fn what_the_speech_channel_says_now_is_its_running_say_until_it_ends() {
    let mut rig = rig("speech: {adapter: log}\n");
    assert_eq!(rig.dispatcher.saying_now(), None);
    let first = rig.trigger("A", Source::Operator, false);
    let second = rig.trigger("B", Source::Operator, false);
    assert_eq!(
        rig.dispatcher.saying_now(),
        Some((first, Arc::from(LONG))),
        "the first runs, the second waits"
    );
    assert_eq!(rig.next_of(first).await.0, "started");
    assert_eq!(rig.next_of(first).await.0, "done");
    assert_eq!(rig.next_of(second).await.0, "started");
    assert_eq!(rig.dispatcher.saying_now().map(|(id, _)| id), Some(second));
    assert_eq!(rig.next_of(second).await.0, "done");
    assert_eq!(rig.dispatcher.saying_now(), None);
}

#[tokio::test(start_paused = true)]
async fn a_request_checked_in_one_bundle_is_resolved_in_it_even_after_a_reload() {
    let rig = rig("speech: {adapter: log}\n");
    let checked = rig.dispatcher.bundle();
    // A reload puts a bundle live whose act A says something else.
    let (_dir, edited) = bundle("speech: {adapter: log}\n");
    let mut edited = edited;
    let index = edited.index["A"];
    edited.acts[index].variants[0].alternatives[0].value = "edited".to_owned();
    rig.dispatcher.replace_bundle(Arc::new(edited));
    let request = TriggerRequest::new("A", Source::Kiosk);
    let old = (rig.dispatcher.trigger_in(checked, request.clone())).expect("triggered");
    assert_eq!(
        old.text.as_deref(),
        Some(LONG),
        "resolved in the bundle it was checked in"
    );
    rig.dispatcher.stop(Source::Operator, "next");
    let new = rig.dispatcher.trigger(request).expect("triggered");
    assert_eq!(
        new.text.as_deref(),
        Some("edited"),
        "a new request: the live bundle"
    );
}
