//! A generated visitor session for the export benchmark (`bench/export.rs`) and the export
//! test of a long session (`tests/corpus_export.rs`): a session folder (`events.jsonl` and
//! `session.json`) as Docent writes one, of any length, with what a busy hour at a kiosk robot
//! holds: an utterance every 10 s (4.5 s long, half of them a visitor's tap), a page shown with
//! every third, a site verb running 2 s with every fifth, a `WAIT` beside every fourth (so
//! commands overlap), a page the visitor follows every 90 s, an operator's situation mark
//! every 5 minutes, and the robot's pose 5 times a second throughout.

use std::io::Write;
use std::path::Path;

use docent::corpus::manifest::{MANIFEST_FORMAT, SessionManifest, SessionMark};
use serde_json::{Value, json};

/// The session's name (its folder's).
pub const NAME: &str = "2026-11-24T10-00-00Z";

/// Writes a session of `seconds` into `dir` (created), its manifest naming `bundle`; returns
/// the number of lines.
pub fn write_session(dir: &Path, seconds: u64, bundle: Option<&str>) -> std::io::Result<usize> {
    std::fs::create_dir_all(dir)?;
    let mut events: Vec<(u64, Value)> = Vec::new();
    let mut id = 0u64;
    let mut next = || {
        id += 1;
        id
    };
    events.push((
        0,
        json!({"type": "session.started", "session": 1, "source": "operator", "client": 1, "consent": "recorded", "page": "index.html", "projector": null}),
    ));
    events.push((400, json!({"type": "visitor.group", "session": 1, "group": "group", "context": "TextGroup", "source": "operator", "client": 1})));
    for n in 0..seconds / 10 {
        let at = n * 10_000_000 + 1_000;
        let kiosk = n % 2 == 0;
        let label = format!("ACT_{}", n % 40);
        let text = format!(
            "This is explanation number {n}: the machine in front of you was built in {}, \
             and it \"remembers\" with magnetic cores.",
            1950 + n % 30
        );
        let trigger = next();
        let source = if kiosk { "kiosk" } else { "operator" };
        let act = json!({"trigger": trigger, "source": source, "client": 2, "label": label, "at": "acts.yaml:1"});
        let mut triggered = act.clone();
        let fields = json!({"type": "act.triggered", "context": "TextGroup", "variant": "TextGroup", "alternative": n % 3, "text": text, "interrupt": false});
        merge(&mut triggered, &fields);
        if kiosk {
            let element = format!("button[data-act={label}] \"{label}\"");
            events.push((at, json!({"type": "touch", "client": 2, "page": "index.html", "element": element, "act": label})));
        }
        events.push((at, triggered));
        let mut command = |verb: &str, arg: Option<&str>, start: u64, end: u64| {
            let id = next();
            let mut events = Vec::new();
            for (kind, t) in [("sent", start - 50), ("started", start), ("done", end)] {
                let mut e = act.clone();
                let fields =
                    json!({"type": format!("command.{kind}"), "command": id, "verb": verb});
                merge(&mut e, &fields);
                if kind == "sent" {
                    merge(&mut e, &json!({"arg": arg, "args": {}, "adapter": "log"}));
                }
                events.push((t, e));
            }
            events
        };
        events.extend(command("SAY", Some(&text), at + 300, at + 4_500_000));
        if n % 3 == 0 {
            let page = format!("room-{}.html", n % 12);
            events.extend(command("DISPLAY_PAGE", Some(&page), at + 400, at + 60_000));
            events.push((at + 500, json!({"type": "display.changed", "page": page, "projector": null, "highlight": null, "projector_state": "black"})));
        }
        if n % 5 == 0 {
            events.extend(command("LIGHTS", Some("dim"), at + 600, at + 2_000_600));
        }
        if n % 4 == 0 {
            events.extend(command("WAIT", None, at + 700, at + 4_500_100));
        }
    }
    for n in 0..seconds / 90 {
        let at = n * 90_000_000 + 7_000_000;
        let page = format!("detail-{}.html", n % 7);
        let element = format!("a[href={page}] \"More\"");
        events.push((
            at,
            json!({"type": "touch", "client": 2, "page": null, "element": element, "link": page}),
        ));
        events.push((at, json!({"type": "display.changed", "page": page, "projector": null, "highlight": null, "projector_state": "black"})));
    }
    for n in 1..seconds / 300 {
        let situation = ["question", "laughter", "leaving"][n as usize % 3];
        events.push((n * 300_000_000 + 8_000_000, json!({"type": "situation.marked", "session": 1, "situation": situation, "source": "operator", "client": 1})));
    }
    for n in 0..seconds * 5 {
        let (x, y) = ((n % 200) as f64 * 0.05, (n % 120) as f64 * 0.05);
        events.push((
            n * 200_000 + 50,
            json!({"type": "pose", "x": x, "y": y, "heading": 90.0, "moving": true}),
        ));
    }
    let end = seconds * 1_000_000;
    events.push((end, json!({"type": "session.ended", "session": 1, "source": "operator", "client": 1, "reason": "marked"})));
    events.sort_by_key(|(at, _)| *at);

    let mut log = std::io::BufWriter::new(std::fs::File::create(dir.join("events.jsonl"))?);
    let count = events.len();
    for (seq, (at, event)) in events.into_iter().enumerate() {
        let mut line = json!({"v": 4, "seq": seq + 1, "time": "2026-11-24T10:00:00.000Z", "mono_us": at + 1_000_000, "session_us": at});
        merge(&mut line, &event);
        serde_json::to_writer(&mut log, &line)?;
        log.write_all(b"\n")?;
    }
    log.flush()?;
    let mark = |seq, time: &str, mono_us, reason: Option<&str>| SessionMark {
        seq,
        time: time.to_owned(),
        mono_us,
        source: "operator".to_owned(),
        reason: reason.map(str::to_owned),
    };
    let manifest = SessionManifest {
        format: MANIFEST_FORMAT,
        session: NAME.to_owned(),
        number: 1,
        docent: "0.1.0".to_owned(),
        bundle: bundle.map(str::to_owned),
        bundle_hash: None,
        started: mark(1, "2026-11-24T10:00:00.000Z", 1_000_000, None),
        ended: Some(mark(
            count as u64,
            "2026-11-24T11:00:00.000Z",
            end + 1_000_000,
            Some("marked"),
        )),
        group: Some("group".to_owned()),
        context: Some("TextGroup".to_owned()),
        consent: "recorded".to_owned(),
        media: Vec::new(),
    };
    manifest.write_to(dir)?;
    Ok(count)
}

/// Adds `extra`'s fields to the object `into`.
fn merge(into: &mut Value, extra: &Value) {
    if let (Some(into), Some(extra)) = (into.as_object_mut(), extra.as_object()) {
        for (k, v) in extra {
            into.insert(k.clone(), v.clone());
        }
    }
}
