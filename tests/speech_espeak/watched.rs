//! A real `docent serve` whose espeak-ng the test can watch and hurt: each speaking espeak-ng
//! tells the test its pid as it starts, an event the test awaits, and the first commands'
//! WAV paths are named pipes nobody reads, so that espeak-ng blocks there mid-utterance until
//! the test acts on it.
//!
//! The real binary, not a server in the test's process, so that its PATH can differ from the
//! test's: first on it is a folder with a wrapper named `espeak-ng` that writes its pid into a
//! named pipe the test reads, then `exec`s the real espeak-ng, which keeps the pid (signals
//! sent to it reach the real process; one sent in the moment between the pid's writing and
//! the `exec` reaches the same process, and ends it the same way).

use std::path::Path;
use std::process::{Child, Command};

use serde_json::{Value, json};
use tokio::io::{AsyncBufReadExt, BufReader, Lines};
use tokio::net::unix::pipe;

use crate::common::process::{serve_args, start, stop};
use crate::common::{DEADLINE, TempBundle, WsClient, within};

/// How many command ids get a blocking pipe (a fresh server numbers its commands from 1).
pub const BLOCKED: u64 = 4;

/// A running `docent serve` speaking through the watched espeak-ng.
pub struct WatchedEspeak {
    docent: Option<Child>,
    addr: String,
    /// One line per espeak-ng that started speaking: its pid.
    started: Lines<BufReader<pipe::Receiver>>,
    http: reqwest::Client,
    _folders: [tempfile::TempDir; 2],
}

impl WatchedEspeak {
    /// Serves `bundle`, writing speech into `wavs`.
    pub fn start(bundle: &TempBundle, wavs: &Path) -> Self {
        for id in 1..=BLOCKED {
            mkfifo(&wavs.join(format!("{id}.wav")));
        }
        let wrapper = tempfile::tempdir().expect("a folder for the wrapper");
        let pids = wrapper.path().join("started");
        mkfifo(&pids);
        // Read and write: never at its end between two espeak-ngs, and a wrapper opening it
        // to write never waits for a reader.
        let receiver = pipe::OpenOptions::new()
            .read_write(true)
            .open_receiver(&pids)
            .expect("the pid pipe opens");
        write_wrapper(&wrapper.path().join("espeak-ng"), &pids);
        let path = std::env::var_os("PATH").unwrap_or_default();
        let mut search = wrapper.path().as_os_str().to_owned();
        search.push(":");
        search.push(path);
        let corpus = tempfile::tempdir().expect("corpus folder");
        let mut command = Command::new(env!("CARGO_BIN_EXE_docent"));
        command
            .args(serve_args(bundle.path(), corpus.path()))
            .arg("--speech-wav")
            .arg(wavs)
            .env("PATH", search);
        let (docent, addr) = start(command);
        WatchedEspeak {
            docent: Some(docent),
            addr,
            started: BufReader::new(receiver).lines(),
            http: reqwest::Client::new(),
            _folders: [wrapper, corpus],
        }
    }

    /// An operator client.
    pub async fn operator(&self) -> WsClient {
        WsClient::operator_at(&self.addr).await
    }

    /// Triggers `label` over HTTP; its first command's id.
    pub async fn trigger(&self, label: &str) -> u64 {
        let url = format!("http://{}/api/acts/{label}/trigger", self.addr);
        let answer = (self.http.post(url).json(&json!({})).send().await).expect("POST");
        assert_eq!(answer.status(), 202, "trigger {label}");
        let body: Value = answer.json().await.expect("JSON");
        body["commands"][0]["id"].as_u64().expect("a command id")
    }

    /// The pid of the next espeak-ng the server starts to speak, once it runs.
    pub async fn next_espeak(&mut self) -> u32 {
        let line = within(DEADLINE, self.started.next_line())
            .await
            .expect("espeak-ng started within the deadline")
            .expect("the pid pipe reads")
            .expect("a pid");
        line.trim().parse().expect("a pid")
    }

    /// Stops the server as systemd does (SIGTERM): it exits cleanly.
    pub fn stop(mut self) {
        stop(self.docent.take().expect("running"));
    }
}

impl Drop for WatchedEspeak {
    /// A failed test's server does not outlive it.
    fn drop(&mut self) {
        if let Some(mut docent) = self.docent.take() {
            let _ = docent.kill();
            let _ = docent.wait();
        }
    }
}

/// Writes the wrapper `espeak-ng` at `at`: a speaking espeak-ng (text on `--stdin`; not the
/// server's start-up questions, `--version` and `--voices`) writes its pid into `pids`, then
/// each becomes the real espeak-ng.
fn write_wrapper(at: &Path, pids: &Path) {
    use std::os::unix::fs::PermissionsExt;
    let found = Command::new("sh")
        .args(["-c", "command -v espeak-ng"])
        .output()
        .expect("sh runs");
    let real = String::from_utf8(found.stdout).expect("a UTF-8 path");
    let real = real.trim();
    assert!(!real.is_empty(), "espeak-ng is not installed");
    let script = format!(
        "#!/bin/sh\ncase \" $* \" in *\" --stdin \"*) echo $$ > '{}' ;; esac\nexec '{real}' \"$@\"\n",
        pids.display()
    );
    std::fs::write(at, script).expect("the wrapper is written");
    std::fs::set_permissions(at, std::fs::Permissions::from_mode(0o755)).expect("chmod");
}

fn mkfifo(path: &Path) {
    let made = Command::new("mkfifo").arg(path).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo {}", path.display());
}

/// Lets the commands after the blocked ones write real files.
pub fn unblock(wavs: &Path) {
    for id in 1..=BLOCKED {
        let _ = std::fs::remove_file(wavs.join(format!("{id}.wav")));
    }
}
