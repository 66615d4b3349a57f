//! The `docent` command: parses the command line, sets up logging and calls into the library
//! (`docent check` is `cli/check.rs`, `docent corpus` `cli/corpus.rs`, and so on).

use std::io::{IsTerminal, Write};
use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::{Parser, Subcommand, ValueEnum};
use docent::access::{AccessMode, decide_access};
use docent::cli::check::{self as check_cli, CheckFormat, counts, explain_hint, render};
use docent::cli::corpus as corpus_cli;
use docent::cli::explain as explain_cli;
use docent::cli::fleet as fleet_cli;
use docent::cli::start::{cannot_listen, open_preview, print_access};
use docent::cli::translations as translations_cli;
use docent::content::config::AdapterKind;
use docent::content::{load_bundle, schema};
use docent::reload::ReloadOptions;
use docent::serve::{ServeOptions, Server, run};
use tokio::net::TcpListener;

/// Docent presents dialog acts on a robot or kiosk: speech, touchscreen pages, projector, drive.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Serve a content bundle: pages, the trigger API and the websocket.
    Serve(ServeArgs),
    /// Check a bundle and list every problem with its file, line and column.
    Check {
        /// The bundle folder.
        bundle: PathBuf,
        /// Output format.
        #[arg(long, value_enum, default_value_t = CheckFormat::Text)]
        format: CheckFormat,
        /// Fail (exit 1) on warnings too, not only on errors.
        #[arg(long)]
        deny_warnings: bool,
    },
    /// Print the JSON Schema of the acts file or of docent.yaml, for editors (VS Code's YAML
    /// extension); `--out DIR` writes both files.
    Schema {
        /// Which schema to print.
        #[arg(value_enum, required_unless_present = "out")]
        which: Option<SchemaKind>,
        /// Write `acts.schema.json` and `docent.schema.json` (or the one asked for) into DIR.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
    },
    /// List the recorded visitor sessions, show one, purge one.
    ///
    /// Exit status 0 when done, 1 when refused or failed, 2 for a command line clap cannot
    /// read (docs/CORPUS.md, "Command line").
    Corpus(corpus_cli::CorpusArgs),
    /// Serve only the fleet view: every robot on an MQTT broker, with Stop (docs/FLEET.md).
    Fleet(fleet_cli::FleetArgs),
    /// Export the texts as a table for a translator (CSV, XLIFF), import the filled table.
    ///
    /// Exit status 0 when done, 1 when refused (nothing written), 2 for a command line clap
    /// cannot read, 3 when done with problems reported (docs/AUTHORING.md).
    Translations(translations_cli::TranslationsArgs),
    /// Explain a problem `docent check` reports, by its code: what it means, a broken example
    /// and its fix (docs/DIAGNOSTICS.md); without a code, list every code.
    Explain(explain_cli::ExplainArgs),
}

/// The schemas `docent schema` knows.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum SchemaKind {
    /// The acts files (`acts.yaml`, ...).
    Acts,
    /// The settings file `docent.yaml`.
    Config,
}

impl SchemaKind {
    fn file_name(self) -> &'static str {
        match self {
            SchemaKind::Acts => "acts.schema.json",
            SchemaKind::Config => "docent.schema.json",
        }
    }

    fn text(self) -> String {
        let schema = match self {
            SchemaKind::Acts => schema::acts_schema(),
            SchemaKind::Config => schema::config_schema(),
        };
        schema::to_file_text(&schema)
    }
}

/// What `docent serve` takes.
#[derive(clap::Args)]
struct ServeArgs {
    /// The bundle folder.
    #[arg(default_value = "dialogs/info-terminal")]
    bundle: PathBuf,
    /// Address to listen on. Stays on loopback unless told otherwise.
    #[arg(long, default_value = "127.0.0.1:8080")]
    listen: SocketAddr,
    /// Seed for choosing among alternative texts (reproducible runs).
    #[arg(long)]
    seed: Option<u64>,
    /// Folder for the corpus log.
    #[arg(long, default_value = "corpus")]
    corpus: PathBuf,
    /// How often the corpus log is synced to disk, bounding what a power cut can lose (e.g.
    /// `1s`, `200ms`; docs/CORPUS.md).
    #[arg(long, value_name = "INTERVAL", default_value = "1s", value_parser = humantime::parse_duration)]
    corpus_sync: std::time::Duration,
    /// Write speech as WAV files into this folder instead of playing it (no sound card).
    #[arg(long, value_name = "DIR")]
    speech_wav: Option<PathBuf>,
    /// Folder for media converted for Chromium (pictures and films it cannot show as they
    /// are), kept across restarts. Default: $CACHE_DIRECTORY/media under systemd, else
    /// $XDG_CACHE_HOME/docent/media, else ~/.cache/docent/media.
    #[arg(long, value_name = "DIR")]
    media_cache: Option<PathBuf>,
    /// For authors: speak in the browser and open the kiosk and projector side by side.
    #[arg(long)]
    preview: bool,
    /// Do not watch the bundle: saved files are not checked and put live while serving (they
    /// are by default; see docs/CONFIG.md, "Live reload").
    #[arg(long)]
    no_watch: bool,
    /// Development only: no credentials for operator and dialog-manager clients. Allowed
    /// only with a loopback --listen address.
    #[arg(long)]
    open: bool,
    /// Join a fleet: publish state and events to this MQTT broker and take commands from it,
    /// mqtt://HOST[:PORT] (docs/FLEET.md; overrides docent.yaml's mqtt: url).
    #[arg(long, value_name = "URL")]
    mqtt: Option<String>,
    /// This robot's id in the fleet's topics, docent/ID/... (overrides mqtt: robot_id).
    #[arg(long, value_name = "ID")]
    robot_id: Option<String>,
    /// For an mqtts:// broker: the PEM file of the CA it is checked against (the system's CAs
    /// without it; overrides mqtt: ca_file).
    #[arg(long, value_name = "FILE")]
    mqtt_ca: Option<PathBuf>,
}

/// How `serve` presents the bundle.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// On the robot or kiosk: speech as the bundle says.
    Robot,
    /// On an author's desktop: browser speech, both screens in one window.
    Preview,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Cmd::Check {
            bundle,
            format,
            deny_warnings,
        } => check_cli::run(&bundle, format, deny_warnings),
        Cmd::Serve(args) => serve(&args),
        Cmd::Schema { which, out } => write_schema(which, out.as_deref()),
        Cmd::Corpus(args) => return corpus_cli::run(&args),
        Cmd::Fleet(args) => fleet(&args),
        Cmd::Translations(args) => return translations_cli::run(&args),
        Cmd::Explain(args) => return explain_cli::run(&args),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("docent: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn write_schema(which: Option<SchemaKind>, out: Option<&Path>) -> anyhow::Result<ExitCode> {
    let Some(dir) = out else {
        let text = which.map(SchemaKind::text).unwrap_or_default();
        std::io::stdout().write_all(text.as_bytes())?;
        return Ok(ExitCode::SUCCESS);
    };
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let kinds = which.map_or(vec![SchemaKind::Acts, SchemaKind::Config], |kind| {
        vec![kind]
    });
    for kind in kinds {
        let path = dir.join(kind.file_name());
        std::fs::write(&path, kind.text())
            .with_context(|| format!("writing {}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(ExitCode::SUCCESS)
}

fn serve(args: &ServeArgs) -> anyhow::Result<ExitCode> {
    let (bundle_dir, listen) = (args.bundle.as_path(), args.listen);
    let mode = if args.preview {
        Mode::Preview
    } else {
        Mode::Robot
    };
    init_logging();
    let report = load_bundle(bundle_dir);
    print!("{}", render(bundle_dir, &report.diagnostics));
    let Some(mut bundle) = report.bundle else {
        let errors = counts(&report.diagnostics).errors;
        eprintln!(
            "docent: {} has {errors} error(s); fix them and start again",
            bundle_dir.display()
        );
        if let Some(hint) = explain_hint(&report.diagnostics) {
            eprintln!("{hint}");
        }
        return Ok(ExitCode::FAILURE);
    };
    if mode == Mode::Preview {
        // An author's desktop has a browser that can speak; the bundle's robot speech stays
        // untouched on disk.
        bundle.config.speech.adapter = Some(AdapterKind::Browser);
    }
    let setup = decide_access(
        args.open,
        listen.ip().is_loopback(),
        &bundle.config.access,
        |var| std::env::var(var).ok(),
    )?;
    let options = ServeOptions {
        seed: args.seed,
        corpus_dir: args.corpus.clone(),
        corpus_sync: args.corpus_sync,
        speech_wav: args.speech_wav.clone(),
        access: setup.mode.clone(),
        limits: None,
        media_cache: (args.media_cache.clone()).unwrap_or_else(docent::media::default_folder),
        media_tools: docent::media::Tools::find(),
    };
    let fleet_flags = docent::fleet::FleetFlags {
        url: args.mqtt.clone(),
        robot_id: args.robot_id.clone(),
        ca_file: args.mqtt_ca.clone(),
    };
    let mqtt_file = bundle.config.mqtt.clone();
    let home = bundle.config.home.clone();
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .max_blocking_threads(docent::serve::BLOCKING_THREADS)
        .build()
        .context("starting the async runtime")?;
    runtime.block_on(async move {
        let listener = TcpListener::bind(listen)
            .await
            .map_err(|error| anyhow::anyhow!(cannot_listen(listen, &error)))?;
        let addr = listener.local_addr()?;
        let password = std::env::var(docent::fleet::MQTT_PASSWORD_ENV).ok();
        let bridge = docent::fleet::decide_bridge(&fleet_flags, &mqtt_file, password, addr)
            .map_err(anyhow::Error::msg)?;
        let server = Server::start(bundle, &options).context("starting the server")?;
        let fleet_line = bridge.as_ref().map(|b| {
            format!(
                "  fleet:       {} as robot {}; fleet view http://{addr}/fleet (docs/FLEET.md)",
                b.broker.url, b.identity.robot
            )
        });
        if let Some(bridge) = bridge {
            let token = match &setup.mode {
                AccessMode::Guarded(credentials) => Some(credentials.operator.clone()),
                AccessMode::Open => None,
            };
            docent::fleet::join_fleet(server.state(), bridge, token);
        }
        if !args.no_watch {
            server.watch(ReloadOptions {
                speech_override: (mode == Mode::Preview).then_some(AdapterKind::Browser),
                ..ReloadOptions::default()
            });
        }
        let preview_note = match mode {
            Mode::Preview => "speech in the browser",
            Mode::Robot => "for authors: the pages and acts, live as you save",
        };
        // A closed stdout (a supervisor that stopped reading) must not stop the server.
        let _ = writeln!(
            std::io::stdout(),
            "Docent is serving {}\n  kiosk:       http://{addr}/\n  projector:   http://{addr}/projector\n  home page:   http://{addr}/pages/{home}\n  preview:     http://{addr}/preview  ({preview_note})\n  report:      http://{addr}/report  (the bundle's problems, as `docent check` tells them)\n  sessions:    http://{addr}/sessions  (recorded visits: replay, annotate, export)\n  trigger API: http://{addr}/api/acts  (docs/PROTOCOL.md)\n  websocket:   ws://{addr}/ws\n  corpus:      {}  (sessions/: one folder per visitor session; days/: other events)",
            bundle_dir.display(),
            server.corpus_path().display()
        );
        print_access(&setup, addr);
        if let Some(line) = fleet_line {
            let _ = writeln!(std::io::stdout(), "{line}");
        }
        // After the addresses, so that what the person starting Docent reads first is where
        // it serves; the log has them too.
        for warning in &server.warnings {
            tracing::warn!("{warning}");
        }
        if mode == Mode::Preview {
            open_preview(&format!("http://{addr}/preview"));
        }
        run(listener, server, shutdown_signal())
            .await
            .context("serving")?;
        anyhow::Ok(ExitCode::SUCCESS)
    })
}

/// `docent fleet`: the fleet view alone, behind the operator credential.
fn fleet(args: &fleet_cli::FleetArgs) -> anyhow::Result<ExitCode> {
    init_logging();
    fleet_cli::run(args, shutdown_signal())
}

/// Logs to standard error, Docent's own at `info` unless `RUST_LOG` says otherwise.
fn init_logging() {
    tracing_subscriber::fmt()
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_default_env()
                .unwrap_or_else(|_| "docent=info,tower_http=warn".into()),
        )
        .with_writer(std::io::stderr)
        // Colours for a person at a terminal; none in a file, the journal or a pipe, nor
        // with NO_COLOR set (no-color.org).
        .with_ansi(std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none())
        .init();
}

/// Completes on Ctrl-C or SIGTERM.
async fn shutdown_signal() {
    let ctrl_c = async {
        if tokio::signal::ctrl_c().await.is_err() {
            std::future::pending::<()>().await;
        }
    };
    #[cfg(unix)]
    let terminate = async {
        match tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()) {
            Ok(mut s) => drop(s.recv().await),
            Err(_) => std::future::pending().await,
        }
    };
    #[cfg(not(unix))]
    let terminate = std::future::pending::<()>();
    tokio::select! {
        () = ctrl_c => {}
        () = terminate => {}
    }
    tracing::info!("shutting down");
}
