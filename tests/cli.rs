//! The `docent` command line: `check` exit codes and JSON output, `serve` refusing a broken
//! bundle, and every shipped bundle passing the check.

use crate::common;

use std::process::Command;

use common::process::run_docent;
use common::{TempBundle, repo};
use serde_json::Value;

#[test]
fn every_shipped_bundle_passes_the_check() {
    for bundle in [
        "paper-fig4",
        "info-terminal",
        "museum-tour",
        "poster-presenter",
    ] {
        let path = format!("dialogs/{bundle}");
        let (code, out, _) = run_docent(&["check", &path, "--format", "json", "--deny-warnings"]);
        let problems: Vec<Value> = serde_json::from_str(&out).unwrap();
        // Only notes: the paper's own MPEG-1 film, converted when served.
        let notes: Vec<(&str, &str)> = (problems.iter())
            .map(|p| (p["severity"].as_str().unwrap(), p["code"].as_str().unwrap()))
            .collect();
        let expected: &[(&str, &str)] = if bundle == "paper-fig4" {
            &[("note", "media-converted")]
        } else {
            &[]
        };
        assert_eq!((code, notes.as_slice()), (0, expected), "{bundle}: {out}");
    }
}

pub(crate) const BROKEN: &str =
    "- Label: A\n  Text: [Hello]\n  Cmds:\n    - SAYY Hi\n    - DISPLAY_PAGE nowhere.html\n";

#[test]
fn check_lists_problems_with_places_and_exits_1() {
    let b = TempBundle::new(BROKEN);
    let (code, out, _) = run_docent(&["check", b.path().to_str().unwrap(), "--format", "json"]);
    assert_eq!(code, 1);
    // A, offered by no page, is the operator's (no act has a `Group`): not a problem.
    let problems: Vec<Value> = serde_json::from_str(&out).unwrap();
    assert_eq!(problems.len(), 2, "{out}");
    for p in &problems {
        let keys: Vec<&str> = p.as_object().unwrap().keys().map(String::as_str).collect();
        for key in ["severity", "code", "message", "file", "line", "column"] {
            assert!(keys.contains(&key), "{key} missing in {p}");
        }
        assert_eq!(
            (p["severity"].as_str(), p["file"].as_str()),
            (Some("error"), Some("acts.yaml"))
        );
    }
    assert_eq!(
        (
            problems[0]["code"].as_str(),
            problems[0]["line"].as_u64(),
            problems[0]["column"].as_u64()
        ),
        (Some("unknown-verb"), Some(4), Some(7))
    );
    assert!(
        problems[0]["message"].as_str().unwrap().contains("SAY"),
        "did you mean SAY: {}",
        problems[0]
    );
    assert_eq!(
        (problems[1]["code"].as_str(), problems[1]["line"].as_u64()),
        (Some("missing-file"), Some(5))
    );

    let (code, text, _) = run_docent(&["check", b.path().to_str().unwrap()]);
    assert_eq!(code, 1);
    // The human form: what happened, the place, the line with a caret, the hint.
    for expected in [
        "error[unknown-verb]: `SAYY` is not a command Docent knows.",
        "--> acts.yaml:4:7",
        "4 |     - SAYY Hi",
        "  |       ^^^^",
        "= help: Did you mean `SAY`?",
    ] {
        assert!(text.contains(expected), "{expected:?} in:\n{text}");
    }
    assert!(
        !text.contains("\u{1b}["),
        "no colours when not on a terminal"
    );
    assert!(text.contains("2 error(s), 0 warning(s)"), "{text}");
}

#[test]
fn check_warns_about_a_language_no_installed_espeak_voice_speaks() {
    // The start-up check and `docent check` share one rule (content::voices).
    let b = TempBundle::new("- Label: A\n  Text: [Hello]\n  Text@de: [Hallo]\n  Key: A\n")
        .with_file(
            "pages/index.html",
            "<!doctype html><title>Start</title><button data-language=\"de\">Deutsch</button>",
        )
        .with_file("pages/de/index.html", "<!doctype html><title>Start</title>")
        .with_file(
            "docent.yaml",
            "languages: [en, de]\nspeech:\n  adapter: espeak\n  voices: {en: en, de: zz-nowhere}\n",
        );
    let (_, out, _) = run_docent(&["check", b.path().to_str().unwrap(), "--format", "json"]);
    let problems: Vec<Value> = serde_json::from_str(&out).unwrap();
    let found: Vec<(&str, &str, &str, u64, u64)> = (problems.iter())
        .map(|p| {
            let text = |k: &str| p[k].as_str().unwrap_or_default();
            let number = |k: &str| p[k].as_u64().unwrap_or_default();
            (
                text("code"),
                text("severity"),
                text("file"),
                number("line"),
                number("column"),
            )
        })
        .collect();
    assert_eq!(
        found,
        [("no-voice", "warning", "docent.yaml", 4, 20)],
        "{out}"
    );
    assert!(
        problems[0]["message"]
            .as_str()
            .unwrap()
            .contains("zz-nowhere")
    );
}

#[test]
fn deny_warnings_fails_a_bundle_with_only_warnings() {
    // B has a `Group` for the operator, A none and no page: A draws the one warning.
    let b = TempBundle::new("- Label: A\n  Text: [Hello]\n- Label: B\n  Group: G\n  Text: [Hi]\n");
    let path = b.path().to_str().unwrap();
    let (code, text, _) = run_docent(&["check", path]);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("warning[unused-act]"), "{text}");
    let (code, text, _) = run_docent(&["check", path, "--deny-warnings"]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("0 error(s), 1 warning(s)"), "{text}");
}

#[test]
fn a_bundle_copied_from_a_mac_passes_deny_warnings_with_a_note_on_what_was_ignored() {
    let b = TempBundle::new("- Label: WELCOME\n  Text: [Hello]\n");
    let forks = common::mac_copy::as_copied_from_a_mac(b.path());
    assert_eq!(forks, 4, "acts.yaml, pages, media, pages/index.html");
    let path = b.path().to_str().unwrap();

    let (code, text, _) = run_docent(&["check", path, "--deny-warnings"]);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("note[ignored-files]"), "{text}");
    assert!(
        text.contains("0 error(s), 0 warning(s), 1 note(s)"),
        "{text}"
    );

    let (code, out, _) = run_docent(&["check", path, "--format", "json", "--deny-warnings"]);
    assert_eq!(code, 0, "{out}");
    let problems: Vec<Value> = serde_json::from_str(&out).unwrap();
    assert_eq!(problems.len(), 1, "{out}");
    assert_eq!(
        (&problems[0]["severity"], &problems[0]["code"]),
        (&Value::from("note"), &Value::from("ignored-files")),
        "{out}"
    );
    assert_eq!(problems[0]["file"], ".DS_Store", "{out}");
    assert_eq!(
        (&problems[0]["line"], &problems[0]["column"]),
        (&1.into(), &1.into())
    );

    // A warning beside the note still fails it: notes are left out, not warnings.
    std::fs::write(
        b.path().join("acts.yaml"),
        "- Label: WELCOME\n  Text: [Hello]\n- Label: B\n  Group: G\n  Text: [Hi]\n",
    )
    .unwrap();
    let (code, text, _) = run_docent(&["check", path, "--deny-warnings"]);
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("0 error(s), 1 warning(s), 1 note(s)"),
        "{text}"
    );
}

#[test]
fn serve_refuses_a_bundle_with_errors_and_lists_them() {
    let b = TempBundle::new(BROKEN);
    let (code, out, err) = run_docent(&[
        "serve",
        b.path().to_str().unwrap(),
        "--listen",
        "127.0.0.1:0",
    ]);
    assert_eq!(code, 1);
    assert!(
        out.contains("error[unknown-verb]") && out.contains("error[missing-file]"),
        "{out}"
    );
    assert!(err.contains("2 error(s)"), "{err}");
}

#[test]
fn a_missing_bundle_folder_is_a_clear_error() {
    let (code, out, _) = run_docent(&["check", "/no/such/bundle"]);
    assert_eq!(code, 1);
    assert!(
        out.contains("/no/such/bundle") || out.contains("bundle"),
        "{out}"
    );
}

#[test]
fn a_port_in_use_is_told_with_what_to_do() {
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = taken.local_addr().unwrap().port();
    let listen = format!("127.0.0.1:{port}");
    let out = serve_without_credentials(&["--listen", &listen, "--open", "--no-watch"])
        .output()
        .unwrap();
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains(&format!("another program already uses port {port}")),
        "{err}"
    );
    assert!(
        err.contains(&format!("--listen 127.0.0.1:{}", port + 1)),
        "{err}"
    );
}

#[test]
fn a_folder_of_bundles_is_told_with_the_path_to_give_instead() {
    let (code, out, _) = run_docent(&["check", "dialogs"]);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("error[not-a-bundle]"), "{out}");
    assert!(out.contains("`dialogs` is a folder of bundles"), "{out}");
    assert!(out.contains("`museum-tour`"), "{out}");
    assert!(out.contains("for example `dialogs/"), "{out}");
    // One error, not a misplaced acts file and a missing home page besides.
    assert_eq!(out.matches("error[").count(), 1, "{out}");
    assert!(!out.contains("warning["), "{out}");
}

#[test]
fn preview_serves_both_screens_and_speaks_in_the_browser() {
    use std::io::{BufRead, BufReader};
    let mut child = Command::new(env!("CARGO_BIN_EXE_docent"))
        .args([
            "serve",
            "dialogs/paper-fig4",
            "--listen",
            "127.0.0.1:0",
            "--preview",
            "--corpus",
        ])
        .arg(tempfile::tempdir().unwrap().keep())
        .current_dir(repo())
        .env("PATH", "/nonexistent") // no xdg-open: the preview is only printed
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let lines: Vec<String> = BufReader::new(child.stdout.take().unwrap())
        .lines()
        .map_while(Result::ok)
        .take_while(|l| !l.contains("open it in a browser"))
        .collect();
    let preview = lines
        .iter()
        .find(|l| l.trim().starts_with("preview:"))
        .expect("a preview line");
    let url = preview.split_whitespace().nth(1).unwrap().to_owned();
    let page = reqwest::blocking_get(&url);
    assert!(page.contains("<iframe src=\"/?preview\""), "{page}");
    assert!(page.contains("<iframe src=\"/projector\""), "{page}");
    let kiosk = reqwest::blocking_get(&url.replace("/preview", "/"));
    assert!(kiosk.contains("data-speech=\"browser\""), "{kiosk}");
    child.kill().unwrap();
    child.wait().unwrap();
}

mod reqwest {
    /// A GET with a fresh runtime (this test is synchronous).
    pub fn blocking_get(url: &str) -> String {
        let rt = tokio::runtime::Runtime::new().unwrap();
        rt.block_on(async { ::reqwest::get(url).await.unwrap().text().await.unwrap() })
    }
}

/// `docent serve` with the credential variables removed from its environment.
fn serve_without_credentials(extra: &[&str]) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_docent"));
    command
        .args(["serve", "dialogs/paper-fig4"])
        .args(extra)
        .current_dir(repo())
        .env_remove("DOCENT_OPERATOR_TOKEN")
        .env_remove("DOCENT_DM_TOKEN");
    command
}

#[test]
fn serve_refuses_a_network_address_without_a_chosen_credential_or_with_open() {
    for extra in [
        &["--listen", "0.0.0.0:0"][..],
        &["--listen", "0.0.0.0:0", "--open"],
    ] {
        let out = serve_without_credentials(extra).output().unwrap();
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(1), "{extra:?}: {err}");
        assert!(
            err.contains("DOCENT_OPERATOR_TOKEN") || err.contains("--open is for development"),
            "{extra:?}: {err}"
        );
    }
    let out = serve_without_credentials(&["--listen", "127.0.0.1:0"])
        .env("DOCENT_OPERATOR_TOKEN", "short")
        .output()
        .unwrap();
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("at least 16"), "{err}");
    assert!(!err.contains("short\""), "{err}");
}

#[test]
fn a_generated_credential_is_printed_once_and_works_but_is_never_logged() {
    use std::io::{BufRead, BufReader};
    let corpus = tempfile::tempdir().unwrap();
    let log = tempfile::NamedTempFile::new().unwrap();
    let mut child = serve_without_credentials(&["--listen", "127.0.0.1:0", "--corpus"])
        .arg(corpus.path())
        .env("RUST_LOG", "debug")
        .stdout(std::process::Stdio::piped())
        .stderr(log.reopen().unwrap())
        .spawn()
        .unwrap();
    let lines: Vec<String> = BufReader::new(child.stdout.take().unwrap())
        .lines()
        .map_while(Result::ok)
        .take_while(|l| !l.contains("dialog manager credential"))
        .collect();
    let line = |prefix: &str| {
        let found = lines.iter().find(|l| l.trim().starts_with(prefix));
        found
            .unwrap_or_else(|| panic!("no {prefix} line in {lines:?}"))
            .clone()
    };
    let token = line("operator credential")
        .rsplit(' ')
        .next()
        .unwrap()
        .to_owned();
    assert_eq!(token.len(), 32, "{token}");
    let api = line("trigger API:");
    let base = api
        .split_whitespace()
        .nth(2)
        .unwrap()
        .trim_end_matches("/api/acts");
    let rt = tokio::runtime::Runtime::new().unwrap();
    let status = |token: &str| {
        rt.block_on(async {
            let request = ::reqwest::Client::new()
                .post(format!("{base}/api/acts/WELCOME/trigger"))
                .bearer_auth(token);
            request.send().await.unwrap().status().as_u16()
        })
    };
    assert_eq!(status("not-it-at-all-000"), 401);
    assert_eq!(status(&token), 202);
    // SIGTERM: a graceful stop flushes the corpus.
    let term = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status();
    assert!(term.unwrap().success());
    assert!(child.wait().unwrap().success());
    let logged = std::fs::read_to_string(log.path()).unwrap();
    assert!(!logged.is_empty(), "debug logging wrote something");
    assert!(
        !logged.contains('\u{1b}'),
        "a log file gets no colour codes: {logged}"
    );
    for page in ["/preview", "/report", "/sessions"] {
        assert!(
            lines.iter().any(|l| l.contains(&format!("{base}{page}"))),
            "the start-up text names {page}: {lines:?}"
        );
    }
    assert!(!logged.contains(&token), "the log holds the credential");
    for file in docent::corpus::layout::event_logs(corpus.path()).unwrap() {
        let text = std::fs::read_to_string(file).unwrap();
        assert!(text.contains("act.triggered"), "{text}");
        assert!(!text.contains(&token), "the corpus holds the credential");
    }
}

#[test]
fn check_read_only_in_part_ends_quietly_with_its_status() {
    // `docent check BUNDLE | head -3`: the reader stops early; the check must not panic.
    use std::io::{BufRead, BufReader};
    // More problems than a pipe holds (64 KiB), so the writes after the reader left fail.
    let acts: String = (0..2000)
        .map(|n| format!("- Label: A{n}\n  Cmds:\n    - SAYY Hi\n"))
        .collect();
    let b = TempBundle::new(&acts);
    let mut child = Command::new(env!("CARGO_BIN_EXE_docent"))
        .args(["check", b.path().to_str().unwrap()])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    let mut reader = BufReader::new(child.stdout.take().unwrap());
    reader.read_line(&mut first).unwrap();
    assert!(first.starts_with("error["), "{first}");
    drop(reader);
    let output = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(output.status.code(), Some(1), "{stderr}");
}
