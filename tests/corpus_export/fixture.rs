//! A corpus written by `main` before its readers took the protocol's types
//! (`tests/fixtures/corpus-v4`, README there): every line reads through them as an event
//! this Docent knows, and every export holds what the session did, tier by tier, text by
//! text. A renamed event type or field that the readers stop understanding empties a tier,
//! and fails here.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use docent::corpus::export::{ExportFormat, ExportWarning, export_session};
use docent_protocol::events::{EventKind, Line, LineEvent};
use serde_json::Value;

use crate::common::repo;

const SESSION: &str = "2026-11-29T03-12-04Z";

fn corpus() -> PathBuf {
    repo().join("tests/fixtures/corpus-v4")
}

fn session() -> PathBuf {
    corpus().join("sessions").join(SESSION)
}

/// The session exported in `format` into a temporary folder, and the one file written.
fn exported(format: ExportFormat) -> (tempfile::TempDir, PathBuf) {
    let out = tempfile::tempdir().unwrap();
    let done = export_session(&session(), format, out.path())
        .unwrap_or_else(|e| panic!("{format:?}: {e}"));
    // The bundle the manifest names is where it was served from; on another machine it is
    // gone, and the vocabulary is the session's labels (the same four acts).
    for warning in &done.warnings {
        assert!(
            matches!(warning, ExportWarning::VocabularyFromSessionOnly(_)),
            "{format:?}: {warning}"
        );
    }
    let [file] = &done.files[..] else {
        panic!("{format:?}: one file, not {:?}", done.files)
    };
    let file = file.clone();
    (out, file)
}

/// Every value between `open` and the next `"` or `<` in `text`, but empty ones.
fn values<'a>(text: &'a str, open: &str) -> Vec<&'a str> {
    let mut found: Vec<&str> = (text.split(open).skip(1))
        .map(|rest| rest.split(['"', '<']).next().unwrap_or_default())
        .filter(|value| !value.is_empty())
        .collect();
    found.sort_unstable();
    found
}

/// The texts of the session's utterances, commands, pages, touches and marks, sorted.
const DRAWN: [&str; 21] = [
    "DISPLAY_PAGE map.html",
    "DRIVE_START",
    "Follow me to the window.",
    "GO",
    "GOODBYE",
    "Goodbye!",
    "Hi there",
    "Look at the wall.",
    "PICTURE",
    "PROJECT picture.png",
    "SECRET (refused: not-offered)",
    "SET_WAYPOINT 1 0.5 90",
    "WELCOME",
    "WELCOME",
    "group: children",
    "index.html",
    "index.html",
    "map.html",
    "note: they laughed at the robot",
    "page: index.html",
    "situation: laughter",
];

#[test]
fn every_line_of_the_old_corpus_reads_as_an_event_this_docent_knows() {
    let day = corpus().join("days/2026-11-29/03-12-02Z.jsonl");
    let mut kinds: BTreeMap<String, u64> = BTreeMap::new();
    for log in [day, session().join("events.jsonl")] {
        for line in std::fs::read_to_string(&log).unwrap().lines() {
            let read = Line::parse(line.as_bytes()).unwrap_or_else(|e| panic!("{e}: {line}"));
            let LineEvent::Event(kind) = read.event else {
                panic!("a type of today's format passed over: {line}")
            };
            let name = serde_json::to_value(&kind).unwrap()["type"].clone();
            assert_eq!(name.as_str(), read.head.kind.as_deref(), "{line}");
            *kinds.entry(read.head.kind.unwrap()).or_default() += 1;
            if let EventKind::Pose { x, heading, .. } = kind {
                assert!(x.is_finite() && heading.is_finite(), "{line}");
            }
        }
    }
    let counted: Vec<(&str, u64)> = kinds.iter().map(|(k, n)| (k.as_str(), *n)).collect();
    assert_eq!(
        counted,
        [
            ("act.triggered", 4),
            ("client.connected", 3),
            ("client.left", 3),
            ("command.done", 8),
            ("command.sent", 8),
            ("command.started", 8),
            ("context.changed", 1),
            ("display.changed", 4),
            ("drive.arrived", 1),
            ("note.written", 1),
            ("pose", 3),
            ("server.started", 1),
            ("server.stopping", 1),
            ("session.ended", 1),
            ("session.started", 1),
            ("situation.marked", 1),
            ("stop", 1),
            ("touch", 3),
            ("trigger.refused", 1),
            ("visitor.group", 1),
        ]
    );
}

#[test]
fn the_eaf_and_the_textgrid_of_the_old_corpus_have_every_tier() {
    let (_out, eaf) = exported(ExportFormat::Eaf);
    let eaf = std::fs::read_to_string(eaf).unwrap();
    assert_eq!(values(&eaf, "<ANNOTATION_VALUE>"), DRAWN);
    for tier in ["speech", "act", "commands", "pages", "touches", "marks"] {
        assert!(eaf.contains(&format!("TIER_ID=\"{tier}\"")), "{tier}");
    }
    let (_out, grid) = exported(ExportFormat::TextGrid);
    let grid = std::fs::read_to_string(grid).unwrap();
    let mut drawn = values(&grid, "text = \"");
    drawn.extend(values(&grid, "mark = \""));
    drawn.sort_unstable();
    assert_eq!(drawn, DRAWN);
}

#[test]
fn the_csv_of_the_old_corpus_has_its_utterances_and_touches() {
    let (_out, csv) = exported(ExportFormat::Csv);
    assert_eq!(
        std::fs::read_to_string(csv).unwrap(),
        "start_s,end_s,source,act,variant,alternative,text,kind\r\n\
         0.007819,0.007819,kiosk,WELCOME,,,,touch\r\n\
         0.008524,0.860532,kiosk,WELCOME,TextChild,0,Hi there,utterance\r\n\
         0.862984,2.839676,operator,GO,Text,0,Follow me to the window.,utterance\r\n\
         1.17209,1.17209,kiosk,,,,page: index.html,touch\r\n\
         1.172998,1.172998,kiosk,SECRET,,,refused: not-offered,touch\r\n\
         2.840857,4.442227,operator,PICTURE,Text,0,Look at the wall.,utterance\r\n\
         4.443349,4.919845,operator,GOODBYE,Text,0,Goodbye!,utterance\r\n"
    );
    let (_out, jsonl) = exported(ExportFormat::Jsonl);
    let log = std::fs::read(session().join("events.jsonl")).unwrap();
    assert_eq!(std::fs::read(jsonl).unwrap(), log, "the log as it is");
}

/// The MCAP's messages by topic, each as JSON.
fn mcap_messages(file: &Path) -> BTreeMap<String, Vec<Value>> {
    let bytes = std::fs::read(file).unwrap();
    let mut topics: BTreeMap<String, Vec<Value>> = BTreeMap::new();
    for message in mcap::MessageStream::new(&bytes).unwrap() {
        let message = message.unwrap();
        let value = serde_json::from_slice(&message.data).unwrap();
        topics
            .entry(message.channel.topic.clone())
            .or_default()
            .push(value);
    }
    topics
}

#[test]
fn the_mcap_of_the_old_corpus_has_its_log_poses_projection_and_tiers() {
    let (_out, file) = exported(ExportFormat::Mcap);
    let topics = mcap_messages(&file);
    let counts: Vec<(&str, usize)> = topics.iter().map(|(t, m)| (t.as_str(), m.len())).collect();
    assert_eq!(
        counts,
        [
            ("/docent/commands", 4),
            ("/docent/log", 46),
            ("/docent/marks", 3),
            ("/docent/page", 3),
            ("/docent/pose", 3),
            ("/docent/projection", 3),
            ("/docent/speech", 4),
            ("/docent/touches", 3),
        ]
    );
    let levels: Vec<(u64, &str)> = (topics["/docent/log"].iter())
        .filter(|m| m["level"] != 2)
        .map(|m| (m["level"].as_u64().unwrap(), m["name"].as_str().unwrap()))
        .collect();
    assert_eq!(
        levels,
        [
            (1, "pose"),
            (1, "pose"),
            (1, "pose"),
            (3, "trigger.refused")
        ]
    );
    let arrived = &topics["/docent/pose"][2];
    assert_eq!(arrived["frame_id"], "map");
    assert_eq!(arrived["pose"]["position"]["x"], 1.0);
    assert_eq!(arrived["pose"]["position"]["y"], 0.5);
    let shown = &topics["/docent/projection"][2];
    assert_eq!(shown["projector"], "picture.png");
    assert_eq!(shown["projector_state"], "shown");
    let spoken: Vec<(&str, &str)> = (topics["/docent/speech"].iter())
        .map(|u| (u["act"].as_str().unwrap(), u["source"].as_str().unwrap()))
        .collect();
    assert_eq!(
        spoken,
        [
            ("WELCOME", "kiosk"),
            ("GO", "operator"),
            ("PICTURE", "operator"),
            ("GOODBYE", "operator")
        ]
    );
}
