//! docent-bench: load client for Docent. For each scenario it starts a fresh Docent with the
//! matching bench bundle (or attaches to a running one), drives it over the websocket and reports
//! trigger → command latency, throughput, lost commands and the server's CPU and memory.
//!
//! Scenarios (`bench/README.md` says more):
//! - `adapter`: senders (operators) at a fixed rate, open loop; one ws adapter answering `done`.
//! - `kiosk`: the same, with 50 kiosk clients each receiving every `DISPLAY_PAGE`.
//! - `max`: closed loop against the ws adapter: the highest sustained throughput.
//! - `flood`: many senders at a fixed rate, each timing its own `triggered` answers (bundle
//!   kiosk, one kiosk connected): the latency an operator or dialog manager feels under a flood.
//! - `idle`: 1,000 idle kiosk connections and the server memory they take.
//!
//! Prints one JSON line per scenario on stdout as it finishes, then a table.

mod client;
mod idle;
mod load;
mod procfs;
mod report;
mod server;
mod tally;

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

use clap::{Parser, ValueEnum};

use client::Role;
use load::Plan;
use report::Outcome;
use server::Server;

/// Any error, with a message for people.
pub type Error = Box<dyn std::error::Error + Send + Sync>;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Scenario {
    /// Open loop, one ws adapter answering `done` (bundle ws-adapter).
    Adapter,
    /// Open loop, many kiosk clients (bundle kiosk).
    Kiosk,
    /// Closed loop, one ws adapter: the highest throughput (bundle ws-adapter).
    Max,
    /// Idle kiosk connections and their memory (bundle kiosk).
    Idle,
    /// Open loop, senders timing their own answers (bundle kiosk, one kiosk).
    Flood,
}

impl Scenario {
    fn name(self) -> &'static str {
        match self {
            Scenario::Adapter => "adapter",
            Scenario::Kiosk => "kiosk",
            Scenario::Max => "max",
            Scenario::Idle => "idle",
            Scenario::Flood => "flood",
        }
    }

    fn bundle(self) -> &'static str {
        match self {
            Scenario::Adapter | Scenario::Max => "ws-adapter",
            Scenario::Kiosk | Scenario::Idle | Scenario::Flood => "kiosk",
        }
    }
}

#[derive(Parser, Debug)]
#[command(about = "Trigger → command latency, throughput and memory of Docent")]
struct Args {
    /// Scenarios to run, in this order (repeat or comma-separate) [default: all]
    #[arg(long = "scenario", value_enum, value_delimiter = ',')]
    scenarios: Vec<Scenario>,
    /// Short runs: 0.5 s warm-up and 3 s measured per scenario, 200 idle connections
    #[arg(long)]
    quick: bool,
    /// The docent binary to start [default: `docent` beside this binary]
    #[arg(long)]
    docent: Option<PathBuf>,
    /// Folder holding the bench bundles `ws-adapter` and `kiosk`
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/bundles"))]
    bundles: PathBuf,
    /// Use this running Docent (its websocket URL, e.g. ws://127.0.0.1:8080/ws) instead of
    /// starting one; it must serve the scenario's bundle
    #[arg(long)]
    attach: Option<String>,
    /// Pid of the attached Docent, for its CPU and memory figures
    #[arg(long, requires = "attach")]
    server_pid: Option<u32>,
    /// Trigger-sending connections (operators) in `adapter` and `kiosk`, each on its own thread
    #[arg(long, default_value_t = 1)]
    senders: usize,
    /// Triggers per second per sender in `adapter` and `kiosk`
    #[arg(long, default_value_t = 200.0)]
    rate: f64,
    /// Kiosk clients in `kiosk`
    #[arg(long, default_value_t = 50)]
    kiosks: usize,
    /// Closed-loop senders in `max`
    #[arg(long, default_value_t = 4)]
    max_senders: usize,
    /// Connections in `idle` [default: 1000; 200 with --quick]
    #[arg(long)]
    idle_connections: Option<usize>,
    /// Measured seconds per scenario [default: 10; 3 with --quick]
    #[arg(long)]
    duration: Option<f64>,
    /// Unmeasured seconds before the measured ones [default: 1; 0.5 with --quick]
    #[arg(long)]
    warmup: Option<f64>,
    /// Seconds to wait for outstanding commands after the last trigger (`max`: per trigger)
    #[arg(long, default_value_t = 2.0)]
    drain: f64,
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(outcomes) => {
            println!();
            print!("{}", report::table(&outcomes));
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("docent-bench: {e}");
            ExitCode::FAILURE
        }
    }
}

fn seconds(
    value: Option<f64>,
    normal: f64,
    quick: f64,
    is_quick: bool,
    what: &str,
) -> Result<Duration, Error> {
    let s = value.unwrap_or(if is_quick { quick } else { normal });
    Duration::try_from_secs_f64(s)
        .map_err(|_| format!("--{what} must be a non-negative number of seconds").into())
}

fn run(args: &Args) -> Result<Vec<Outcome>, Error> {
    let scenarios = match args.scenarios.as_slice() {
        [] => vec![
            Scenario::Adapter,
            Scenario::Kiosk,
            Scenario::Max,
            Scenario::Idle,
        ],
        some => some.to_vec(),
    };
    let docent = match &args.docent {
        Some(path) => path.clone(),
        None => std::env::current_exe()?
            .parent()
            .ok_or("cannot tell this binary's folder")?
            .join("docent"),
    };
    let warmup = seconds(args.warmup, 1.0, 0.5, args.quick, "warmup")?;
    let duration = seconds(args.duration, 10.0, 3.0, args.quick, "duration")?;
    let drain = seconds(Some(args.drain), 2.0, 2.0, args.quick, "drain")?;
    let idle_connections = args
        .idle_connections
        .unwrap_or(if args.quick { 200 } else { 1000 });
    let mut outcomes = Vec::new();
    for scenario in scenarios {
        let server = match &args.attach {
            Some(url) => Server::attach(url.clone(), args.server_pid),
            None => Server::start(&docent, &bundle(&args.bundles, scenario)?)?,
        };
        eprintln!("== {}: Docent at {}", scenario.name(), server.url);
        let rt = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()?;
        let outcome = match scenario {
            Scenario::Idle => {
                let report = rt.block_on(idle::run(&server.url, idle_connections, server.pid))?;
                Outcome::Idle { report }
            }
            _ => {
                let plan = plan(args, scenario, &server, warmup, duration, drain);
                let measured = rt.block_on(load::run(&plan))?;
                Outcome::Load {
                    name: scenario.name(),
                    plan,
                    measured: Box::new(measured),
                }
            }
        };
        // Subscriber tasks end with their runtime, before the server goes.
        drop(rt);
        drop(server);
        println!("{}", outcome.json());
        outcomes.push(outcome);
    }
    Ok(outcomes)
}

fn bundle(root: &Path, scenario: Scenario) -> Result<PathBuf, Error> {
    let dir = root.join(scenario.bundle());
    if !dir.join("acts.yaml").is_file() {
        let shown = dir.display();
        return Err(format!("no bench bundle at {shown} (see --bundles)").into());
    }
    Ok(dir)
}

fn plan(
    args: &Args,
    scenario: Scenario,
    server: &Server,
    warmup: Duration,
    duration: Duration,
    drain: Duration,
) -> Plan {
    let (subscriber, subscribers, senders, rate) = match scenario {
        Scenario::Kiosk => (Role::Kiosk, args.kiosks, args.senders, Some(args.rate)),
        Scenario::Flood => (Role::Kiosk, 1, args.senders, Some(args.rate)),
        Scenario::Max => (Role::SayAdapter, 1, args.max_senders, None),
        _ => (Role::SayAdapter, 1, args.senders, Some(args.rate)),
    };
    Plan {
        url: server.url.clone(),
        label: "OK".to_owned(),
        answers: scenario == Scenario::Flood,
        subscriber,
        subscribers,
        senders,
        rate,
        warmup,
        duration,
        drain,
        server_pid: server.pid,
    }
}
