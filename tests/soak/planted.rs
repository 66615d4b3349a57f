//! The pass rules judged on a made-up run: a clean one passes, and each fault the soak is there
//! to find, planted alone, is reported in words. So no rule of the soak passes on nothing.

use std::os::unix::process::ExitStatusExt;
use std::process::ExitStatus;
use std::time::Duration;

use serde_json::{Value, json};

use crate::ledger::{Book, Latency, Role};
use crate::plan::Plan;
use crate::run::{Run, Sample};
use crate::verdict::judge;

const ANSWERS: usize = 600;

fn plan() -> Plan {
    Plan {
        length: Duration::from_secs(60),
        ..Plan::from_env()
    }
}

/// One minute: flat memory and descriptors, 600 triggers answered in 5 ms and logged once,
/// two sessions opened and closed, one recording of 4 bytes kept whole, one save gone live.
fn clean() -> Run {
    let corpus_dir = tempfile::tempdir().expect("a corpus folder");
    let session = corpus_dir.path().join("sessions/2026-11-29T09-00-00Z");
    std::fs::create_dir_all(session.join("media")).expect("a session folder");
    std::fs::write(session.join("session.json"), r#"{"number": 1}"#).expect("manifest");
    std::fs::write(session.join("media/audio-1.webm"), b"WEBM").expect("recording");
    let mut book = Book::default();
    let mut corpus: Vec<Value> = Vec::new();
    for n in 0..ANSWERS {
        let reference = format!("k{}-{n}", n % 50);
        corpus.push(json!({"type": "act.triggered", "ref": reference}));
        book.latencies.push(Latency {
            at: n as f64 * 0.1,
            role: Role::Kiosk,
            ms: 5.0,
        });
        book.acked.push(reference);
    }
    for session in [1, 2] {
        corpus.push(json!({"type": "session.started", "session": session}));
        corpus.push(json!({"type": "session.ended", "session": session}));
    }
    corpus.push(json!({"type": "recording.started", "recording": 1}));
    corpus.push(
        json!({"type": "recording.stopped", "recording": 1, "session": 1,
        "file": "media/audio-1.webm", "bytes": 4}),
    );
    corpus.push(json!({"type": "bundle.reloaded"}));
    book.recordings.insert(1, 4);
    book.chunks = 2;
    let samples = (0..60)
        .map(|s| Sample {
            at: f64::from(s),
            rss_kb: 40_000,
            fds: 200,
            kiosks: 50,
            acked: 0,
        })
        .collect();
    Run {
        samples,
        book,
        corpus,
        corpus_dir,
        exit: Some(ExitStatus::from_raw(0)),
        server_log: String::new(),
        reloads: 1,
        storms: 1,
        wall: Duration::from_secs(61),
    }
}

/// The failures of `run`, which must be exactly one, containing `words`.
fn fails_with(run: &Run, words: &str) {
    let failures = judge(&plan(), run).failures;
    assert!(
        failures.len() == 1 && failures[0].contains(words),
        "expected one failure saying {words:?}, got {failures:#?}"
    );
}

#[test]
fn a_clean_run_passes() {
    let failures = judge(&plan(), &clean()).failures;
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn an_acknowledged_trigger_missing_from_the_corpus_fails() {
    let mut run = clean();
    run.corpus.remove(17);
    fails_with(
        &run,
        "1 acknowledged triggers are not in the corpus exactly once",
    );
}

#[test]
fn a_trigger_logged_twice_fails() {
    let mut run = clean();
    run.corpus
        .push(json!({"type": "act.triggered", "ref": "k3-3"}));
    let failures = judge(&plan(), &run).failures;
    assert_eq!(failures.len(), 2, "{failures:#?}");
    assert!(failures[1].contains("refs logged twice"), "{failures:#?}");
}

#[test]
fn a_session_left_open_fails() {
    let mut run = clean();
    run.corpus
        .retain(|e| !(e["type"] == "session.ended" && e["session"] == 2));
    fails_with(&run, "sessions started [1, 2] but ended [1]");
}

#[test]
fn memory_growing_after_the_warm_up_fails() {
    let mut run = clean();
    for s in run.samples.iter_mut().filter(|s| s.at >= 45.0) {
        s.rss_kb = 44_000;
    }
    fails_with(&run, "RSS grew");
}

#[test]
fn descriptors_growing_after_the_warm_up_fails() {
    let mut run = clean();
    for s in run.samples.iter_mut().filter(|s| s.at >= 45.0) {
        s.fds = 220;
    }
    fails_with(&run, "open file descriptors grew");
}

#[test]
fn latency_growing_through_the_run_fails() {
    let mut run = clean();
    for l in run.book.latencies.iter_mut().filter(|l| l.at >= 45.0) {
        l.ms = 40.0;
    }
    fails_with(&run, "p99 trigger latency");
}

#[test]
fn acknowledged_recording_bytes_not_kept_fail() {
    let mut run = clean();
    run.book.recordings.insert(1, 8);
    fails_with(&run, "recording 1: 8 bytes acknowledged, 4 kept");
}

#[test]
fn a_server_that_does_not_stop_cleanly_fails() {
    let mut run = clean();
    run.exit = None;
    fails_with(&run, "docent did not exit 0 after SIGTERM");
}
