//! Benchmark of `docent corpus export`'s library: how long exporting a one-hour visitor
//! session takes in each format, from reading its log to the file written. The session is
//! generated (`bench/export_session.rs`: about 26,000 lines, 18,000 of them poses) into a
//! temporary folder, its manifest naming the shipped `dialogs/museum-tour` so that the
//! vocabulary's bundle load is part of the time, as it is for a real session. Run with
//! `cargo run --release --example export-bench -- [--seconds N] [--runs N]`; figures in
//! `bench/README.md`.

#[path = "export_session.rs"]
mod export_session;

use std::time::{Duration, Instant};

use docent::corpus::export::{ExportFormat, SessionExport, export_session};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let arg = |name: &str, default: u64| {
        (args.iter().position(|a| a == name))
            .and_then(|i| args.get(i + 1))
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let (seconds, runs) = (arg("--seconds", 3600), arg("--runs", 7) as usize);
    let root = std::env::temp_dir().join(format!("docent-export-bench-{}", std::process::id()));
    let session = root.join("sessions").join(export_session::NAME);
    let bundle = concat!(env!("CARGO_MANIFEST_DIR"), "/dialogs/museum-tour");
    let lines = export_session::write_session(&session, seconds, Some(bundle))?;
    let log_bytes = std::fs::metadata(session.join("events.jsonl"))?.len();
    println!(
        "session of {seconds} s: {lines} lines, {:.1} MB of log; {runs} runs each, wall clock",
        log_bytes as f64 / 1e6
    );
    let ms = |d: Duration| d.as_secs_f64() * 1000.0;
    let summary = |mut times: Vec<Duration>| {
        times.sort();
        format!(
            "min {:7.1} ms  p50 {:7.1} ms  max {:7.1} ms",
            ms(times[0]),
            ms(times[times.len() / 2]),
            ms(times[times.len() - 1])
        )
    };
    let mut times = Vec::new();
    for _ in 0..runs {
        let started = Instant::now();
        let read = SessionExport::open(&session)?;
        times.push(started.elapsed());
        assert!(read.warnings().is_empty(), "{:?}", read.warnings());
    }
    println!("{:<22} {}", "read (log + bundle)", summary(times));
    let mut times = Vec::new();
    for _ in 0..runs {
        let started = Instant::now();
        let report = docent::content::load_bundle(std::path::Path::new(bundle));
        times.push(started.elapsed());
        assert!(report.bundle.is_some(), "{:?}", report.diagnostics.first());
    }
    println!("{:<22} {}", "  of which the bundle", summary(times));
    let out = root.join("exports");
    for format in ExportFormat::ALL {
        let mut times = Vec::new();
        let mut size = 0;
        for _ in 0..runs {
            let started = Instant::now();
            let exported = export_session(&session, format, &out)?;
            times.push(started.elapsed());
            size = std::fs::metadata(&exported.files[0])?.len();
        }
        let name = format!("export {format}");
        println!(
            "{name:<22} {}  {:6.2} MB",
            summary(times),
            size as f64 / 1e6
        );
    }
    std::fs::remove_dir_all(&root)?;
    Ok(())
}
