//! `docent corpus list | show | purge`, the real binary run against a corpus that real
//! servers recorded: sessions ended (marked, and by a shutdown), one being recorded by a
//! server in another process (which holds its log's lock), one that server left open when it
//! was killed with SIGKILL, and hand-made damaged folders. Outputs, exit codes and the files
//! left behind are checked; nothing is mocked. The corpus is made in `corpus_cli/recorded.rs`;
//! the purge cases are in `corpus_cli/purge_cases.rs`.

#[path = "corpus_cli/purge_cases.rs"]
mod purge_cases;
#[path = "corpus_cli/recorded.rs"]
mod recorded;

use docent::corpus::annotations::{Draft, Edit, append};
use docent::corpus::manifest::SessionManifest;
use recorded::{
    corpus_cmd, damaged_sessions, events, events_by_type, recorded_run, recording_server,
    sessions_by_number, tour,
};
use serde_json::Value;

/// The rows of `list` as columns (split on two spaces or more), header and summary left out.
fn rows(out: &str) -> Vec<Vec<String>> {
    let lines: Vec<&str> = out.lines().collect();
    assert!(lines[0].starts_with("SESSION"), "{out}");
    lines[1..lines.len() - 1]
        .iter()
        .map(|l| {
            l.split("  ")
                .map(str::trim)
                .filter(|c| !c.is_empty())
                .map(str::to_owned)
                .collect()
        })
        .collect()
}

#[tokio::test]
async fn list_gives_each_session_its_state_events_and_group_oldest_first() {
    let b = tour();
    let folder = tempfile::tempdir().unwrap();
    let corpus = folder.path();
    recorded_run(b.path(), corpus).await;
    let recorded = sessions_by_number(corpus);
    let (a_name, a_dir) = recorded[&1].clone();
    let (b_name, b_dir) = recorded[&2].clone();
    let (bad, bare) = damaged_sessions(corpus, &a_dir);
    let (mut child, _op, running) = recording_server(b.path(), corpus).await;
    let c_name = running.file_name().unwrap().to_str().unwrap().to_owned();
    let c_events = events(&running.join("events.jsonl")).to_string();

    let (code, out, err) = corpus_cmd(corpus, &["list"]);
    assert_eq!(code, 0, "{err}");
    let table = rows(&out);
    let names: Vec<&str> = table.iter().map(|r| r[0].as_str()).collect();
    assert_eq!(
        names,
        [
            "2000-01-01T00-00-00Z",
            "2000-01-01T00-00-00Z-1",
            &a_name,
            &b_name,
            &c_name
        ]
    );
    let a_events = events(&a_dir.join("events.jsonl")).to_string();
    let b_events = events(&b_dir.join("events.jsonl")).to_string();
    // Columns: name, start, duration, state, events, group[, problem].
    let (a, b_row, c) = (&table[2], &table[3], &table[4]);
    assert_eq!(
        (a[3].as_str(), &a[4], a[5].as_str()),
        ("ended", &a_events, "children")
    );
    assert_eq!(
        (b_row[3].as_str(), &b_row[4], b_row[5].as_str()),
        ("ended", &b_events, "-")
    );
    assert_eq!(
        (c[2].as_str(), c[3].as_str(), &c[4], c[5].as_str()),
        ("open", "recording", &c_events, "group")
    );
    let manifest = SessionManifest::read_from(&a_dir).unwrap();
    assert_eq!(a[1], manifest.started.time[..19].replacen('T', " ", 1));
    assert!(a[2].ends_with('s'), "a duration: {a:?}");
    let bad_row = &table[0];
    assert_eq!(
        (
            bad_row[3].as_str(),
            bad_row[5].as_str(),
            bad_row[6].as_str()
        ),
        (
            "damaged",
            "children",
            "events.jsonl:3: a JSON line cut short at column 24"
        )
    );
    assert_eq!(bad_row[4], a_events, "the bad line is not an event");
    let bare_row = &table[1];
    assert_eq!(
        (
            bare_row[1].as_str(),
            bare_row[3].as_str(),
            bare_row[6].as_str()
        ),
        (a[1].as_str(), "damaged", "session.json is missing")
    );
    let summary = out.lines().last().unwrap();
    assert!(
        summary.starts_with("5 sessions (2 ended, 1 recording, 2 damaged), 2 day logs, "),
        "{summary}"
    );
    assert!(
        summary.ends_with(&format!(" in {}", corpus.display())),
        "{summary}"
    );

    child.kill();
    let (code, out, _) = corpus_cmd(corpus, &["list"]);
    assert_eq!(code, 0);
    let c = &rows(&out)[4];
    assert_eq!(
        (c[2].as_str(), c[3].as_str(), &c[4]),
        ("interrupted", "interrupted", &c_events)
    );
    assert!(
        out.contains("5 sessions (2 ended, 1 interrupted, 2 damaged), 2 day logs, "),
        "{out}"
    );
    drop((bad, bare));
}

#[tokio::test]
async fn show_tells_a_session_in_words_with_its_events_by_type_and_its_files() {
    let b = tour();
    let folder = tempfile::tempdir().unwrap();
    let corpus = folder.path();
    recorded_run(b.path(), corpus).await;
    let (name, dir) = sessions_by_number(corpus)[&1].clone();
    let manifest = SessionManifest::read_from(&dir).unwrap();
    let ended = manifest.ended.clone().unwrap();
    let log = dir.join("events.jsonl");
    let last: Value = serde_json::from_str(
        std::fs::read_to_string(&log)
            .unwrap()
            .lines()
            .last()
            .unwrap(),
    )
    .unwrap();

    let (code, out, err) = corpus_cmd(corpus, &["show", &name]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    let by_type = events_by_type(&log);
    let mut expected = vec![
        format!("session   {name}"),
        format!("folder    {}", dir.display()),
        "state     ended".to_owned(),
        format!("bundle    {}", manifest.bundle.clone().unwrap()),
        format!("content   {}", manifest.bundle_hash.clone().unwrap()),
        format!("docent    {}", env!("CARGO_PKG_VERSION")),
        format!("started   {} by operator", manifest.started.time),
        format!("ended     {} by operator (its end was marked)", ended.time),
        "group     children".to_owned(),
        "context   TextChild".to_owned(),
        "consent   recorded".to_owned(),
    ];
    let us = last["session_us"].as_u64().unwrap();
    assert_eq!(us, ended.mono_us - manifest.started.mono_us);
    assert_eq!(&lines[..expected.len()], &expected[..], "{out}");
    let duration = lines[expected.len()];
    assert!(
        duration.starts_with("duration  ")
            && duration.ends_with("s (on the session clock: session_us of its last line)"),
        "{duration}"
    );
    expected.clear();
    expected.push(format!("events    {}", by_type.values().sum::<u64>()));
    let width = by_type.keys().map(String::len).max().unwrap();
    expected.extend(
        by_type
            .iter()
            .map(|(kind, n)| format!("  {kind:<width$}  {n:>6}")),
    );
    expected.push("files".to_owned());
    let sizes =
        ["events.jsonl", "session.json"].map(|f| std::fs::metadata(dir.join(f)).unwrap().len());
    expected.push(format!("  events.jsonl  {:>10} bytes", sizes[0]));
    expected.push(format!("  session.json  {:>10} bytes", sizes[1]));
    expected.push(format!("  2 files, {} bytes", sizes[0] + sizes[1]));
    let start = lines.len() - expected.len();
    assert_eq!(&lines[start..], &expected[..], "{out}");
    assert_eq!(by_type["act.triggered"], 2);

    // The folder's path names the same session.
    let (code, by_path, _) = corpus_cmd(corpus, &["show", dir.to_str().unwrap()]);
    assert_eq!((code, by_path), (0, out));

    // Its recording and researchers' annotations, said after the consent.
    let mut with_media: Value =
        serde_json::from_slice(&std::fs::read(dir.join("session.json")).unwrap()).unwrap();
    with_media["media"] = serde_json::json!([{"file": "media/audio-1.webm", "track": "audio",
        "mime": "audio/webm;codecs=opus", "start_us": 734_000, "recording": 1}]);
    std::fs::write(dir.join("session.json"), with_media.to_string()).unwrap();
    let draft = |code: &str| Draft {
        tier: "situation".into(),
        code: code.into(),
        start_us: 0,
        end_us: 0,
        annotator: None,
    };
    let time = || "2026-11-24T13:00:00Z".to_owned();
    append(&dir, Edit::Add(draft("question")), time()).unwrap();
    append(&dir, Edit::Add(draft("laughter")), time()).unwrap();
    append(&dir, Edit::Delete("a1".into()), time()).unwrap();
    let (code, out, err) = corpus_cmd(corpus, &["show", &name]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    let consent = lines.iter().position(|l| l.starts_with("consent")).unwrap();
    assert_eq!(
        lines[consent + 1..consent + 3],
        [
            "media     media/audio-1.webm (audio, its first sample at 0.734s on the session clock)",
            "annotations 1 annotation (annotations.jsonl)",
        ],
        "{out}"
    );
}

#[tokio::test]
async fn show_of_a_damaged_session_says_what_is_wrong_and_what_it_still_knows() {
    let b = tour();
    let folder = tempfile::tempdir().unwrap();
    let corpus = folder.path();
    recorded_run(b.path(), corpus).await;
    let (_, model) = sessions_by_number(corpus)[&1].clone();
    let manifest = SessionManifest::read_from(&model).unwrap();
    damaged_sessions(corpus, &model);

    let (code, out, err) = corpus_cmd(corpus, &["show", "2000-01-01T00-00-00Z"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("\nstate     damaged (see the problems below)\n"),
        "{out}"
    );
    assert!(
        out.ends_with("problems\n  events.jsonl:3: a JSON line cut short at column 24\n"),
        "{out}"
    );

    let (code, out, _) = corpus_cmd(corpus, &["show", "2000-01-01T00-00-00Z-1"]);
    assert_eq!(code, 0);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines[3], "manifest  none readable (see the problems below)");
    assert_eq!(
        lines[4],
        format!("started   {} (from its first line)", manifest.started.time)
    );
    assert_eq!(lines[5], "ended     its log's last line ends it");
    assert!(
        out.ends_with("problems\n  session.json is missing\n"),
        "{out}"
    );
}

#[test]
fn a_missing_corpus_is_an_error_naming_it_and_an_empty_one_is_said_plainly() {
    let folder = tempfile::tempdir().unwrap();
    let missing = folder.path().join("no-corpus-here");
    for args in [&["list"][..], &["show", "x"], &["purge", "x"]] {
        let (code, out, err) = corpus_cmd(&missing, args);
        assert_eq!((code, out.as_str()), (1, ""), "{args:?}");
        assert!(
            err.starts_with(&format!(
                "docent: there is no corpus folder at {}: ",
                missing.display()
            )),
            "{err}"
        );
    }
    let (code, out, _) = corpus_cmd(folder.path(), &["list"]);
    assert_eq!(
        (code, out),
        (
            0,
            format!(
                "no sessions in {} (0 day logs, 0 B)\n",
                folder.path().display()
            )
        )
    );
    std::fs::create_dir_all(folder.path().join("days/2026-11-24")).unwrap();
    std::fs::write(
        folder.path().join("days/2026-11-24/09-12-00Z.jsonl"),
        vec![b'\n'; 100],
    )
    .unwrap();
    let (code, out, _) = corpus_cmd(folder.path(), &["list"]);
    assert_eq!(
        (code, out),
        (
            0,
            format!(
                "no sessions in {} (1 day log, 100 B)\n",
                folder.path().display()
            )
        )
    );
}

#[tokio::test]
async fn export_writes_a_sessions_files_and_all_passes_over_one_recorded_and_names_a_damaged_one() {
    let b = tour();
    let folder = tempfile::tempdir().unwrap();
    let corpus = folder.path();
    recorded_run(b.path(), corpus).await;
    let recorded = sessions_by_number(corpus);
    let (a_name, a_dir) = recorded[&1].clone();

    let (code, out, err) = corpus_cmd(corpus, &["export", &a_name, "--format", "eaf,csv,mcap"]);
    assert_eq!(code, 0, "{err}");
    for extension in ["eaf", "csv", "mcap"] {
        let file = a_dir.join("exports").join(format!("{a_name}.{extension}"));
        assert!(file.is_file(), "{file:?}: {out}");
        assert!(out.contains(&format!("wrote {}", file.display())), "{out}");
    }
    assert!(out.ends_with("exported 3 files\n"), "{out}");

    let (bad, _bare) = damaged_sessions(corpus, &a_dir);
    let (mut child, _op, running) = recording_server(b.path(), corpus).await;
    let running_name = running.file_name().unwrap().to_str().unwrap().to_owned();
    let bad_name = bad.file_name().unwrap().to_str().unwrap().to_owned();
    let out_dir = folder.path().join("for-elan");
    let (code, out, err) = corpus_cmd(
        corpus,
        &[
            "export",
            "--all",
            "--format",
            "textgrid",
            "--out",
            out_dir.to_str().unwrap(),
        ],
    );
    child.kill();
    assert_eq!(code, 1, "a damaged session fails the run: {out}");
    assert!(
        out.contains(&format!("{running_name}: being recorded, passed over")),
        "{out}"
    );
    assert!(out.contains(&format!("{bad_name}: not exported:")), "{out}");
    assert!(err.contains(&bad_name), "{err}");
    let (_, b_dir) = recorded[&2].clone();
    for dir in [&a_dir, &b_dir] {
        let name = dir.file_name().unwrap().to_str().unwrap();
        assert!(out_dir.join(format!("{name}.TextGrid")).is_file(), "{out}");
    }
    assert!(!out_dir.join(format!("{running_name}.TextGrid")).exists());

    let (code, _, err) = corpus_cmd(corpus, &["export", "--format", "csv"]);
    assert_eq!(code, 2, "no session and no --all: {err}");
}
