//! Cool-downs on a paused tokio clock: a reaction fires, is held back for its cool-down and
//! fires again after it; an undecidable condition is told once per cool-down.

use std::sync::Arc;
use std::time::Duration;

use serde_json::json;

use super::{Reacted, Reactions};
use crate::content::load_bundle;
use crate::dispatch::Dispatcher;
use crate::events::{EventKind, Hub, ReactionFailed};

const CONFIG: &str = "speech: {adapter: log}\nreactions:\n  - {event: person.near, if: distance < 2, act: HELLO, cooldown: 30s}\n";

fn dispatcher() -> (tempfile::TempDir, Arc<Dispatcher>, Hub) {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(
        dir.path().join("acts.yaml"),
        "- Label: HELLO\n  Text: [Hi]\n",
    )
    .unwrap();
    std::fs::create_dir_all(dir.path().join("pages")).unwrap();
    std::fs::write(
        dir.path().join("pages/index.html"),
        "<!doctype html><title>x</title>",
    )
    .unwrap();
    std::fs::write(dir.path().join("docent.yaml"), CONFIG).unwrap();
    let report = load_bundle(dir.path());
    let bundle = report
        .bundle
        .unwrap_or_else(|| panic!("{:#?}", report.diagnostics));
    let (hub, _corpus) = Hub::new();
    let dispatcher = crate::dispatch::log_dispatcher(bundle, &hub);
    (dir, dispatcher, hub)
}

#[tokio::test(start_paused = true)]
async fn a_reaction_fires_again_only_once_its_cooldown_has_passed() {
    let (_dir, dispatcher, hub) = dispatcher();
    let reactions = Reactions::default();
    let config = dispatcher.bundle().config.clone();
    let near = json!({"distance": 1.0});
    let react = || reactions.react(&config.reactions, ("person.near", &near), &dispatcher, &hub);
    assert_eq!(react(), [Reacted::Triggered]);
    tokio::time::advance(Duration::from_secs(29)).await;
    assert_eq!(react(), [Reacted::CoolingDown]);
    tokio::time::advance(Duration::from_secs(1)).await;
    assert_eq!(react(), [Reacted::Triggered]);
    let far = json!({"distance": 5});
    let other = reactions.react(&config.reactions, ("person.near", &far), &dispatcher, &hub);
    assert_eq!(other, [Reacted::NotMet]);
    let unrelated = reactions.react(&config.reactions, ("bumper", &near), &dispatcher, &hub);
    assert_eq!(unrelated, []);
}

#[tokio::test(start_paused = true)]
async fn an_undecidable_condition_is_told_once_per_cooldown() {
    let (_dir, dispatcher, hub) = dispatcher();
    let mut events = hub.subscribe();
    let reactions = Reactions::default();
    let config = dispatcher.bundle().config.clone();
    let odd = json!({"range": 1.0});
    let react = || reactions.react(&config.reactions, ("person.near", &odd), &dispatcher, &hub);
    let undecided = Reacted::Undecided("the event's data has no field `distance`".into());
    assert_eq!(react(), std::slice::from_ref(&undecided));
    assert_eq!(react(), std::slice::from_ref(&undecided));
    tokio::time::advance(Duration::from_secs(30)).await;
    assert_eq!(react(), [undecided]);
    let mut told = 0;
    while let Ok(event) = events.try_recv() {
        if let EventKind::ReactionFailed(ReactionFailed { reaction, .. }) = &event.kind {
            assert_eq!(*reaction, 1);
            told += 1;
        }
    }
    assert_eq!(told, 2, "once, and once more after the cool-down");
}
