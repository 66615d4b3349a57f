//! The bench's record of a soak, in `DOCENT_SOAK_OUT`: `soak-latest.csv` (the server sampled
//! every second), `soak-latest.json` (the plan, each tenth's figures, the verdict) and
//! `soak-latest.svg` (RSS, descriptors and latency over the run, drawn here: no plotting
//! tool to install); and the paragraph the test prints.

use std::fmt::Write as _;
use std::path::Path;

use serde_json::json;

use crate::ledger::Role;
use crate::plan::Plan;
use crate::run::Run;
use crate::verdict::{FACTOR, GROWTH_PCT, SLACK_MS, Verdict};

/// Writes the three files into `dir`.
pub fn write(dir: &Path, plan: &Plan, run: &Run, verdict: &Verdict) {
    std::fs::create_dir_all(dir).expect("the results folder");
    let mut csv = String::from("at_s,rss_kb,fds,kiosks_connected,acked\n");
    for s in &run.samples {
        let _ = writeln!(
            csv,
            "{:.1},{},{},{},{}",
            s.at, s.rss_kb, s.fds, s.kiosks, s.acked
        );
    }
    std::fs::write(dir.join("soak-latest.csv"), csv).expect("soak-latest.csv");
    let f = &verdict.figures;
    let windows: Vec<_> = (f.windows.iter())
        .map(|w| {
            let by_role = |values: &[Option<f64>; 4]| {
                let mut o = serde_json::Map::new();
                for (i, name) in Role::ALL
                    .iter()
                    .map(|r| r.name())
                    .chain(["all"])
                    .enumerate()
                {
                    o.insert(name.into(), json!(values[i]));
                }
                o
            };
            json!({"from_s": w.from, "rss_max_kb": w.rss_max_kb, "fds_max": w.fds_max,
                "answers": w.answers, "p50_ms": by_role(&w.p50), "p99_ms": by_role(&w.p99)})
        })
        .collect();
    let report = json!({
        "docent": plan.docent, "seconds": plan.length.as_secs(), "kiosks": plan.kiosks,
        "wall_s": run.wall.as_secs_f64(), "storms": run.storms, "reloads": run.reloads,
        "kiosk_connections": f.connections, "sessions": f.sessions, "recordings": f.recordings,
        "chunks": f.chunks, "acked": f.acked, "act_triggered": f.triggered_in_corpus,
        "events": f.events, "refused": f.refused, "unanswered_at_drop": f.unanswered_at_drop,
        "warmup_s": plan.warmup().as_secs(), "growth_span_s": plan.growth_span().as_secs(),
        "rss_kb_after_warmup_and_at_end": f.rss_kb, "fds_after_warmup_and_at_end": f.fds,
        "rss_growth_pct": f.rss_growth_pct, "fds_growth_pct": f.fds_growth_pct,
        "p99_first_ms": f.p99_first_ms, "p99_last_ms": f.p99_last_ms,
        "p99_slices_after_warmup_ms": f.p99_slices_ms,
        "rules": {"growth_pct_below": GROWTH_PCT, "p99_median_of_last_five_slices_at_most": format!("{FACTOR} x that of the first five + {SLACK_MS} ms")},
        "server_warning_count": f.server_warning_count, "server_warnings": f.server_warnings,
        "windows": windows, "failures": verdict.failures,
    });
    let text = serde_json::to_string_pretty(&report).expect("JSON");
    std::fs::write(dir.join("soak-latest.json"), text + "\n").expect("soak-latest.json");
    std::fs::write(dir.join("soak-latest.svg"), svg(plan, run, verdict)).expect("soak-latest.svg");
}

const WIDTH: f64 = 640.0;
const PANEL: f64 = 120.0;
const LEFT: f64 = 70.0;

/// Three panels over the run's seconds: RSS (MB), open descriptors, p50/p99 per tenth (ms);
/// a dashed line marks the end of the warm-up.
fn svg(plan: &Plan, run: &Run, verdict: &Verdict) -> String {
    let length = run.samples.last().map_or(1.0, |s| s.at.max(1.0));
    let rss: Vec<(f64, f64)> = run
        .samples
        .iter()
        .map(|s| (s.at, s.rss_kb as f64 / 1024.0))
        .collect();
    let fds: Vec<(f64, f64)> = run.samples.iter().map(|s| (s.at, s.fds as f64)).collect();
    let windows = &verdict.figures.windows;
    let mid = |w: &crate::verdict::Window| w.from + length / 20.0;
    let p99: Vec<(f64, f64)> = windows
        .iter()
        .filter_map(|w| Some((mid(w), w.p99[3]?)))
        .collect();
    let p50: Vec<(f64, f64)> = windows
        .iter()
        .filter_map(|w| Some((mid(w), w.p50[3]?)))
        .collect();
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{}\" \
         font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
        PANEL * 3.0 + 40.0
    );
    let panels = [
        ("server RSS (MB)", vec![(&rss, "#1f77b4")]),
        ("open file descriptors", vec![(&fds, "#2ca02c")]),
        (
            "trigger → answer, ms (p99 red, p50 grey), per tenth",
            vec![(&p99, "#d62728"), (&p50, "#7f7f7f")],
        ),
    ];
    for (i, (title, series)) in panels.iter().enumerate() {
        let top = 10.0 + i as f64 * PANEL;
        let max = series
            .iter()
            .flat_map(|(s, _)| s.iter().map(|p| p.1))
            .fold(0.0, f64::max)
            * 1.1;
        let max = if max > 0.0 { max } else { 1.0 };
        let (x0, x1, y0, y1) = (LEFT, WIDTH - 10.0, top + PANEL - 25.0, top + 15.0);
        let _ = writeln!(
            out,
            "<text x=\"{LEFT}\" y=\"{}\">{title}</text>",
            top + 10.0
        );
        let warm = x0 + plan.warmup().as_secs_f64() / length * (x1 - x0);
        let _ = writeln!(
            out,
            "<line x1=\"{warm:.1}\" y1=\"{y0}\" x2=\"{warm:.1}\" y2=\"{y1}\" \
             stroke=\"#999\" stroke-dasharray=\"4 3\"/>"
        );
        let _ = writeln!(
            out,
            "<line x1=\"{x0}\" y1=\"{y0}\" x2=\"{x1}\" y2=\"{y0}\" stroke=\"black\"/>"
        );
        let _ = writeln!(
            out,
            "<line x1=\"{x0}\" y1=\"{y0}\" x2=\"{x0}\" y2=\"{y1}\" stroke=\"black\"/>"
        );
        let _ = writeln!(
            out,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{max:.1}</text>",
            x0 - 4.0,
            y1 + 4.0
        );
        let _ = writeln!(
            out,
            "<text x=\"{}\" y=\"{y0}\" text-anchor=\"end\">0</text>",
            x0 - 4.0
        );
        let _ = writeln!(
            out,
            "<text x=\"{x1}\" y=\"{}\" text-anchor=\"end\">{length:.0} s</text>",
            y0 + 14.0
        );
        for (points, colour) in series {
            let path: Vec<String> = (points.iter())
                .map(|(t, v)| {
                    let x = x0 + t / length * (x1 - x0);
                    let y = y0 - v / max * (y0 - y1);
                    format!("{x:.1},{y:.1}")
                })
                .collect();
            let _ = writeln!(
                out,
                "<polyline fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\" points=\"{}\"/>",
                path.join(" ")
            );
        }
    }
    out.push_str("</svg>\n");
    out
}

/// One paragraph for the test's output.
pub fn summary(run: &Run, v: &Verdict) -> String {
    let f = &v.figures;
    format!(
        "soak: {:.0} s wall, {} kiosk connections, {} storms, {} reloads, {} sessions, \
         {} recordings ({} chunks), {} triggers acknowledged ({} act.triggered in {} events), \
         refused {:?}, {} unanswered when a storm dropped them; RSS {:+.1} % ({} → {} kB), \
         fds {:+.1} % ({} → {}), p99 {:.1} → {:.1} ms; {} warnings in the server log, \
         the first: {:#?}",
        run.wall.as_secs_f64(),
        f.connections,
        run.storms,
        run.reloads,
        f.sessions,
        f.recordings,
        f.chunks,
        f.acked,
        f.triggered_in_corpus,
        f.events,
        f.refused,
        f.unanswered_at_drop,
        f.rss_growth_pct,
        f.rss_kb.0,
        f.rss_kb.1,
        f.fds_growth_pct,
        f.fds.0,
        f.fds.1,
        f.p99_first_ms,
        f.p99_last_ms,
        f.server_warning_count,
        &f.server_warnings[..f.server_warnings.len().min(5)],
    )
}
