//! The real `docent` binary as a child process, for tests that kill it or limit it from
//! outside (`kill -9`, a file size limit), which an in-process server cannot show.

use std::ffi::OsString;
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, Stdio};

/// Runs `docent ARGS` to its end in the repository's folder: exit status, stdout, stderr.
pub fn run_docent(args: &[&str]) -> (i32, String, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_docent"))
        .args(args)
        .current_dir(super::repo())
        .output()
        .expect("docent runs");
    let text = |b: Vec<u8>| String::from_utf8(b).expect("utf-8");
    (
        output.status.code().expect("exit status"),
        text(output.stdout),
        text(output.stderr),
    )
}

/// `docent serve BUNDLE --listen 127.0.0.1:0 --open --no-watch --corpus CORPUS`'s arguments.
pub fn serve_args(bundle: &Path, corpus: &Path) -> Vec<OsString> {
    let mut args: Vec<OsString> = vec!["serve".into(), bundle.into()];
    args.extend(
        [
            "--listen",
            "127.0.0.1:0",
            "--open",
            "--no-watch",
            "--corpus",
        ]
        .map(OsString::from),
    );
    args.push(corpus.into());
    args
}

/// The `docent` binary serving `bundle`, logging into `corpus`; with its address.
pub fn spawn_docent(bundle: &Path, corpus: &Path) -> (Child, String) {
    let mut command = Command::new(env!("CARGO_BIN_EXE_docent"));
    command.args(serve_args(bundle, corpus));
    start(command)
}

/// Starts `command` (which runs `docent serve` on port 0, perhaps through a shell) and waits
/// for the address it prints; its output is read on until it exits.
pub fn start(command: Command) -> (Child, String) {
    start_logging(command, Stdio::null())
}

/// As [`start`], with the server's stderr (its log) going to `stderr`.
pub fn start_logging(mut command: Command, stderr: impl Into<Stdio>) -> (Child, String) {
    let mut child = command
        .stdout(Stdio::piped())
        .stderr(stderr)
        .spawn()
        .unwrap_or_else(|e| panic!("starting {:?}: {e}", command.get_program()));
    let mut lines = BufReader::new(child.stdout.take().expect("stdout")).lines();
    let addr = (&mut lines)
        .map_while(Result::ok)
        .find_map(|l| {
            let url = l.trim().strip_prefix("websocket:")?.trim();
            Some(
                url.trim_start_matches("ws://")
                    .trim_end_matches("/ws")
                    .to_owned(),
            )
        })
        .expect("docent prints its websocket address");
    std::thread::spawn(move || lines.for_each(drop));
    (child, addr)
}

/// Sends `pid` SIGTERM, as systemd stops Docent.
pub fn terminate(pid: u32) {
    let sent = Command::new("kill").arg(pid.to_string()).status();
    assert!(sent.is_ok_and(|s| s.success()), "kill -TERM {pid}");
}

/// Stops `docent` as systemd would (SIGTERM) and waits for it: it exits cleanly, its corpus
/// complete.
pub fn stop(mut docent: Child) {
    terminate(docent.id());
    let exit = docent.wait().expect("docent exits");
    assert!(exit.success(), "{exit}");
}
