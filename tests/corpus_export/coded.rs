//! What a session's `annotations.jsonl` says the readers should find in the annotation tiers,
//! worked out from its lines as `docs/CORPUS.md` ("Replay and annotation") describes them:
//! the latest line per `id` wins, `deleted` removes; per codebook tier its intervals
//! (`TIER`, `TIER-2` for overlaps) and its points (`TIER-points`), each valued with its code,
//! the code named in the tier's vocabulary by `CVE_REF` in the EAF.

use std::collections::BTreeMap;

use serde_json::{Value, json};

use super::expected::{
    NamedTier, Span, assert_eaf_tier, assert_praat_intervals, assert_praat_points, point_spans, s,
    spread,
};

/// The annotation tiers expected, in file order: (codebook tier, its interval tiers, its
/// point tiers as 1 ms spans).
pub struct Coded {
    pub tiers: Vec<(String, Vec<NamedTier>, Vec<NamedTier>)>,
    /// Every live annotation: (start, end, code, tier), by start.
    pub rows: Vec<(u64, u64, String, String)>,
}

/// From the codebook's tier names (in order) and the lines of `annotations.jsonl`.
pub fn coded(codebook: &[&str], lines: &[Value]) -> Coded {
    let mut latest: BTreeMap<String, &Value> = BTreeMap::new();
    for line in lines {
        latest.insert(line["id"].as_str().unwrap().to_owned(), line);
    }
    let live: Vec<&Value> = (latest.into_values())
        .filter(|l| l["deleted"] != json!(true))
        .collect();
    let mut names: Vec<String> = codebook.iter().map(|t| (*t).to_owned()).collect();
    for l in &live {
        let tier = l["tier"].as_str().unwrap().to_owned();
        if !names.contains(&tier) {
            names.push(tier);
        }
    }
    let field = |l: &Value, k: &str| l[k].as_u64().unwrap();
    let text = |l: &Value, k: &str| l[k].as_str().unwrap().to_owned();
    let tiers = (names.into_iter())
        .map(|name| {
            let mine: Vec<&&Value> = live.iter().filter(|l| l["tier"] == name).collect();
            let intervals: Vec<Span> = (mine.iter())
                .filter(|l| field(l, "start_us") != field(l, "end_us"))
                .map(|l| {
                    let start = field(l, "start_us");
                    (start, field(l, "end_us").max(start + 1000), text(l, "code"))
                })
                .collect();
            let points: Vec<(u64, String)> = (mine.iter())
                .filter(|l| field(l, "start_us") == field(l, "end_us"))
                .map(|l| (field(l, "start_us"), text(l, "code")))
                .collect();
            let points = spread(&format!("{name}-points"), &point_spans(&points));
            (name.clone(), spread(&name, &intervals), points)
        })
        .collect();
    let mut rows: Vec<(u64, u64, String, String)> = (live.iter())
        .map(|l| {
            let (start, end) = (field(l, "start_us"), field(l, "end_us"));
            (start, end, text(l, "code"), text(l, "tier"))
        })
        .collect();
    rows.sort_by_key(|r| r.0);
    Coded { tiers, rows }
}

impl Coded {
    /// Their names in file order.
    pub fn order(&self) -> Vec<String> {
        (self.tiers.iter())
            .flat_map(|(_, intervals, points)| intervals.iter().chain(points))
            .map(|(n, _)| n.clone())
            .collect()
    }

    /// Every annotation tier as ELAN (pympi, with the EAF's vocabularies) and Praat read it.
    pub fn assert_read(&self, read: &Value) {
        let eaf = &read["eaf"];
        let praat = &read["textgrid_praat"];
        for (tier, intervals, points) in &self.tiers {
            for (name, spans) in intervals.iter().chain(points) {
                assert_eaf_tier(eaf, name, spans);
                let codes: Vec<Value> = spans.iter().map(|(_, _, v)| json!(v)).collect();
                assert_eq!(
                    read["eaf_coded"][name],
                    json!(codes),
                    "EAF tier {name}: each annotation's CVE_REF names its code in the \
                     vocabulary of {tier}"
                );
            }
            for (name, spans) in intervals {
                assert_praat_intervals(praat, name, spans);
            }
            for (name, spans) in points {
                let points: Vec<(u64, String)> =
                    spans.iter().map(|(t, _, v)| (*t, v.clone())).collect();
                assert_praat_points(praat, name, &points);
            }
        }
    }

    /// The CSV rows the annotations are: (start, row).
    pub fn csv_rows(&self) -> Vec<(u64, Value)> {
        (self.rows.iter())
            .map(|(start, end, code, tier)| {
                let cell = |text: &str| docent::content::spreadsheet::neutralise(text).into_owned();
                let row = json!([
                    s(*start),
                    s(*end),
                    "annotation",
                    "",
                    "",
                    "",
                    cell(code),
                    cell(tier)
                ]);
                (*start, row)
            })
            .collect()
    }
}
