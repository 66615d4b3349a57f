//! What `docent serve` tells the person starting it beyond the bundle's problems: how
//! operators and dialog managers get in, the preview opened in a browser, and what to do
//! when the address cannot be listened on.

use std::io::Write;
use std::net::SocketAddr;

use crate::access::{AccessMode, AccessSetup, Origin};

/// What to do when Docent cannot listen on `listen`, in the words of the person starting it.
pub fn cannot_listen(listen: SocketAddr, error: &std::io::Error) -> String {
    let (ip, port) = (listen.ip(), listen.port());
    let next = SocketAddr::new(ip, port.saturating_add(1));
    match error.kind() {
        std::io::ErrorKind::AddrInUse => format!(
            "cannot listen on {listen}: another program already uses port {port} (another \
             Docent, or the kiosk's own service: `ss -ltnp 'sport = :{port}'` names it). Stop \
             it, or give another address: --listen {next}"
        ),
        std::io::ErrorKind::PermissionDenied => format!(
            "cannot listen on {listen}: ports below 1024 need administrator rights. Give a \
             higher port, for example --listen {ip}:8080"
        ),
        std::io::ErrorKind::AddrNotAvailable => format!(
            "cannot listen on {listen}: this computer has no network address {ip}. Give one \
             it has (`ip -brief address` lists them), 127.0.0.1 for this computer only, or \
             0.0.0.0 for all of them"
        ),
        _ => format!("cannot listen on {listen}: {error}"),
    }
}

/// Says how operators and dialog managers get in. A generated credential is printed here,
/// on the console of the person starting Docent, and nowhere else (never in the log).
pub fn print_access(setup: &AccessSetup, addr: SocketAddr) {
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "  operator:    http://{addr}/operator");
    let AccessMode::Guarded(credentials) = &setup.mode else {
        let _ = writeln!(
            out,
            "  access:      open (--open): no credentials needed; for development only"
        );
        return;
    };
    let roles = [
        (
            "operator",
            &credentials.operator,
            setup.operator,
            "DOCENT_OPERATOR_TOKEN",
        ),
        (
            "dialog manager",
            &credentials.dm,
            setup.dm,
            "DOCENT_DM_TOKEN",
        ),
    ];
    for (role, secret, origin, var) in roles {
        let line = match origin {
            Some(Origin::Generated) => format!(
                "{role} credential (generated for this run; set {var} to choose one): {}",
                secret.expose()
            ),
            Some(Origin::Environment) => format!("{role} credential: from {var}"),
            Some(Origin::Settings) => format!("{role} credential: from docent.yaml"),
            None => continue,
        };
        let _ = writeln!(out, "  {line}");
    }
}

/// Opens the preview in the desktop's browser, or says to when there is none.
pub fn open_preview(url: &str) {
    let opened = std::process::Command::new("xdg-open")
        .arg(url)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn();
    if opened.is_err() {
        let _ = writeln!(
            std::io::stdout(),
            "  open it in a browser to preview the bundle"
        );
    }
}
