//! Sessions that cannot be exported as they are, one hand-written fixture each: a folder that is
//! no session, a damaged line, a missing manifest, and a session whose server was killed (its
//! last line torn, no `session.ended`, its bundle gone). Each outcome is what the researcher
//! is told, word for word.

use std::path::PathBuf;

use docent::corpus::export::{
    ExportError, ExportFormat, ExportWarning, UnknownFormat, export_session,
};
use docent::corpus::manifest::{MANIFEST_FORMAT, SessionManifest, SessionMark};
use serde_json::json;

use super::read_back;

const NAME: &str = "2026-11-24T10-15-02Z";

/// A session folder `sessions/NAME/` holding `log` as its events and a manifest naming
/// `bundle` (in a temporary corpus folder, returned with it).
fn session(log: &str, bundle: &str) -> (tempfile::TempDir, PathBuf) {
    let corpus = tempfile::tempdir().unwrap();
    let dir = corpus.path().join("sessions").join(NAME);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("events.jsonl"), log).unwrap();
    let manifest = SessionManifest {
        format: MANIFEST_FORMAT,
        session: NAME.to_owned(),
        number: 1,
        docent: "0.1.0".to_owned(),
        bundle: Some(bundle.to_owned()),
        bundle_hash: None,
        started: SessionMark {
            seq: 5,
            time: "2026-11-24T10:15:02.000Z".to_owned(),
            mono_us: 100,
            source: "operator".to_owned(),
            reason: None,
        },
        ended: None,
        group: None,
        context: Some("Text".to_owned()),
        consent: "recorded".to_owned(),
        media: Vec::new(),
    };
    manifest.write_to(&dir).unwrap();
    (corpus, dir)
}

/// A tour that was still under way when the server was killed: the act's `SAY` and
/// `DRIVE_START` began, a pose, and a line cut short.
const KILLED: &str = concat!(
    r#"{"v":3,"seq":5,"time":"2026-11-24T10:15:02.000Z","mono_us":100,"session_us":0,"type":"session.started","session":1,"source":"operator","client":1}"#,
    "\n",
    r#"{"v":3,"seq":6,"time":"2026-11-24T10:15:02.001Z","mono_us":1100,"session_us":1000,"type":"act.triggered","trigger":2,"source":"operator","client":1,"label":"TOUR","at":"acts.yaml:4","context":"Text","variant":"Text","alternative":0,"text":"Follow me","interrupt":false}"#,
    "\n",
    r#"{"v":3,"seq":7,"time":"2026-11-24T10:15:02.001Z","mono_us":1200,"session_us":1100,"type":"command.sent","command":3,"trigger":2,"source":"operator","client":1,"label":"TOUR","at":"acts.yaml:4","verb":"SAY","arg":"Follow me","args":{"text":"Follow me"},"adapter":"log"}"#,
    "\n",
    r#"{"v":3,"seq":8,"time":"2026-11-24T10:15:02.001Z","mono_us":1300,"session_us":1200,"type":"command.started","command":3,"trigger":2,"source":"operator","client":1,"label":"TOUR","at":"acts.yaml:4","verb":"SAY"}"#,
    "\n",
    r#"{"v":3,"seq":9,"time":"2026-11-24T10:15:02.001Z","mono_us":1400,"session_us":1300,"type":"command.sent","command":4,"trigger":2,"source":"operator","client":1,"label":"TOUR","at":"acts.yaml:4","verb":"DRIVE_START","arg":null,"args":{},"adapter":"sim"}"#,
    "\n",
    r#"{"v":3,"seq":10,"time":"2026-11-24T10:15:02.001Z","mono_us":1500,"session_us":1400,"type":"command.started","command":4,"trigger":2,"source":"operator","client":1,"label":"TOUR","at":"acts.yaml:4","verb":"DRIVE_START"}"#,
    "\n",
    r#"{"v":3,"seq":11,"time":"2026-11-24T10:15:04.500Z","mono_us":2500100,"session_us":2500000,"type":"pose","x":1.0,"y":0.0,"heading":0.0,"moving":true}"#,
    "\n",
    r#"{"v":3,"seq":12,"time":"2026-11-24T10:15:04.6"#,
);

#[test]
fn a_folder_that_is_no_session_is_named_with_what_a_session_is() {
    let corpus = tempfile::tempdir().unwrap();
    let out = corpus.path().join("out");
    let missing = corpus.path().join("sessions/2026-01-01T00-00-00Z");
    let error = export_session(&missing, ExportFormat::Eaf, &out).unwrap_err();
    assert!(matches!(error, ExportError::UnknownSession(_)), "{error:?}");
    assert_eq!(
        error.to_string(),
        format!(
            "there is no session folder {}: a session is named by its folder under the corpus \
             folder's `sessions/` (`docent corpus list` names them)",
            missing.display()
        )
    );
    let error = export_session(corpus.path(), ExportFormat::Eaf, &out).unwrap_err();
    assert_eq!(
        error.to_string(),
        format!(
            "{} is not a session folder: it has no `events.jsonl` (a session folder is one \
             under the corpus folder's `sessions/`)",
            corpus.path().display()
        )
    );
    assert!(!out.exists(), "nothing written");
}

#[test]
fn a_damaged_line_stops_the_export_at_its_file_and_line_and_writes_nothing() {
    let lines: Vec<&str> = KILLED.lines().take(2).collect();
    let broken = r#"{"v":3,"seq":7,"session_us":1100,"type":"command.sent","command":3}"#;
    let (_corpus, dir) = session(&format!("{}\n{broken}\n", lines.join("\n")), "/nowhere");
    let out = dir.join("exports");
    let error = export_session(&dir, ExportFormat::TextGrid, &out).unwrap_err();
    let log = dir.join("events.jsonl");
    assert!(
        matches!(&error, ExportError::DamagedLog { path, line: 3, .. } if *path == log),
        "{error:?}"
    );
    assert_eq!(
        error.to_string(),
        format!(
            "{}:3: the session's log is damaged: missing field `verb` (column 67). Nothing \
             was exported; repair or remove that line (keep a copy of the original) and export \
             again",
            log.display()
        )
    );
    assert!(!out.exists(), "nothing written");
}

#[test]
fn a_session_without_its_manifest_is_damaged() {
    let (_corpus, dir) = session(KILLED, "/nowhere");
    std::fs::remove_file(dir.join("session.json")).unwrap();
    let error = export_session(&dir, ExportFormat::Csv, &dir.join("exports")).unwrap_err();
    assert_eq!(
        error.to_string(),
        format!(
            "{}: the session's manifest is missing or damaged (No such file or directory (os \
             error 2)); nothing was exported",
            dir.join("session.json").display()
        )
    );
}

#[test]
fn a_format_is_named_as_the_command_line_takes_it() {
    let names: Vec<String> = ExportFormat::ALL.iter().map(|f| f.to_string()).collect();
    assert_eq!(names, ["eaf", "textgrid", "csv", "jsonl", "mcap"]);
    assert_eq!("TextGrid".parse(), Ok(ExportFormat::TextGrid));
    assert_eq!("MCAP".parse(), Ok(ExportFormat::Mcap));
    let unknown = "elan".parse::<ExportFormat>().unwrap_err();
    assert_eq!(unknown, UnknownFormat("elan".into()));
    assert_eq!(
        unknown.to_string(),
        "\"elan\" is not an export format: use eaf, textgrid, csv, jsonl or mcap"
    );
}

#[test]
fn a_killed_servers_session_exports_up_to_its_last_whole_line_and_says_so() {
    let gone = "/nowhere/museum-tour";
    let (_corpus, dir) = session(KILLED, gone);
    let out = dir.join("exports");
    let mut warnings = Vec::new();
    for format in ExportFormat::ALL {
        let exported = export_session(&dir, format, &out).unwrap();
        warnings = exported.warnings;
    }
    let log = dir.join("events.jsonl");
    let told: Vec<String> = warnings.iter().map(ToString::to_string).collect();
    assert_eq!(
        warnings[..2],
        [
            ExportWarning::IncompleteLastLine {
                path: log.clone(),
                line: 8
            },
            ExportWarning::NotEnded {
                end_s: "2.5".into()
            },
        ]
    );
    assert_eq!(
        told[2],
        format!(
            "the EAF's vocabulary of act labels holds only the labels this session used: its \
             bundle {gone} does not load any more: {gone}:1: `{gone}` is not a folder Docent \
             can open. Give the path of the bundle folder (the one holding the acts files, \
             pages/ and media/)."
        )
    );
    assert_eq!(
        told[1],
        "the session has no `session.ended` (its server was killed or crashed while it ran): \
         it is taken to end at its last line, 2.5 s after its start, and what was under way \
         then is shown as ending there"
    );
    let copy = std::fs::read_to_string(out.join(format!("{NAME}.jsonl"))).unwrap();
    assert_eq!(
        copy,
        KILLED[..KILLED.rfind('\n').unwrap() + 1],
        "the whole lines"
    );

    let read = read_back(&out, NAME);
    assert_eq!(read["problems"], json!([]));
    let eaf = &read["eaf"];
    assert_eq!(eaf["tiers"]["speech"], json!([[1, 2500, "Follow me"]]));
    let open = "DRIVE_START (no outcome in the log)";
    assert_eq!(eaf["tiers"]["commands"], json!([[1, 2500, open]]));
    assert_eq!(
        eaf["ref_tiers"]["act"],
        json!([[1, 2500, "TOUR", "Follow me"]])
    );
    assert_eq!(
        eaf["vocabulary"],
        json!({"cveid_1": "TOUR"}),
        "the session's labels"
    );
    assert_eq!(read["textgrid_praat"]["xmax"], json!(2.5));
    let rows = &read["csv"]["rows"];
    assert_eq!(
        rows,
        &json!([[
            "0.0012",
            "2.5",
            "operator",
            "TOUR",
            "Text",
            "0",
            "Follow me",
            "utterance"
        ]])
    );
}
