//! `docent-reload-bench`: save → new bundle live, as live reload gives it. Starts a fresh
//! Docent (watching, the default) on a temporary copy of a bundle, connects as an operator, then
//! `--saves` times appends a comment line to an acts file and measures from just before the
//! write until the `bundle.reloaded` event arrives over the websocket, which Docent publishes
//! right after the swap. Reports p50 and max, and the server's own `elapsed_ms`.
//! `--generate N` replaces the bundle with a generated one of N acts and N/10 pages.

// Shared with docent-bench, which uses the parts this binary does not (attach, pid).
#[allow(dead_code)]
#[path = "server.rs"]
mod server;

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use clap::Parser;
use futures_util::{SinkExt, StreamExt};
use serde_json::{Value, json};
use tokio_tungstenite::connect_async;
use tokio_tungstenite::tungstenite::Message;

use server::Server;

/// The error type shared with `server.rs`.
pub type Error = Box<dyn std::error::Error + Send + Sync>;

/// How long one save may take to go live before the run fails.
const DEADLINE: Duration = Duration::from_secs(30);

#[derive(Parser)]
#[command(about = "Save → new bundle live: p50 and max over a series of saves")]
struct Args {
    /// The bundle to copy (ignored with --generate).
    #[arg(long, default_value = "dialogs/museum-tour")]
    bundle: PathBuf,
    /// Generate a bundle of this many acts (and a tenth as many pages) instead.
    #[arg(long)]
    generate: Option<usize>,
    /// How many saves to measure.
    #[arg(long, default_value_t = 50)]
    saves: usize,
    /// The docent binary.
    #[arg(long, default_value = "target/release/docent")]
    docent: PathBuf,
}

fn main() -> ExitCode {
    let args = Args::parse();
    let runtime = match tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
    {
        Ok(runtime) => runtime,
        Err(e) => {
            eprintln!("docent-reload-bench: {e}");
            return ExitCode::FAILURE;
        }
    };
    match runtime.block_on(run(&args)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("docent-reload-bench: {e}");
            ExitCode::FAILURE
        }
    }
}

async fn run(args: &Args) -> Result<(), Error> {
    let scratch = std::env::temp_dir().join(format!("docent-reload-bench-{}", std::process::id()));
    let bundle = scratch.join("bundle");
    match args.generate {
        Some(acts) => generate(&bundle, acts)?,
        None => copy_dir(&args.bundle, &bundle)?,
    }
    let acts_file = first_acts_file(&bundle)?;
    let server = Server::start(&args.docent, &bundle)?;
    let (mut ws, _) = connect_async(server.url.as_str()).await?;
    ws.send(Message::text(
        json!({"type": "hello", "role": "operator"}).to_string(),
    ))
    .await?;
    let mut took = Vec::with_capacity(args.saves);
    let mut server_ms = Vec::with_capacity(args.saves);
    for n in 0..args.saves {
        let started = Instant::now();
        let mut file = fs::OpenOptions::new().append(true).open(&acts_file)?;
        writeln!(file, "# save {n}")?;
        drop(file);
        let event = tokio::time::timeout(DEADLINE, next_reloaded(&mut ws))
            .await
            .map_err(|_| format!("save {n} was not live within {DEADLINE:?}"))??;
        took.push(started.elapsed());
        server_ms.push(event["elapsed_ms"].as_u64().unwrap_or(0));
    }
    drop(server);
    let _ = fs::remove_dir_all(&scratch);
    took.sort();
    server_ms.sort_unstable();
    let what = match args.generate {
        Some(acts) => format!("generated ({acts} acts, {} pages)", acts / 10),
        None => args.bundle.display().to_string(),
    };
    let ms = |d: Duration| d.as_secs_f64() * 1000.0;
    println!(
        "{what}: {} saves, save → live p50 {:.0} ms, max {:.0} ms (server: first change seen → \
         live p50 {} ms, max {} ms)",
        took.len(),
        ms(took[took.len() / 2]),
        ms(took[took.len() - 1]),
        server_ms[server_ms.len() / 2],
        server_ms[server_ms.len() - 1],
    );
    Ok(())
}

/// Reads frames until a `bundle.reloaded` event; a refused save fails the run.
async fn next_reloaded<S>(ws: &mut S) -> Result<Value, Error>
where
    S: futures_util::Stream<Item = Result<Message, tokio_tungstenite::tungstenite::Error>> + Unpin,
{
    while let Some(message) = ws.next().await {
        let Message::Text(text) = message? else {
            continue;
        };
        let frame: Value = serde_json::from_str(&text)?;
        match frame["event"]["type"].as_str() {
            Some("bundle.reloaded") => return Ok(frame["event"].clone()),
            Some("bundle.refused") => return Err(format!("a save was refused: {frame}").into()),
            _ => {}
        }
    }
    Err("the server closed the connection".into())
}

/// The first acts file of a bundle, by name.
fn first_acts_file(bundle: &Path) -> Result<PathBuf, Error> {
    let mut names: Vec<PathBuf> = fs::read_dir(bundle)?
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.extension().is_some_and(|e| e == "yaml" || e == "yml")
                && p.file_name().is_some_and(|n| n != "docent.yaml")
        })
        .collect();
    names.sort();
    names
        .into_iter()
        .next()
        .ok_or_else(|| format!("no acts file in {}", bundle.display()).into())
}

fn copy_dir(from: &Path, to: &Path) -> Result<(), Error> {
    fs::create_dir_all(to)?;
    for entry in fs::read_dir(from)? {
        let entry = entry?;
        let target = to.join(entry.file_name());
        if entry.file_type()?.is_dir() {
            copy_dir(&entry.path(), &target)?;
        } else {
            fs::copy(entry.path(), target)?;
        }
    }
    Ok(())
}

/// A bundle of `acts` acts in 10 files and `acts / 10` pages, each page offering ten acts.
fn generate(bundle: &Path, acts: usize) -> Result<(), Error> {
    fs::create_dir_all(bundle.join("pages"))?;
    fs::create_dir_all(bundle.join("media"))?;
    let per_file = acts.div_ceil(10).max(1);
    for (file, chunk) in (0..acts).collect::<Vec<_>>().chunks(per_file).enumerate() {
        let mut text = String::new();
        for i in chunk {
            text.push_str(&format!(
                "- Label: ACT_{i}\n  Text:\n    - This is sentence number {i}.\n    - And another one, {i}.\n"
            ));
        }
        fs::write(bundle.join(format!("acts-{file:02}.yaml")), text)?;
    }
    let pages = (acts / 10).max(1);
    for p in 0..pages {
        let mut html = format!("<!doctype html><title>Page {p}</title>\n");
        for i in (p * 10)..((p * 10 + 10).min(acts)) {
            html.push_str(&format!("<button data-act=\"ACT_{i}\">Act {i}</button>\n"));
        }
        let name = if p == 0 {
            "index.html".to_owned()
        } else {
            format!("page-{p}.html")
        };
        fs::write(bundle.join("pages").join(name), html)?;
    }
    Ok(())
}
