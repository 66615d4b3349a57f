//! Benchmark of `docent check` on a large generated bundle: how long `load_bundle` takes for
//! 10,000 acts (two alternatives, a context variant and two commands each, over 10 acts files)
//! and 1,000 pages (each offering acts, linking pages, showing a picture), as a museum with a
//! big info terminal would have. Run with
//! `cargo run --release --example check-bench -- [--acts N] [--pages N] [--runs N]`, or with
//! `--write DIR` to write the bundle only (to time `docent check DIR` as a whole).
//! The bundle is written to a temporary folder; the figures are wall-clock times of the whole
//! check, as `docent check` runs it (settings, acts files in parallel, commands, pages, media).

use std::fmt::Write as _;
use std::path::Path;
use std::time::{Duration, Instant};

use docent::content::load_bundle;

/// A 1x1 PNG, so that media checks read a real picture.
const PNG: &[u8] = &[
    0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A, 0x00, 0x00, 0x00, 0x0D, 0x49, 0x48, 0x44, 0x52,
    0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0x1F, 0x15, 0xC4,
    0x89, 0x00, 0x00, 0x00, 0x0D, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9C, 0x63, 0xF8, 0xCF, 0xC0, 0xF0,
    0x1F, 0x00, 0x05, 0x00, 0x01, 0xFF, 0x89, 0x99, 0x3D, 0x1D, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45,
    0x4E, 0x44, 0xAE, 0x42, 0x60, 0x82,
];

fn main() -> std::io::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let arg = |name: &str, default: usize| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let (acts, pages, runs) = (
        arg("--acts", 10_000),
        arg("--pages", 1_000),
        arg("--runs", 15),
    );
    // `--write DIR` only writes the bundle, to time the `docent check` command itself.
    if let Some(out) = args
        .iter()
        .position(|a| a == "--write")
        .and_then(|i| args.get(i + 1))
    {
        return write_bundle(Path::new(out), acts, pages);
    }
    let dir = std::env::temp_dir().join(format!("docent-check-bench-{}", std::process::id()));
    write_bundle(&dir, acts, pages)?;
    let mut times = Vec::with_capacity(runs);
    let mut problems = 0;
    for _ in 0..runs {
        let started = Instant::now();
        let report = load_bundle(&dir);
        times.push(started.elapsed());
        problems = report.diagnostics.len();
        assert!(
            report.bundle.is_some(),
            "the generated bundle must load: {:?}",
            report.diagnostics.first()
        );
    }
    std::fs::remove_dir_all(&dir)?;
    times.sort();
    let ms = |d: Duration| d.as_secs_f64() * 1000.0;
    println!(
        "docent check, {acts} acts, {pages} pages, {runs} runs: min {:.1} ms, p50 {:.1} ms, max {:.1} ms ({problems} warnings)",
        ms(times[0]),
        ms(times[times.len() / 2]),
        ms(times[times.len() - 1]),
    );
    Ok(())
}

/// Writes the bundle: `acts-N.yaml` files, `pages/pN.html`, `media/pic.png`.
fn write_bundle(dir: &Path, acts: usize, pages: usize) -> std::io::Result<()> {
    std::fs::create_dir_all(dir.join("pages"))?;
    std::fs::create_dir_all(dir.join("media"))?;
    std::fs::write(dir.join("media/pic.png"), PNG)?;
    std::fs::write(
        dir.join("docent.yaml"),
        "contexts: [TextGroup]\nhome: p0.html\n",
    )?;
    let files = 10;
    for f in 0..files {
        let mut text = String::new();
        for i in (f..acts).step_by(files) {
            let page = i % pages.max(1);
            let _ = write!(
                text,
                "- Label: ACT_{i}\n  Group: Topic {f}\n  Text:\n    - This is the first way to say act number {i}.\n    \
                 - And here is another way to say act {i}, for variety.\n  TextGroup:\n    \
                 - Hello everyone, this is act {i} for a group.\n  Cmds:\n    \
                 - DISPLAY_PAGE p{page}.html\n    - WAIT 2s\n"
            );
        }
        std::fs::write(dir.join(format!("acts-{f}.yaml")), text)?;
    }
    for p in 0..pages {
        let next = (p + 1) % pages;
        let offered: String = (0..3)
            .map(|k| {
                let act = (p * 3 + k) % acts.max(1);
                format!("    <button data-act=\"ACT_{act}\">Act {act}</button>\n")
            })
            .collect();
        let page = format!(
            "<!doctype html>\n<html lang=\"en\">\n<head><meta charset=\"utf-8\"><title>Page {p}</title></head>\n\
             <body>\n  <h1>Page {p}</h1>\n  <img src=\"/media/pic.png\" alt=\"\">\n  <nav>\n{offered}    \
             <a href=\"p{next}.html\">Next</a>\n  </nav>\n</body>\n</html>\n"
        );
        std::fs::write(dir.join(format!("pages/p{p}.html")), page)?;
    }
    Ok(())
}
