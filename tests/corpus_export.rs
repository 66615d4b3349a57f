//! A real visitor session exported to ELAN EAF, Praat TextGrid, CSV and JSON Lines, then read
//! back with the tools researchers use (pympi-ling; praatio and Praat itself through
//! praat-parselmouth; Python's csv module: `tests/readers/check_exports.py`, in the virtualenv
//! `scripts/install-test-deps.sh` makes) and compared with the session's log tier by tier,
//! time by time, text by text. The expectations are worked out here from the log's lines, not
//! from the exporter's model. Also: what a researcher is told about a session that cannot be
//! exported as it is.

mod common;

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;

use common::{TempBundle, TestServer, WsClient, repo};
use docent::corpus::export::{ExportError, ExportFormat, ExportWarning, export_session};
use docent::corpus::layout::{SESSION_EVENTS, SESSIONS_DIR};
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
fn read_back(dir: &Path, name: &str) -> Value {
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

fn log_lines(session: &Path) -> Vec<Value> {
    (std::fs::read_to_string(session.join(SESSION_EVENTS))
        .unwrap()
        .lines())
    .map(|l| serde_json::from_str(l).unwrap())
    .collect()
}

fn at(e: &Value) -> u64 {
    e["session_us"].as_u64().unwrap()
}

/// What the log says each tool should read: (start µs, end µs drawn, value) per tier kind.
struct Expected {
    /// Each begun `SAY`: start, end, text, act label, and its act's variant and alternative.
    speech: Vec<(u64, u64, String, String, Value, Value)>,
    /// Each other command: start, end, `VERB arg`.
    commands: Vec<(u64, u64, String)>,
    pages: Vec<(u64, u64, String)>,
    touches: Vec<(u64, String)>,
    marks: Vec<(u64, String)>,
    end_us: u64,
}

/// Worked out from the log's lines as the docs describe the tiers (an interval shorter than
/// 1 ms drawn 1 ms long).
fn expected(log: &[Value]) -> Expected {
    let drawn = |start: u64, end: u64| end.max(start + 1000);
    let mut commands: BTreeMap<u64, (Option<u64>, Option<u64>, String, Value)> = BTreeMap::new();
    let mut acts = BTreeMap::new();
    let (mut pages, mut touches, mut marks) = (Vec::new(), Vec::new(), Vec::new());
    for e in log {
        let id = e["command"].as_u64().unwrap_or(0);
        match e["type"].as_str().unwrap() {
            "act.triggered" => {
                acts.insert(e["trigger"].as_u64().unwrap(), e.clone());
                if e["source"] == "kiosk" {
                    touches.push((at(e), e["label"].as_str().unwrap().to_owned()));
                }
            }
            "command.sent" => {
                let verb = e["verb"].as_str().unwrap();
                let value = match e["arg"].as_str() {
                    Some(arg) if verb != "SAY" => format!("{verb} {arg}"),
                    Some(arg) => arg.to_owned(),
                    None => verb.to_owned(),
                };
                commands.insert(id, (None, None, value, e.clone()));
            }
            "command.started" => commands.get_mut(&id).unwrap().0 = Some(at(e)),
            "command.done" => commands.get_mut(&id).unwrap().1 = Some(at(e)),
            "display.changed" => {
                let page = e["page"].as_str().unwrap().to_owned();
                if pages.last().is_none_or(|(_, p): &(u64, String)| *p != page) {
                    if page == "index.html" {
                        touches.push((at(e), format!("page: {page}")));
                    }
                    pages.push((at(e), page));
                }
            }
            "situation.marked" => {
                let situation = e["situation"].as_str().unwrap();
                marks.push((at(e), format!("situation: {situation}")));
            }
            "visitor.group" => {
                let group = e["group"].as_str().unwrap();
                marks.push((at(e), format!("group: {group}")));
            }
            _ => {}
        }
    }
    let end_us = at(log.last().unwrap());
    let (mut speech, mut others) = (Vec::new(), Vec::new());
    for (started, done, value, sent) in commands.into_values() {
        let (start, end) = (started.unwrap(), done.unwrap());
        if sent["verb"] == "SAY" {
            let act = &acts[&sent["trigger"].as_u64().unwrap()];
            let label = sent["label"].as_str().unwrap().to_owned();
            let (variant, alternative) = (act["variant"].clone(), act["alternative"].clone());
            speech.push((start, drawn(start, end), value, label, variant, alternative));
        } else {
            others.push((start, drawn(start, end), value));
        }
    }
    let ends: Vec<u64> = pages
        .iter()
        .skip(1)
        .map(|(t, _)| *t)
        .chain([end_us])
        .collect();
    let pages = (pages.into_iter().zip(ends))
        .map(|((start, page), end)| (start, end, page))
        .collect();
    Expected {
        speech,
        commands: others,
        pages,
        touches,
        marks,
        end_us,
    }
}

fn ms(us: u64) -> u64 {
    us / 1000
}

fn s(us: u64) -> f64 {
    us as f64 / 1e6
}

fn close(a: &Value, b: f64) -> bool {
    (a.as_f64().unwrap() - b).abs() < 1e-9
}

/// The documented rule for overlaps: each interval, by start, goes to the first tier of its
/// kind (`base`, `base-2`, ...) whose intervals have all ended by then.
fn spread(base: &str, spans: &[(u64, u64, String)]) -> Vec<(String, Vec<(u64, u64, String)>)> {
    let mut sorted = spans.to_vec();
    sorted.sort();
    let mut tiers: Vec<(String, Vec<(u64, u64, String)>)> = vec![(base.to_owned(), Vec::new())];
    for span in sorted {
        let free = (tiers.iter_mut()).find(|(_, t)| t.last().is_none_or(|last| last.1 <= span.0));
        match free {
            Some((_, tier)) => tier.push(span),
            None => {
                let name = format!("{base}-{}", tiers.len() + 1);
                tiers.push((name, vec![span]));
            }
        }
    }
    tiers
}

/// Points as the 1 ms intervals both formats lay them out by.
fn point_spans(points: &[(u64, String)]) -> Vec<(u64, u64, String)> {
    (points.iter())
        .map(|(t, v)| (*t, t + 1000, v.clone()))
        .collect()
}

/// An EAF tier as pympi read it, against spans in µs.
fn assert_eaf_tier(eaf: &Value, name: &str, want: &[(u64, u64, String)]) {
    let want: Vec<Value> = (want.iter())
        .map(|(start, end, v)| json!([ms(*start), ms(*end), v]))
        .collect();
    assert_eq!(eaf["tiers"][name], json!(want), "EAF tier {name}");
}

/// A TextGrid interval tier as Praat read it (labelled intervals), against spans in µs.
fn assert_praat_intervals(grid: &Value, name: &str, want: &[(u64, u64, String)]) {
    let tier = &grid["tiers"][name];
    assert_eq!(tier["class"], "IntervalTier", "{name}");
    let read = tier["entries"].as_array().unwrap();
    assert_eq!(read.len(), want.len(), "TextGrid tier {name}: {read:?}");
    for (r, (start, end, value)) in read.iter().zip(want) {
        assert!(
            close(&r[0], s(*start)) && close(&r[1], s(*end)),
            "{name}: {r} {start} {end}"
        );
        assert_eq!(r[2], json!(value), "TextGrid tier {name}");
    }
}

/// A TextGrid point tier as Praat read it.
fn assert_praat_points(grid: &Value, name: &str, want: &[(u64, String)]) {
    let tier = &grid["tiers"][name];
    assert_eq!(tier["class"], "TextTier", "{name}");
    let read = tier["entries"].as_array().unwrap();
    assert_eq!(read.len(), want.len(), "TextGrid tier {name}: {read:?}");
    for (r, (t, value)) in read.iter().zip(want) {
        assert!(close(&r[0], s(*t)), "{name}: {r} {t}");
        assert_eq!(r[1], json!(value), "TextGrid tier {name}");
    }
}

#[tokio::test]
async fn a_recorded_session_reads_back_the_same_in_elan_praat_and_a_spreadsheet() {
    let b = bundle();
    let corpus = tempfile::tempdir().unwrap();
    let session = record_session(&b, corpus.path()).await;
    let name = session.file_name().unwrap().to_str().unwrap().to_owned();
    let out = tempfile::tempdir().unwrap();
    for format in ExportFormat::ALL {
        let exported = export_session(&session, format, out.path()).unwrap();
        let file = out.path().join(format!("{name}.{}", format.extension()));
        assert_eq!(exported.files, [file], "{format}");
        assert_eq!(exported.warnings, [], "{format}");
    }
    let copy = std::fs::read(out.path().join(format!("{name}.jsonl"))).unwrap();
    assert_eq!(copy, std::fs::read(session.join(SESSION_EVENTS)).unwrap());

    let log = log_lines(&session);
    let want = expected(&log);
    let read = read_back(out.path(), &name);
    assert_eq!(read["problems"], json!([]), "what the readers let pass");

    // The session as it was played.
    let said: Vec<&str> = want.speech.iter().map(|u| u.2.as_str()).collect();
    let welcome = "Hello, \"friends\": welcome to the café!";
    assert_eq!(said, ["Follow me, please", welcome, "Goodbye"]);
    let touched: Vec<&str> = want.touches.iter().map(|t| t.1.as_str()).collect();
    assert_eq!(touched, ["page: index.html", "WELCOME"]);
    let commands = spread("commands", &want.commands);
    assert!(
        commands.len() >= 2,
        "the drive and the page overlap: {commands:?}"
    );
    let speech: Vec<(u64, u64, String)> = (want.speech.iter())
        .map(|u| (u.0, u.1, u.2.clone()))
        .collect();
    let acts: Vec<(u64, u64, String)> = (want.speech.iter())
        .map(|u| (u.0, u.1, u.3.clone()))
        .collect();
    let pages = [("pages".to_owned(), want.pages.clone())];
    let touches = spread("touches", &point_spans(&want.touches));
    let marks = spread("marks", &point_spans(&want.marks));
    let mut order = vec!["speech".to_owned(), "act".to_owned()];
    order.extend(commands.iter().map(|(n, _)| n.clone()));
    order.push("pages".to_owned());
    order.extend(touches.iter().chain(&marks).map(|(n, _)| n.clone()));

    // ELAN, through pympi.
    let eaf = &read["eaf"];
    assert_eq!(eaf["order"], json!(order));
    assert_eq!(eaf["parents"], json!({"act": "speech"}));
    assert_eaf_tier(eaf, "speech", &speech);
    let act_tier: Vec<Value> = (want.speech.iter())
        .map(|u| json!([ms(u.0), ms(u.1), u.3, u.2]))
        .collect();
    assert_eq!(
        eaf["ref_tiers"]["act"],
        json!(act_tier),
        "labels beside their parents' texts"
    );
    for (name, spans) in commands.iter().chain(&pages).chain(&touches).chain(&marks) {
        assert_eaf_tier(eaf, name, spans);
    }
    let vocabulary: BTreeSet<&str> = (eaf["vocabulary"].as_object().unwrap().values())
        .map(|v| v.as_str().unwrap())
        .collect();
    assert_eq!(
        vocabulary,
        BTreeSet::from(["GOODBYE", "LATER", "TOUR", "WELCOME"]),
        "the bundle's labels, the unused too"
    );

    // Praat's own reading (praatio's agrees: `problems` is empty).
    let praat = &read["textgrid_praat"];
    assert_eq!(praat["order"], json!(order));
    assert!(close(&praat["xmin"], 0.0) && close(&praat["xmax"], s(want.end_us)));
    assert_praat_intervals(praat, "speech", &speech);
    assert_praat_intervals(praat, "act", &acts);
    for (name, spans) in commands.iter().chain(&pages) {
        assert_praat_intervals(praat, name, spans);
    }
    for (name, spans) in touches.iter().chain(&marks) {
        let points: Vec<(u64, String)> = spans.iter().map(|(t, _, v)| (*t, v.clone())).collect();
        assert_praat_points(praat, name, &points);
    }

    // The spreadsheet, through Python's csv module.
    let csv = &read["csv"];
    let header = "start_s end_s source act variant alternative text kind";
    assert_eq!(csv["header"], json!(header.split(' ').collect::<Vec<_>>()));
    let mut rows: Vec<(u64, Value)> = (want.speech.iter())
        .map(|(start, end, text, label, variant, alternative)| {
            let source = &log
                .iter()
                .find(|e| e["type"] == "act.triggered" && e["label"] == *label)
                .unwrap()["source"];
            let row = json!([
                s(*start),
                s(*end),
                source,
                label,
                variant,
                alternative.to_string(),
                text,
                "utterance"
            ]);
            (*start, row)
        })
        .collect();
    for (t, value) in &want.touches {
        let (act, text) = match value.strip_prefix("page: ") {
            Some(_) => ("", value.as_str()),
            None => (value.as_str(), ""),
        };
        rows.push((
            *t,
            json!([s(*t), s(*t), "kiosk", act, "", "", text, "touch"]),
        ));
    }
    rows.sort_by_key(|(t, _)| *t);
    let read_rows = csv["rows"].as_array().unwrap();
    assert_eq!(read_rows.len(), rows.len(), "{read_rows:?}");
    for (r, (_, w)) in read_rows.iter().zip(&rows) {
        let number = |v: &Value| v.as_str().unwrap().parse::<f64>().unwrap();
        assert!(
            (number(&r[0]) - w[0].as_f64().unwrap()).abs() < 1e-9,
            "{r} {w}"
        );
        assert!(
            (number(&r[1]) - w[1].as_f64().unwrap()).abs() < 1e-9,
            "{r} {w}"
        );
        assert_eq!(
            r.as_array().unwrap()[2..],
            w.as_array().unwrap()[2..],
            "CSV row"
        );
    }
}
