//! Output: one JSON object per scenario (one line each), and a table for people.

use serde_json::{Value, json};

use crate::idle::IdleReport;
use crate::load::{Measured, Plan};
use crate::tally::quantile_us;

/// One scenario's result.
pub enum Outcome {
    /// `adapter`, `kiosk` or `max`.
    Load {
        name: &'static str,
        plan: Plan,
        measured: Box<Measured>,
    },
    /// `idle`.
    Idle { report: IdleReport },
}

fn round1(x: f64) -> f64 {
    (x * 10.0).round() / 10.0
}

impl Outcome {
    /// The scenario's figures as one JSON object.
    pub fn json(&self) -> Value {
        match self {
            Outcome::Load {
                name,
                plan,
                measured,
            } => load_json(name, plan, measured),
            Outcome::Idle { report } => json!({
                "scenario": "idle",
                "connections": report.connections,
                "connect_s": (report.connect_s * 100.0).round() / 100.0,
                "server_rss_before_kb": report.rss_before_kb,
                "server_rss_after_kb": report.rss_after_kb,
                "server_rss_per_connection_kb": report.per_connection_kb().map(round1),
                "server_idle_cpu_pct": report.idle_cpu_pct.map(round1),
            }),
        }
    }
}

fn load_json(name: &str, plan: &Plan, m: &Measured) -> Value {
    let s = &m.summary;
    let per_s = |n: u64, secs: f64| round1(n as f64 / secs);
    let cpu_us_per_command = m
        .usage
        .server_cpu_s
        .filter(|_| s.received > 0)
        .map(|cpu| round1(cpu * 1e6 / s.received as f64));
    json!({
        "scenario": name,
        "mode": if plan.rate.is_some() { "open" } else { "closed" },
        "senders": plan.senders,
        "subscribers": plan.subscribers,
        "subscriber_role": match plan.subscriber {
            crate::client::Role::Kiosk => "kiosk",
            _ => "adapter",
        },
        "rate_per_sender": plan.rate,
        "warmup_s": plan.warmup.as_secs_f64(),
        "duration_s": plan.duration.as_secs_f64(),
        "sent": s.sent,
        "expected": s.expected,
        "received": s.received,
        "lost": s.expected.saturating_sub(s.received),
        "lost_triggers": s.lost_triggers,
        "unexpected": s.unexpected,
        "errors": s.errors,
        "first_error": s.first_error,
        "p50_us": quantile_us(&s.latency_ns, 0.5),
        "p90_us": quantile_us(&s.latency_ns, 0.9),
        "p99_us": quantile_us(&s.latency_ns, 0.99),
        "p999_us": quantile_us(&s.latency_ns, 0.999),
        "max_us": quantile_us(&s.latency_ns, 1.0),
        "triggers_per_s": per_s(s.sent, plan.duration.as_secs_f64()),
        "commands_per_s": per_s(s.received, m.delivery_window_s),
        "send_lag_p99_us": quantile_us(&s.send_lag_ns, 0.99),
        "send_lag_max_us": quantile_us(&s.send_lag_ns, 1.0),
        "server_cpu_pct": m.usage.server_cpu_pct.map(round1),
        "server_cpu_us_per_command": cpu_us_per_command,
        "server_rss_peak_kb": m.usage.server_rss_peak_kb,
        "client_cpu_pct": m.usage.client_cpu_pct.map(round1),
        "host_steal_ms": m.usage.steal_ms.map(round1),
    })
}

/// A figure for the table: `-` when absent.
fn cell(v: &Value) -> String {
    match v {
        Value::Null => "-".to_owned(),
        Value::Number(n) => match n.as_f64() {
            Some(x) if x.fract() == 0.0 => format!("{x:.0}"),
            Some(x) => format!("{x:.1}"),
            None => n.to_string(),
        },
        other => other.to_string(),
    }
}

fn mib(kb: &Value) -> String {
    kb.as_f64()
        .map_or_else(|| "-".to_owned(), |kb| format!("{:.1}", kb / 1024.0))
}

/// The readable table of all scenarios run.
pub fn table(outcomes: &[Outcome]) -> String {
    let mut out = String::new();
    let header = [
        "scenario",
        "load",
        "p50 µs",
        "p99 µs",
        "max µs",
        "cmds/s",
        "lost",
        "errors",
        "CPU %",
        "CPU µs/cmd",
        "RSS MiB",
    ];
    let mut rows: Vec<Vec<String>> = vec![header.iter().map(|h| (*h).to_owned()).collect()];
    let mut notes = Vec::new();
    for o in outcomes {
        let j = o.json();
        match o {
            Outcome::Load { name, plan, .. } => {
                let who = match plan.subscriber {
                    crate::client::Role::Kiosk => "kiosk",
                    _ => "adapter",
                };
                let plural = if plan.subscribers == 1 { "" } else { "s" };
                let load = match plan.rate {
                    Some(rate) if plan.answers => format!(
                        "{}×{rate}/s, own answers ({} {who}{plural})",
                        plan.senders, plan.subscribers
                    ),
                    Some(rate) => format!(
                        "{}×{rate}/s → {} {who}{plural}",
                        plan.senders, plan.subscribers
                    ),
                    None => format!(
                        "{} closed-loop → {} {who}{plural}",
                        plan.senders, plan.subscribers
                    ),
                };
                let lost = format!("{} / {}", cell(&j["lost"]), cell(&j["expected"]));
                rows.push(vec![
                    (*name).to_owned(),
                    load,
                    cell(&j["p50_us"]),
                    cell(&j["p99_us"]),
                    cell(&j["max_us"]),
                    cell(&j["commands_per_s"]),
                    lost,
                    cell(&j["errors"]),
                    cell(&j["server_cpu_pct"]),
                    cell(&j["server_cpu_us_per_command"]),
                    mib(&j["server_rss_peak_kb"]),
                ]);
                if let Some(e) = j["first_error"].as_str() {
                    notes.push(format!("{name}: first error frame: {e}"));
                }
            }
            Outcome::Idle { report } => {
                let mut row = vec![
                    "idle".to_owned(),
                    format!("{} idle kiosks", report.connections),
                ];
                row.extend(std::iter::repeat_n("-".to_owned(), 6));
                row.push(cell(&j["server_idle_cpu_pct"]));
                row.push("-".to_owned());
                row.push(mib(&j["server_rss_after_kb"]));
                rows.push(row);
                notes.push(format!(
                    "idle: server RSS {} MiB before, {} MiB with {} connections: {} kB per connection",
                    mib(&j["server_rss_before_kb"]),
                    mib(&j["server_rss_after_kb"]),
                    report.connections,
                    cell(&j["server_rss_per_connection_kb"]),
                ));
            }
        }
    }
    let widths: Vec<usize> = (0..header.len())
        .map(|c| rows.iter().map(|r| r[c].chars().count()).max().unwrap_or(0))
        .collect();
    for row in &rows {
        let line: Vec<String> = row
            .iter()
            .zip(&widths)
            .enumerate()
            .map(|(c, (text, &w))| {
                let pad = w - text.chars().count();
                match c {
                    0 | 1 => format!("{text}{}", " ".repeat(pad)),
                    _ => format!("{}{text}", " ".repeat(pad)),
                }
            })
            .collect();
        out.push_str(line.join("  ").trim_end());
        out.push('\n');
    }
    for note in notes {
        out.push_str(&note);
        out.push('\n');
    }
    out
}
