//! What the session's log says the readers should find, worked out from its lines as
//! `docs/CORPUS.md` ("Exports") describes the tiers, independently of the exporter's model;
//! and the comparisons with what each reader read.

use std::collections::BTreeMap;

use serde_json::{Value, json};

use super::coded::Coded;

/// An interval: start and end in µs, and its value.
pub type Span = (u64, u64, String);

/// A tier's name and intervals.
pub type NamedTier = (String, Vec<Span>);

pub fn at(e: &Value) -> u64 {
    e["session_us"].as_u64().unwrap()
}

/// A `SAY` as the log tells it.
pub struct Said {
    pub start: u64,
    /// Its end, drawn at least 1 ms after its start.
    pub end: u64,
    pub text: String,
    pub label: String,
    /// Who triggered its act, and the act's variant and alternative.
    pub source: Value,
    pub variant: Value,
    pub alternative: Value,
}

/// What the log says each tool should read: (start µs, end µs drawn, value) per tier kind.
pub struct Expected {
    /// Each begun `SAY`.
    pub speech: Vec<Said>,
    /// Each other command: start, end, `VERB arg`.
    pub commands: Vec<(u64, u64, String)>,
    pub pages: Vec<(u64, u64, String)>,
    pub touches: Vec<(u64, String)>,
    pub marks: Vec<(u64, String)>,
    pub end_us: u64,
}

/// Worked out from the log's lines as the docs describe the tiers (an interval shorter than
/// 1 ms drawn 1 ms long).
pub fn expected(log: &[Value]) -> Expected {
    let drawn = |start: u64, end: u64| end.max(start + 1000);
    let mut commands: BTreeMap<u64, (Option<u64>, Option<u64>, String, Value)> = BTreeMap::new();
    let mut acts = BTreeMap::new();
    let (mut pages, mut touches, mut marks) = (Vec::new(), Vec::new(), Vec::new());
    for e in log {
        let id = e["command"].as_u64().unwrap_or(0);
        match e["type"].as_str().unwrap() {
            "session.started" => {
                if let Some(page) = e["page"].as_str() {
                    pages.push((at(e), page.to_owned()));
                }
            }
            "act.triggered" => {
                acts.insert(e["trigger"].as_u64().unwrap(), e.clone());
            }
            "touch" => match (e["act"].as_str(), e["link"].as_str()) {
                (Some(act), _) => touches.push((at(e), act.to_owned())),
                (None, Some(link)) => touches.push((at(e), format!("page: {link}"))),
                (None, None) => {}
            },
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
                    pages.push((at(e), page));
                }
            }
            "situation.marked" => {
                let situation = e["situation"].as_str().unwrap();
                marks.push((at(e), format!("situation: {situation}")));
            }
            "note.written" => {
                let text = e["text"].as_str().unwrap();
                marks.push((at(e), format!("note: {text}")));
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
            speech.push(Said {
                start,
                end: drawn(start, end),
                text: value,
                label,
                source: sent["source"].clone(),
                variant: act["variant"].clone(),
                alternative: act["alternative"].clone(),
            });
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

pub fn ms(us: u64) -> u64 {
    us / 1000
}

pub fn s(us: u64) -> f64 {
    us as f64 / 1e6
}

pub fn close(a: &Value, b: f64) -> bool {
    (a.as_f64().unwrap() - b).abs() < 1e-9
}

/// The documented rule for overlaps: each interval, by start, goes to the first tier of its
/// kind (`base`, `base-2`, ...) whose intervals have all ended by then.
pub fn spread(base: &str, spans: &[Span]) -> Vec<NamedTier> {
    let mut sorted = spans.to_vec();
    sorted.sort();
    let mut tiers: Vec<NamedTier> = vec![(base.to_owned(), Vec::new())];
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
pub fn point_spans(points: &[(u64, String)]) -> Vec<(u64, u64, String)> {
    (points.iter())
        .map(|(t, v)| (*t, t + 1000, v.clone()))
        .collect()
}

/// An EAF tier as pympi read it, against spans in µs.
pub fn assert_eaf_tier(eaf: &Value, name: &str, want: &[(u64, u64, String)]) {
    let want: Vec<Value> = (want.iter())
        .map(|(start, end, v)| json!([ms(*start), ms(*end), v]))
        .collect();
    assert_eq!(eaf["tiers"][name], json!(want), "EAF tier {name}");
}

/// A TextGrid interval tier as Praat read it (labelled intervals), against spans in µs.
pub fn assert_praat_intervals(grid: &Value, name: &str, want: &[(u64, u64, String)]) {
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
pub fn assert_praat_points(grid: &Value, name: &str, want: &[(u64, String)]) {
    let tier = &grid["tiers"][name];
    assert_eq!(tier["class"], "TextTier", "{name}");
    let read = tier["entries"].as_array().unwrap();
    assert_eq!(read.len(), want.len(), "TextGrid tier {name}: {read:?}");
    for (r, (t, value)) in read.iter().zip(want) {
        assert!(close(&r[0], s(*t)), "{name}: {r} {t}");
        assert_eq!(r[1], json!(value), "TextGrid tier {name}");
    }
}

/// Compares what every reader read (`read`, from `check_exports.py`) with what `log` and the
/// annotations (`coded`) say, tier by tier, time by time, text by text; returns what the log
/// says.
pub fn assert_reads_back(log: &[Value], coded: &Coded, read: &Value) -> Expected {
    assert_eq!(
        read["problems"],
        json!([]),
        "what the readers found or let pass"
    );
    let want = expected(log);
    let commands = spread("commands", &want.commands);
    let speech: Vec<Span> = (want.speech.iter())
        .map(|u| (u.start, u.end, u.text.clone()))
        .collect();
    let acts: Vec<Span> = (want.speech.iter())
        .map(|u| (u.start, u.end, u.label.clone()))
        .collect();
    let pages = [("pages".to_owned(), want.pages.clone())];
    let touches = spread("touches", &point_spans(&want.touches));
    let marks = spread("marks", &point_spans(&want.marks));
    let mut order = vec!["speech".to_owned(), "act".to_owned()];
    order.extend(commands.iter().map(|(n, _)| n.clone()));
    order.push("pages".to_owned());
    order.extend(touches.iter().chain(&marks).map(|(n, _)| n.clone()));
    order.extend(coded.order());

    // ELAN, through pympi.
    let eaf = &read["eaf"];
    assert_eq!(eaf["order"], json!(order));
    assert_eq!(eaf["parents"], json!({"act": "speech"}));
    assert_eaf_tier(eaf, "speech", &speech);
    let act_tier: Vec<Value> = (want.speech.iter())
        .map(|u| json!([ms(u.start), ms(u.end), u.label, u.text]))
        .collect();
    assert_eq!(
        eaf["ref_tiers"]["act"],
        json!(act_tier),
        "labels beside their parents' texts"
    );
    for (name, spans) in commands.iter().chain(&pages).chain(&touches).chain(&marks) {
        assert_eaf_tier(eaf, name, spans);
    }

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

    // The researchers' annotations, in both.
    coded.assert_read(read);

    // The spreadsheet, through Python's csv module: a cell that starts like a formula has a
    // `'` before it (`docent::content::spreadsheet`).
    let cell = |text: &str| docent::content::spreadsheet::neutralise(text).into_owned();
    let csv = &read["csv"];
    let header = "start_s end_s source act variant alternative text kind";
    assert_eq!(csv["header"], json!(header.split(' ').collect::<Vec<_>>()));
    let mut rows: Vec<(u64, Value)> = (want.speech.iter())
        .map(|u| {
            let alternative = match &u.alternative {
                Value::Null => String::new(),
                n => n.to_string(),
            };
            let variant = u.variant.as_str().unwrap_or_default();
            let row = json!([
                s(u.start),
                s(u.end),
                u.source,
                cell(&u.label),
                variant,
                alternative,
                cell(&u.text),
                "utterance"
            ]);
            (u.start, row)
        })
        .collect();
    for (t, value) in &want.touches {
        let (act, text) = match value.strip_prefix("page: ") {
            Some(_) => ("", value.as_str()),
            None => (value.as_str(), ""),
        };
        rows.push((
            *t,
            json!([
                s(*t),
                s(*t),
                "kiosk",
                cell(act),
                "",
                "",
                cell(text),
                "touch"
            ]),
        ));
    }
    rows.extend(coded.csv_rows());
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
    want
}
