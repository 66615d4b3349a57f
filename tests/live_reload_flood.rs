//! Live reloads during a flood of triggers: four operators trigger one act 500 times each while
//! its text is saved anew ("v1", "v2", ...) as the answers come in. Every trigger is answered
//! exactly once; every one is in the log (as many `act.triggered` as answers); and each was
//! resolved in one bundle: the text it answered, its `act.triggered` and its `SAY` all belong
//! to the bundle its `act.triggered` names by fingerprint.

use crate::common;

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::Path;
use std::time::Duration;

use common::{TempBundle, TestServer, WsClient};
use docent::reload::ReloadOptions;
use serde_json::{Value, json};
use tokio::sync::{mpsc, watch};

const CLIENTS: usize = 4;
const EACH: usize = 500;
/// A new text is saved each time this many more answers have come in.
const SAVE_EVERY: usize = 350;
/// How many times a new text is saved during the flood.
const SAVES: usize = (CLIENTS * EACH - 1) / SAVE_EVERY;

fn acts(version: usize) -> String {
    format!("- Label: X\n  Text:\n    - v{version}\n")
}

/// Saves version `version` of the acts file in one step (a rename), so that a reload never
/// reads half a file, and returns the bundle's fingerprint with it.
fn save(bundle: &Path, scratch: &Path, version: usize) -> String {
    let staged = scratch.join("acts.yaml");
    std::fs::write(&staged, acts(version)).expect("stage");
    std::fs::rename(&staged, bundle.join("acts.yaml")).expect("save");
    docent::content::bundle_fingerprint(bundle).expect("fingerprint")
}

/// Triggers X `EACH` times, one after another, each answer awaited; returns every answer's
/// text by reference. Any second answer to a reference fails the test.
async fn flood(mut client: WsClient, name: usize, answered: watch::Sender<usize>) -> Vec<String> {
    let mut texts = Vec::with_capacity(EACH);
    let mut seen = BTreeSet::new();
    for n in 0..EACH {
        let reference = format!("c{name}-{n}");
        let trigger = json!({"type": "trigger", "label": "X", "interrupt": true, "ref": reference});
        client.send(trigger).await;
        loop {
            let frame = client.recv().await;
            // Outcomes tell how a command ended (cut short by the next trigger): not answers.
            if frame["type"] == "outcome" {
                continue;
            }
            let Some(said) = frame["ref"].as_str() else {
                continue;
            };
            assert!(seen.insert(said.to_owned()), "answered twice: {frame}");
            assert_eq!(said, reference, "an answer out of order: {frame}");
            assert_eq!(frame["type"], "triggered", "{frame}");
            texts.push(frame["text"].as_str().expect("a text").to_owned());
            break;
        }
        answered.send_modify(|n| *n += 1);
    }
    texts
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_flood_of_triggers_across_live_reloads_is_answered_once_each_in_one_bundle() {
    let b = TempBundle::new(&acts(1)).with_file("docent.yaml", "speech: {adapter: log}\n");
    let scratch = tempfile::tempdir().expect("scratch folder");
    let mut versions: HashMap<String, String> = HashMap::new();
    let first = docent::content::bundle_fingerprint(b.path()).expect("fingerprint");
    versions.insert(first, "v1".into());
    let watch = |server: &docent::serve::Server| {
        server.watch(ReloadOptions {
            debounce: Duration::from_millis(20),
            ..ReloadOptions::default()
        });
    };
    let server = TestServer::start_prepared(b.path(), |_| {}, watch).await;
    let reloaded = reloads(server.operator().await);
    let (answered, mut count) = watch::channel(0);
    let mut clients = Vec::new();
    for name in 0..CLIENTS {
        let quiet = json!({"type": "hello", "role": "operator", "events": false});
        let client = server.client(quiet).await;
        clients.push(tokio::spawn(flood(client, name, answered.clone())));
    }
    // Saves while the answers come in: a new text after each `SAVE_EVERY` answers, each one
    // once the one before is live (so no two saves are checked as one).
    let mut reloaded = reloaded;
    for version in 2..=SAVES + 1 {
        let due = (version - 1) * SAVE_EVERY;
        let flowing = common::within(common::DEADLINE, count.wait_for(|n| *n >= due));
        flowing.await.expect("the flood goes on").expect("counted");
        let hash = save(b.path(), scratch.path(), version);
        versions.insert(hash.clone(), format!("v{version}"));
        let live = common::within(common::DEADLINE, reloaded.recv()).await;
        assert_eq!(
            live.expect("reloaded in time").as_deref(),
            Some(hash.as_str())
        );
    }
    let mut answers: BTreeMap<String, String> = BTreeMap::new();
    for (name, client) in clients.into_iter().enumerate() {
        let texts = client.await.expect("a flooding client");
        assert_eq!(texts.len(), EACH);
        // One operator's triggers, one after another: the texts only move on.
        let mut sorted = texts.clone();
        sorted.sort_by_key(|t| t[1..].parse::<usize>().expect("vN"));
        assert_eq!(texts, sorted, "client {name} went back to an older bundle");
        for (n, text) in texts.into_iter().enumerate() {
            answers.insert(format!("c{name}-{n}"), text);
        }
    }
    let log = server.stop().await;
    assert_in_one_bundle(&log, &answers, &versions);
}

/// The fingerprints of the next `SAVES` bundles that go live, as `watcher` reads them; read
/// on their own task so that the flood's events never pile up unread.
fn reloads(mut watcher: WsClient) -> mpsc::UnboundedReceiver<String> {
    let (tx, rx) = mpsc::unbounded_channel();
    tokio::spawn(async move {
        for _ in 0..SAVES {
            let live = watcher.event("bundle.reloaded").await;
            let hash = live["bundle_hash"].as_str().unwrap_or_default().to_owned();
            if tx.send(hash).is_err() {
                return;
            }
        }
    });
    rx
}

/// Every answer is in the log once, resolved in the bundle its `act.triggered` names, with its
/// `SAY` saying that bundle's text; and the triggers span several bundles.
fn assert_in_one_bundle(
    log: &[Value],
    answers: &BTreeMap<String, String>,
    versions: &HashMap<String, String>,
) {
    let triggered: Vec<&Value> = (log.iter())
        .filter(|e| e["type"] == "act.triggered" && e["label"] == "X")
        .collect();
    assert_eq!(triggered.len(), CLIENTS * EACH, "triggers lost or doubled");
    let mut by_trigger: HashMap<u64, &str> = HashMap::new();
    let mut spanned = BTreeSet::new();
    for e in &triggered {
        let hash = e["bundle_hash"].as_str().expect("the bundle's fingerprint");
        let version = (versions.get(hash)).unwrap_or_else(|| panic!("an unknown bundle: {e}"));
        assert_eq!(e["text"], **version, "resolved in two bundles: {e}");
        let reference = e["ref"].as_str().expect("a ref");
        assert_eq!(answers[reference], *version, "answered otherwise: {e}");
        by_trigger.insert(e["trigger"].as_u64().expect("a trigger id"), version);
        spanned.insert(version.as_str());
    }
    let refs: BTreeSet<&str> = triggered.iter().filter_map(|e| e["ref"].as_str()).collect();
    assert_eq!(refs.len(), answers.len(), "a reference logged twice");
    let says: Vec<&Value> = (log.iter())
        .filter(|e| e["type"] == "command.sent" && e["verb"] == "SAY")
        .collect();
    assert!(!says.is_empty());
    for say in says {
        let trigger = say["trigger"].as_u64().expect("a trigger id");
        assert_eq!(
            say["arg"], by_trigger[&trigger],
            "a SAY from another bundle: {say}"
        );
    }
    assert!(
        spanned.len() >= 3,
        "the reloads did not happen during the flood: {spanned:?}"
    );
}
