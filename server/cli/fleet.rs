//! `docent fleet --mqtt URL`: the command line of a server of the fleet view alone (the
//! serving itself is `standalone.rs`), apart from `main.rs` like `docent corpus`'s.

use std::future::Future;
use std::io::Write;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use tokio::net::TcpListener;

use crate::access::{AccessMode, Origin, decide_access};

/// What `docent fleet` takes.
#[derive(clap::Args)]
pub struct FleetArgs {
    /// The fleet's broker, mqtt://HOST[:PORT] (password in DOCENT_MQTT_PASSWORD).
    #[arg(long, value_name = "URL")]
    pub mqtt: String,
    /// The broker's user name for the fleet view.
    #[arg(long, value_name = "NAME")]
    pub mqtt_username: Option<String>,
    /// For an mqtts:// broker: the PEM file of the CA it is checked against (the system's CAs
    /// without it).
    #[arg(long, value_name = "FILE")]
    pub mqtt_ca: Option<PathBuf>,
    /// Address to listen on. Stays on loopback unless told otherwise.
    #[arg(long, default_value = "127.0.0.1:8090")]
    pub listen: SocketAddr,
    /// Development only: no operator credential. Allowed only with a loopback --listen address.
    #[arg(long)]
    pub open: bool,
}

/// Runs `docent fleet` until `shutdown` completes.
pub fn run(
    args: &FleetArgs,
    shutdown: impl Future<Output = ()> + Send + 'static,
) -> anyhow::Result<ExitCode> {
    let url = crate::fleet::BrokerUrl::parse(&args.mqtt)
        .map_err(|why| anyhow::anyhow!("--mqtt: {why}"))?;
    let password = std::env::var(crate::fleet::MQTT_PASSWORD_ENV)
        .ok()
        .filter(|p| !p.is_empty())
        .map(crate::access::Secret::new);
    let tls = crate::fleet::tls_for(&url, args.mqtt_ca.as_deref()).map_err(anyhow::Error::msg)?;
    let broker = crate::fleet::Broker {
        tls,
        url,
        username: args.mqtt_username.clone(),
        password,
    };
    let listen = args.listen;
    let setup = decide_access(
        args.open,
        listen.ip().is_loopback(),
        &Default::default(),
        |var| std::env::var(var).ok(),
    )?;
    let runtime = tokio::runtime::Runtime::new().context("starting the async runtime")?;
    runtime.block_on(async move {
        let listener = TcpListener::bind(listen)
            .await
            .with_context(|| format!("listening on {listen}"))?;
        let addr = listener.local_addr()?;
        let _ = writeln!(
            std::io::stdout(),
            "Docent fleet view of {}\n  fleet:       http://{addr}/fleet",
            broker.url
        );
        if let AccessMode::Guarded(credentials) = &setup.mode {
            let line = match setup.operator {
                Some(Origin::Generated) => format!(
                    "operator credential (generated for this run): {}",
                    credentials.operator.expose()
                ),
                Some(Origin::Environment) => {
                    "operator credential: from DOCENT_OPERATOR_TOKEN".into()
                }
                _ => String::new(),
            };
            let _ = writeln!(std::io::stdout(), "  {line}");
        } else {
            let _ = writeln!(
                std::io::stdout(),
                "  access:      open (--open): for development only"
            );
        }
        if setup.operator == Some(Origin::Generated) {
            let _ = writeln!(
                std::io::stdout(),
                "  note:        the robots will refuse a Stop with a generated credential: set \
                 DOCENT_OPERATOR_TOKEN to the fleet's operator credential (docs/FLEET.md)"
            );
        }
        let options = crate::fleet::FleetOptions {
            broker,
            access: setup.mode.clone(),
        };
        crate::fleet::serve_fleet(listener, options, shutdown)
            .await
            .context("serving")?;
        anyhow::Ok(ExitCode::SUCCESS)
    })
}
