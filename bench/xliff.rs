//! Benchmark of `docent translations import`'s XLIFF reader: how long reading a table of
//! translations takes as it grows (`bench/xliff_table.rs` generates one shaped as Docent
//! exports it), to show the time grows with the size, not its square; and how soon a file
//! nested a million deep is refused. Run with
//! `cargo run --release --example xliff-bench -- [--mb 1,2,4] [--runs N]`; figures in
//! `bench/README.md`.

#[path = "xliff_table.rs"]
mod xliff_table;

use std::time::{Duration, Instant};

use docent::content::Language;
use docent::translations::xliff::read_xliff;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let value =
        |name: &str| (args.iter().position(|a| a == name)).and_then(|i| args.get(i + 1).cloned());
    let sizes: Vec<usize> = value("--mb")
        .unwrap_or_else(|| "1,2,4".to_owned())
        .split(',')
        .map(str::parse)
        .collect::<Result<_, _>>()?;
    let runs: usize = value("--runs").map_or(Ok(5), |r| r.parse())?;
    let en = Language::parse("en").ok_or("en")?;
    println!("XLIFF tables read with read_xliff; {runs} runs each, wall clock");
    let mut first: Option<(f64, f64)> = None;
    for mb in sizes {
        let (text, units) = xliff_table::table(mb << 20);
        let mut times: Vec<Duration> = Vec::with_capacity(runs);
        for _ in 0..runs {
            let start = Instant::now();
            let table = read_xliff(text.as_bytes(), &en, None)?;
            times.push(start.elapsed());
            assert_eq!(table.entries.len(), units);
        }
        times.sort();
        let ms = |d: Duration| d.as_secs_f64() * 1000.0;
        let p50 = ms(times[times.len() / 2]);
        let size = text.len() as f64 / 1e6;
        let (size0, p50_0) = *first.get_or_insert((size, p50));
        println!(
            "{size:5.2} MB, {units:6} units: min {:8.1} ms  p50 {p50:8.1} ms  max {:8.1} ms  \
             ({:.1}x the size, {:.1}x the time of the first)",
            ms(times[0]),
            ms(times[times.len() - 1]),
            size / size0,
            p50 / p50_0
        );
    }
    let deep = xliff_table::nested(1 << 20);
    let start = Instant::now();
    let refused = read_xliff(deep.as_bytes(), &en, None).is_err();
    println!(
        "{:5.2} MB nested {} deep: refused {refused}, in {:.1} ms",
        deep.len() as f64 / 1e6,
        1 << 20,
        start.elapsed().as_secs_f64() * 1000.0
    );
    Ok(())
}
