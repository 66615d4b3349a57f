//! The MCAP export read back by the `mcap` Python reader (`tests/readers/check_mcap.py`, which
//! validates every message against its channel's schema) and compared with the session's log
//! channel by channel, time by time, text by text: what each channel should hold is worked out
//! here from the log's lines as `docs/CORPUS.md` ("MCAP") describes it.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;
use std::time::UNIX_EPOCH;

use serde_json::{Value, json};

use crate::common::repo;
use crate::corpus_export::expected::{at, expected};

/// What check_mcap.py read from `file`; its `problems` must be empty.
pub fn read_mcap(file: &Path) -> Value {
    let python = repo().join("tests/readers/.venv/bin/python");
    assert!(
        python.is_file(),
        "{} is missing: run scripts/install-test-deps.sh (it installs the mcap reader)",
        python.display()
    );
    let output = Command::new(python)
        .arg(repo().join("tests/readers/check_mcap.py"))
        .arg(file)
        .output()
        .expect("python runs");
    assert!(
        output.status.success(),
        "check_mcap.py failed:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let read: Value = serde_json::from_slice(&output.stdout).expect("a JSON summary");
    assert_eq!(
        read["problems"],
        json!([]),
        "what the reader found or let pass"
    );
    read
}

/// The session clock's zero on the MCAP's clock: the manifest's `started.time`, in ns.
pub fn zero_ns(manifest: &Value) -> u64 {
    let time = manifest["started"]["time"].as_str().unwrap();
    let since = humantime::parse_rfc3339(time)
        .unwrap()
        .duration_since(UNIX_EPOCH);
    since.unwrap().as_nanos() as u64
}

/// A channel's messages as read: (log time, message).
fn messages<'a>(read: &'a Value, topic: &str, schema: &str) -> Vec<(u64, &'a Value)> {
    let channel = &read["channels"][topic];
    if channel.is_null() {
        return Vec::new();
    }
    assert_eq!(channel["schema"], schema, "{topic}");
    (channel["messages"].as_array().unwrap().iter())
        .map(|m| (m[0].as_u64().unwrap(), &m[1]))
        .collect()
}

/// A command as its events tell it: start, end (its outcome's time, real, not drawn), outcome.
struct Run {
    sent: Value,
    started: Option<u64>,
    sent_at: u64,
    end: Option<(u64, &'static str, Value)>,
}

/// Compares what the reader read (`read`) with `log` and `manifest`, channel by channel.
pub fn assert_mcap_reads_back(
    log: &[Value],
    log_text: &str,
    manifest: &Value,
    annotations: &[Value],
    read: &Value,
) {
    let zero = zero_ns(manifest);
    let ns = |us: u64| zero + us * 1000;
    assert_eq!(read["compressions"], json!(["lz4"]));

    // Every line, as it is, on /docent/log.
    let lines: Vec<&str> = log_text.lines().collect();
    let read_log = messages(read, "/docent/log", "foxglove.Log");
    assert_eq!(read_log.len(), lines.len(), "one Log per line");
    for ((t, m), (e, line)) in read_log.iter().zip(log.iter().zip(&lines)) {
        assert_eq!(*t, ns(at(e)), "{line}");
        assert_eq!(m["message"], *line);
        assert_eq!(m["name"], e["type"]);
        let level = match e["type"].as_str().unwrap() {
            "pose" => 1,
            "command.failed" => 4,
            "command.cancelled" | "trigger.refused" | "stop" => 3,
            _ => 2,
        };
        assert_eq!(m["level"], level, "{line}");
    }

    // The poses, as foxglove.PoseInFrame in the map.
    let poses: Vec<&Value> = log.iter().filter(|e| e["type"] == "pose").collect();
    let read_poses = messages(read, "/docent/pose", "foxglove.PoseInFrame");
    assert_eq!(read_poses.len(), poses.len());
    for ((t, m), e) in read_poses.iter().zip(&poses) {
        assert_eq!(*t, ns(at(e)));
        assert_eq!(m["frame_id"], "map");
        let p = &m["pose"]["position"];
        assert_eq!((&p["x"], &p["y"], &p["z"]), (&e["x"], &e["y"], &json!(0.0)));
        let q = &m["pose"]["orientation"];
        let yaw = 2.0 * q["z"].as_f64().unwrap().atan2(q["w"].as_f64().unwrap());
        let heading = e["heading"].as_f64().unwrap().to_radians();
        let turn = (yaw - heading).rem_euclid(std::f64::consts::TAU);
        assert!(turn.min(std::f64::consts::TAU - turn) < 1e-9, "{q} {e}");
    }

    // Speech and the other commands, from their start to their outcome.
    let mut runs: BTreeMap<u64, Run> = BTreeMap::new();
    let mut acts = BTreeMap::new();
    for e in log {
        let id = e["command"].as_u64().unwrap_or(0);
        let outcome = match e["type"].as_str().unwrap() {
            "act.triggered" => {
                acts.insert(e["trigger"].as_u64().unwrap(), e.clone());
                continue;
            }
            "command.sent" => {
                let run = Run {
                    sent: e.clone(),
                    started: None,
                    sent_at: at(e),
                    end: None,
                };
                runs.insert(id, run);
                continue;
            }
            "command.started" => {
                runs.get_mut(&id).unwrap().started = Some(at(e));
                continue;
            }
            "command.done" => "done",
            "command.failed" => "failed",
            "command.cancelled" => "cancelled",
            _ => continue,
        };
        runs.get_mut(&id).unwrap().end = Some((at(e), outcome, e["reason"].clone()));
    }
    let (mut speech, mut commands) = (Vec::new(), Vec::new());
    for run in runs.values() {
        let (end, outcome, reason) = run.end.clone().expect("every command ended");
        let e = &run.sent;
        match (e["verb"].as_str().unwrap(), run.started) {
            ("SAY", Some(start)) => {
                let act = &acts[&e["trigger"].as_u64().unwrap()];
                let own = act["text"] == e["arg"];
                let message = json!({
                    "start_us": start, "end_us": end, "text": e["arg"], "act": e["label"],
                    "source": e["source"],
                    "variant": if own { act["variant"].clone() } else { Value::Null },
                    "alternative": if own { act["alternative"].clone() } else { Value::Null },
                    "outcome": outcome, "reason": reason,
                });
                speech.push((ns(start), message));
            }
            (verb, started) => {
                let start = started.unwrap_or(run.sent_at);
                let message = json!({
                    "start_us": start, "end_us": end, "verb": verb, "arg": e["arg"],
                    "outcome": outcome, "reason": reason,
                });
                commands.push((ns(start), message));
            }
        }
    }
    assert_channel(read, "/docent/speech", "docent.Utterance", speech);
    assert_channel(read, "/docent/commands", "docent.Command", commands);

    // Pages, touches and marks as the other exports have them (real ends: pages are never
    // drawn longer), and what the projector showed.
    let want = expected(log);
    let pages = (want.pages.iter())
        .map(|(s, e, p)| (ns(*s), json!({"start_us": s, "end_us": e, "page": p})))
        .collect();
    assert_channel(read, "/docent/page", "docent.Page", pages);
    let touches = (want.touches.iter())
        .map(|(t, v)| {
            let (kind, act, page) = match v.strip_prefix("page: ") {
                Some(page) => ("page", Value::Null, json!(page)),
                None => ("act", json!(v), Value::Null),
            };
            let touch = json!({"at_us": t, "kind": kind, "act": act, "code": null, "page": page});
            (ns(*t), touch)
        })
        .collect();
    assert_channel(read, "/docent/touches", "docent.Touch", touches);
    let marks = (want.marks.iter())
        .map(|(t, v)| {
            let (kind, value) = v.split_once(": ").unwrap();
            (ns(*t), json!({"at_us": t, "kind": kind, "value": value}))
        })
        .collect();
    assert_channel(read, "/docent/marks", "docent.Mark", marks);
    let mut projections: Vec<(u64, Value)> = Vec::new();
    for e in log.iter().filter(|e| e["type"] == "display.changed") {
        let shown = json!({"at_us": at(e), "projector": e["projector"],
                           "highlight": e["highlight"], "projector_state": e["projector_state"]});
        let same = |last: &(u64, Value)| {
            ["projector", "highlight", "projector_state"]
                .iter()
                .all(|k| last.1[k] == shown[k])
        };
        if !projections.last().is_some_and(same) {
            projections.push((ns(at(e)), shown));
        }
    }
    assert_channel(read, "/docent/projection", "docent.Projection", projections);

    // The live annotations (the last line of each id, unless it deletes it), by start.
    let mut latest: std::collections::BTreeMap<&str, &Value> = Default::default();
    for line in annotations {
        latest.insert(line["id"].as_str().unwrap(), line);
    }
    let mut live: Vec<&Value> = (latest.into_values())
        .filter(|l| l["deleted"] != json!(true))
        .collect();
    let key = |l: &Value| {
        (
            l["start_us"].as_u64(),
            l["tier"].clone().to_string(),
            l["id"].to_string(),
        )
    };
    live.sort_by_key(|l| key(l));
    let coded = (live.iter())
        .map(|l| {
            let message = json!({"id": l["id"], "tier": l["tier"], "code": l["code"],
                "start_us": l["start_us"], "end_us": l["end_us"], "annotator": l["annotator"]});
            (ns(l["start_us"].as_u64().unwrap()), message)
        })
        .collect();
    assert_channel(read, "/docent/annotations", "docent.Annotation", coded);

    // The manifest, every field, with the clock's zero.
    let session = &read["metadata"]["docent.session"];
    assert_eq!(session.as_array().unwrap().len(), 1);
    let session = &session[0];
    assert_eq!(session["session_clock_zero_ns"], zero.to_string());
    assert_eq!(session["session"], manifest["session"]);
    assert_eq!(session["started.time"], manifest["started"]["time"]);
    assert_eq!(session["consent"], manifest["consent"]);
    assert_eq!(session["ended.reason"], manifest["ended"]["reason"]);
    assert_eq!(
        read["attachments"],
        json!([]),
        "media are linked, not embedded"
    );
}

/// A typed channel read, against (log time, message) worked out from the log.
fn assert_channel(read: &Value, topic: &str, schema: &str, mut want: Vec<(u64, Value)>) {
    want.sort_by_key(|(t, _)| *t);
    let got: Vec<(u64, Value)> = (messages(read, topic, schema).into_iter())
        .map(|(t, m)| (t, m.clone()))
        .collect();
    assert_eq!(got, want, "{topic}");
}
