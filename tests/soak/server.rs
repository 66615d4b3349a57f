//! The real `docent` binary serving the soak: started with the operator's and the dialog
//! manager's credentials in its environment and live reload on (as a site runs it), measured
//! from /proc while it runs, and stopped as systemd stops it (SIGTERM).

use std::path::Path;
use std::process::{Child, Command, ExitStatus, Stdio};
use std::time::Duration;

use crate::common::process::{start_logging, terminate};

/// The operator's credential the soak's server is started with.
pub const OPERATOR_TOKEN: &str = "soak-operator-credential";
/// The dialog manager's credential.
pub const DM_TOKEN: &str = "soak-dialog-manager-credential";

/// A running `docent serve`.
pub struct Docent {
    child: Child,
    /// `127.0.0.1:PORT`.
    pub addr: String,
}

impl Docent {
    /// Serves `bundle` on a free port of 127.0.0.1, logging into `corpus`; waits for the
    /// address it prints.
    pub fn start(docent: &Path, bundle: &Path, corpus: &Path, log: &Path) -> Docent {
        let stderr = std::fs::File::create(log).expect("server log");
        let mut command = Command::new(docent);
        command
            .arg("serve")
            .arg(bundle)
            .args(["--listen", "127.0.0.1:0", "--corpus"])
            .arg(corpus)
            .env("DOCENT_OPERATOR_TOKEN", OPERATOR_TOKEN)
            .env("DOCENT_DM_TOKEN", DM_TOKEN)
            .stdin(Stdio::null());
        let (child, addr) = start_logging(command, stderr);
        Docent { child, addr }
    }

    /// Its process id.
    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// Stops it with SIGTERM and waits for its exit, at most `limit`; `None` if it did not
    /// exit in time (it is then killed).
    pub fn stop(mut self, limit: Duration) -> Option<ExitStatus> {
        let pid = self.pid().to_string();
        terminate(self.pid());
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || tx.send(self.child.wait().expect("docent's status")));
        let status = rx.recv_timeout(limit).ok();
        if status.is_none() {
            let _ = Command::new("kill").args(["-KILL", &pid]).status();
        }
        status
    }
}

/// Resident memory (VmRSS) of `pid`, in kB.
pub fn rss_kb(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find_map(|l| l.strip_prefix("VmRSS:"))?;
    line.trim().trim_end_matches("kB").trim().parse().ok()
}

/// Open file descriptors of `pid` (sockets, logs, recordings, the watcher).
pub fn open_fds(pid: u32) -> Option<usize> {
    Some(std::fs::read_dir(format!("/proc/{pid}/fd")).ok()?.count())
}
