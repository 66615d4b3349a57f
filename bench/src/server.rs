//! The Docent under test: started fresh from its binary with one bench bundle on a free
//! loopback port (and killed when dropped), or an already running one the benchmark attaches to.

use std::fs::{self, File};
use std::net::{Ipv4Addr, TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::thread;
use std::time::{Duration, Instant};

use crate::Error;

/// How long a started Docent may take to listen.
const START_TIMEOUT: Duration = Duration::from_secs(15);

/// A Docent to send load to.
pub struct Server {
    /// Its websocket URL.
    pub url: String,
    /// Its pid, for /proc figures; unknown when attached without `--server-pid`.
    pub pid: Option<u32>,
    child: Option<Child>,
    /// Scratch folder (corpus log, server log) of a started server.
    scratch: Option<PathBuf>,
}

impl Server {
    /// Starts `docent serve bundle` on a free loopback port, with its corpus and log in a fresh
    /// scratch folder, and waits until it listens.
    pub fn start(docent: &Path, bundle: &Path) -> Result<Server, Error> {
        if !docent.is_file() {
            let shown = docent.display();
            return Err(format!("no Docent binary at {shown} (cargo build --release?)").into());
        }
        let port = free_port()?;
        let scratch =
            std::env::temp_dir().join(format!("docent-bench-{}-{port}", std::process::id()));
        fs::create_dir_all(&scratch).map_err(|e| format!("creating {}: {e}", scratch.display()))?;
        let log_path = scratch.join("docent.log");
        let log =
            File::create(&log_path).map_err(|e| format!("creating {}: {e}", log_path.display()))?;
        let log2 = log.try_clone()?;
        let child = Command::new(docent)
            .arg("serve")
            .arg(bundle)
            .args(["--listen", &format!("127.0.0.1:{port}"), "--corpus"])
            .arg(scratch.join("corpus"))
            // Loopback only: the load clients say hello as operators without a credential.
            .arg("--open")
            .stdin(Stdio::null())
            .stdout(log)
            .stderr(log2)
            .spawn()
            .map_err(|e| format!("starting {}: {e}", docent.display()))?;
        let mut server = Server {
            url: format!("ws://127.0.0.1:{port}/ws"),
            pid: Some(child.id()),
            child: Some(child),
            scratch: Some(scratch),
        };
        server.wait_listening(port, &log_path)?;
        Ok(server)
    }

    /// A server someone else started.
    pub fn attach(url: String, pid: Option<u32>) -> Server {
        Server {
            url,
            pid,
            child: None,
            scratch: None,
        }
    }

    fn wait_listening(&mut self, port: u16, log: &Path) -> Result<(), Error> {
        let give_up = Instant::now() + START_TIMEOUT;
        loop {
            if TcpStream::connect((Ipv4Addr::LOCALHOST, port)).is_ok() {
                return Ok(());
            }
            let exited = match self.child.as_mut() {
                Some(child) => child.try_wait()?,
                None => None,
            };
            if exited.is_some() || Instant::now() > give_up {
                let tail = fs::read_to_string(log).unwrap_or_default();
                let what = match exited {
                    Some(status) => format!("Docent exited ({status})"),
                    None => format!("Docent did not listen within {START_TIMEOUT:?}"),
                };
                return Err(format!("{what}; its output:\n{tail}").into());
            }
            thread::sleep(Duration::from_millis(50));
        }
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        if let Some(mut child) = self.child.take() {
            let _ = child.kill();
            let _ = child.wait();
        }
        if let Some(scratch) = self.scratch.take() {
            let _ = fs::remove_dir_all(scratch);
        }
    }
}

/// A loopback port nobody listens on right now.
fn free_port() -> Result<u16, Error> {
    let listener = TcpListener::bind((Ipv4Addr::LOCALHOST, 0))
        .map_err(|e| format!("finding a free port: {e}"))?;
    Ok(listener.local_addr()?.port())
}
