//! `docent corpus purge`: a session removed completely and nothing else; refused while a
//! server in another process records it, taken once that server was killed; refused for
//! anything that is not a session folder of the corpus.

use std::path::PathBuf;

use crate::corpus_cli::recorded::{
    corpus_cmd, recorded_run, recording_server, sessions_by_number, snapshot, tour,
};

#[tokio::test]
async fn purge_removes_every_file_of_the_session_and_nothing_else() {
    let b = tour();
    let folder = tempfile::tempdir().unwrap();
    let corpus = folder.path();
    recorded_run(b.path(), corpus).await;
    let (name, dir) = sessions_by_number(corpus)[&1].clone();
    // What later slices will keep there: media in a folder of its own.
    std::fs::create_dir_all(dir.join("media")).unwrap();
    std::fs::write(dir.join("media/kiosk-0001.webm"), vec![7u8; 1500]).unwrap();
    let before = snapshot(corpus);
    let session = PathBuf::from("sessions").join(&name);
    let size = |f: &str| before[&session.join(f)].len();

    let (code, out, err) = corpus_cmd(corpus, &["purge", &name]);
    assert_eq!(code, 0, "{err}");
    let total = size("events.jsonl") + size("media/kiosk-0001.webm") + size("session.json");
    let expected = [
        format!(
            "removed sessions/{name}/events.jsonl  ({} bytes)",
            size("events.jsonl")
        ),
        format!("removed sessions/{name}/media/kiosk-0001.webm  (1500 bytes)"),
        format!(
            "removed sessions/{name}/session.json  ({} bytes)",
            size("session.json")
        ),
    ];
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(&lines[..3], &expected[..], "{out}");
    assert!(
        lines[3].starts_with(&format!("purged session {name}: 3 files, {total} bytes (")),
        "{out}"
    );
    assert!(
        lines[3].ends_with(&format!(
            "; sessions/{name} and 1 folder inside it removed with it, nothing else touched"
        )),
        "{out}"
    );
    assert!(!dir.exists());
    let mut rest = before;
    rest.retain(|path, _| !path.starts_with(&session));
    assert_eq!(snapshot(corpus), rest, "everything else is as it was");

    let (code, _, err) = corpus_cmd(corpus, &["purge", &name]);
    assert_eq!(code, 1);
    assert!(
        err.starts_with(&format!(
            "docent: no session {name} in {}",
            corpus.display()
        )),
        "{err}"
    );
}

#[tokio::test]
async fn purge_refuses_a_session_being_recorded_and_takes_it_once_its_server_was_killed() {
    let b = tour();
    let folder = tempfile::tempdir().unwrap();
    let corpus = folder.path();
    let (mut child, _op, running) = recording_server(b.path(), corpus).await;
    let name = running.file_name().unwrap().to_str().unwrap().to_owned();
    let before = snapshot(corpus);

    let (code, out, err) = corpus_cmd(corpus, &["purge", &name]);
    assert_eq!((code, out.as_str()), (1, ""));
    assert_eq!(
        err,
        format!(
            "docent: session {name} is being recorded by a running server (its events.jsonl is \
             locked): end the session from the operator console, or stop the server, then purge \
             it; nothing was removed\n"
        )
    );
    // The server still runs and may append (logs only grow): every file is still there,
    // holding at least what it held.
    let after = snapshot(corpus);
    assert_eq!(
        after.keys().collect::<Vec<_>>(),
        before.keys().collect::<Vec<_>>()
    );
    for (path, bytes) in &before {
        assert!(
            after[path].starts_with(bytes),
            "{} lost bytes",
            path.display()
        );
    }

    child.kill();
    let (code, out, err) = corpus_cmd(corpus, &["purge", &name]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains(&format!("removed sessions/{name}/events.jsonl  (")),
        "{out}"
    );
    assert!(!running.exists());
    assert!(corpus.join("days").exists(), "the day log stays");
}

#[tokio::test]
async fn purge_refuses_anything_but_a_session_folder_of_the_corpus() {
    let b = tour();
    let folder = tempfile::tempdir().unwrap();
    let corpus = folder.path();
    recorded_run(b.path(), corpus).await;
    let (name, dir) = sessions_by_number(corpus)[&1].clone();
    let elsewhere = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(elsewhere.path().join("sessions/x")).unwrap();
    std::fs::write(elsewhere.path().join("sessions/x/events.jsonl"), "{}\n").unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(
        elsewhere.path().join("sessions/x"),
        corpus.join("sessions/linked"),
    )
    .unwrap();
    let before = snapshot(corpus);
    let outside = snapshot(elsewhere.path());

    let not_a_session = |arg: &str| {
        format!(
            "docent: `{arg}` is not a session of {c}: name a session by its folder in {c}/sessions \
             (`docent corpus list` lists them), or give that folder's path\n",
            c = corpus.display()
        )
    };
    let other_corpus = elsewhere.path().join("sessions/x");
    let through_days = format!("{}/sessions/../days", corpus.display());
    for arg in [
        "..",
        "../x",
        "sessions/..",
        other_corpus.to_str().unwrap(),
        &through_days,
    ] {
        let (code, _, err) = corpus_cmd(corpus, &["purge", arg]);
        assert_eq!((code, err), (1, not_a_session(arg)), "{arg}");
    }
    let (code, _, err) = corpus_cmd(corpus, &["purge", "days"]);
    assert_eq!(
        (code, err),
        (
            1,
            format!(
                "docent: no session days in {}; `docent corpus list` lists the sessions\n",
                corpus.display()
            )
        )
    );
    // One letter short: no session has that name, and this one is the closest.
    let typo = name.trim_end_matches('Z').to_owned();
    let (code, _, err) = corpus_cmd(corpus, &["purge", &typo]);
    assert_eq!(code, 1);
    assert!(
        err.contains(&format!(
            "no session {typo} in {} (did you mean {name}?)",
            corpus.display()
        )),
        "{err}"
    );
    #[cfg(unix)]
    {
        let (code, _, err) = corpus_cmd(corpus, &["purge", "linked"]);
        assert_eq!(code, 1);
        assert!(
            err.contains("sessions/linked is a symbolic link, not a folder"),
            "{err}"
        );
    }
    assert_eq!(snapshot(corpus), before, "nothing in the corpus removed");
    assert_eq!(
        snapshot(elsewhere.path()),
        outside,
        "nothing outside it removed"
    );
    assert!(dir.exists());
}
