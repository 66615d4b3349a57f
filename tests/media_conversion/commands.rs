//! The `docent` binary with the media to convert: `docent check` asks ffmpeg about each file
//! and says when it is missing; `docent serve` says at start-up which files will not be shown.

use std::path::Path;
use std::process::Command;

use serde_json::Value;

use super::{cut_mov, film_bundle, mpeg1};
use crate::common;
use common::TempBundle;

/// `docent check --format json BUNDLE` with `PATH` as given: exit status and problems.
fn check_with_path(bundle: &Path, path: &std::ffi::OsStr) -> (i32, Vec<Value>) {
    let output = Command::new(env!("CARGO_BIN_EXE_docent"))
        .args(["check", "--format", "json"])
        .arg(bundle)
        .env("PATH", path)
        .output()
        .expect("docent runs");
    let problems = serde_json::from_slice(&output.stdout).expect("JSON problems");
    (output.status.code().expect("an exit status"), problems)
}

#[test]
fn docent_check_asks_ffmpeg_and_says_when_it_is_missing() {
    let bundle =
        TempBundle::new("- Label: FILMS\n  Cmds:\n    - PROJECT good.mpg\n    - PROJECT cut.mov\n");
    cut_mov(&bundle.path().join("media/cut.mov"));
    mpeg1(&bundle.path().join("media/good.mpg"), 1, 440);
    let path = std::env::var_os("PATH").expect("PATH");

    let (status, problems) = check_with_path(bundle.path(), &path);
    let found: Vec<(&str, &str, u64)> = (problems.iter())
        .map(|p| {
            let code = p["code"].as_str().expect("code");
            (
                code,
                p["severity"].as_str().expect("severity"),
                p["line"].as_u64().expect("line"),
            )
        })
        .collect();
    assert_eq!(
        found,
        [
            ("media-converted", "note", 3),
            ("media-undecodable", "error", 4)
        ]
    );
    assert_eq!(status, 1, "a file ffmpeg cannot read is an error");
    let message = problems[1]["message"].as_str().expect("message");
    assert!(
        message.contains("ffmpeg cannot read it (moov atom not found"),
        "{message}"
    );

    // On a computer without ffmpeg the note becomes a warning saying what to install.
    let bare = tempfile::tempdir().expect("an empty PATH folder");
    let (_, problems) = check_with_path(bundle.path(), bare.path().as_os_str());
    let good = &problems[0];
    assert_eq!(
        (good["code"].as_str(), good["severity"].as_str()),
        (Some("media-converted"), Some("warning"))
    );
    assert!(
        good["message"]
            .as_str()
            .expect("message")
            .contains("sudo apt install ffmpeg"),
        "{good}"
    );
}

#[test]
fn docent_serve_without_ffmpeg_says_at_start_up_which_files_will_not_be_shown() {
    use std::io::{BufRead, BufReader, Read};
    let (bundle, _) = film_bundle(1);
    let corpus = tempfile::tempdir().expect("corpus");
    let bare = tempfile::tempdir().expect("an empty PATH folder");
    let mut child = Command::new(env!("CARGO_BIN_EXE_docent"))
        .args(common::process::serve_args(bundle.path(), corpus.path()))
        .env("PATH", bare.path())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("docent starts");
    let lines = BufReader::new(child.stdout.take().expect("stdout")).lines();
    let serving = (lines.map_while(Result::ok)).any(|l| l.trim().starts_with("websocket:"));
    assert!(serving, "docent serves");
    child.kill().expect("stop docent");
    let mut said = String::new();
    (child.stderr.take().expect("stderr"))
        .read_to_string(&mut said)
        .expect("read");
    child.wait().expect("reaped");
    let told: Vec<&str> = (said.lines())
        .filter(|l| l.contains("media/Exhibit/video.mpg will not be shown"))
        .collect();
    assert_eq!(told.len(), 1, "{said}");
    assert!(told[0].contains("sudo apt install ffmpeg"), "{said}");
}
