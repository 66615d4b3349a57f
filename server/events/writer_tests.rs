//! The hub and the corpus crate's writer together: every event published is a line in
//! sequence order, an acknowledged one is in the file, and after the writer stopped an
//! acknowledgement is refused.

use std::path::Path;
use std::time::Duration;

use crate::corpus::{CorpusWriter, DEFAULT_SYNC_INTERVAL, layout};
use crate::events::{EventKind, Hub, Logged, Source};
use docent_corpus::Feed;

/// Waits for the writer thread on a blocking thread, as the server does.
async fn finish(writer: CorpusWriter) -> std::io::Result<u64> {
    tokio::task::spawn_blocking(move || writer.finish())
        .await
        .unwrap()
}

fn context(n: usize) -> EventKind {
    EventKind::ContextChanged {
        source: Source::Http,
        context: format!("T{n}"),
    }
}

/// The `seq` of every line in the corpus folder, in file order.
fn seqs(corpus: &Path) -> Vec<u64> {
    let mut seqs = Vec::new();
    for log in layout::event_logs(corpus).unwrap() {
        let text = std::fs::read_to_string(log).unwrap();
        seqs.extend(text.lines().map(|l| {
            serde_json::from_str::<serde_json::Value>(l).unwrap()["seq"]
                .as_u64()
                .unwrap()
        }));
    }
    seqs
}

#[tokio::test]
async fn every_published_event_is_a_json_line_in_sequence_order() {
    let dir = tempfile::tempdir().unwrap();
    let (hub, feed) = Hub::new();
    let writer = CorpusWriter::start(dir.path(), feed, DEFAULT_SYNC_INTERVAL).unwrap();
    for n in 0..100 {
        hub.publish(context(n));
    }
    let corpus = writer.dir().to_owned();
    hub.close_corpus();
    assert_eq!(finish(writer).await.unwrap(), 100);
    assert_eq!(seqs(&corpus), (1..=100).collect::<Vec<_>>());
}

#[tokio::test]
async fn an_event_is_in_the_file_when_logged_returns() {
    let dir = tempfile::tempdir().unwrap();
    let (hub, feed) = Hub::new();
    // A long sync interval: what is read back was written, not synced.
    let writer = CorpusWriter::start(dir.path(), feed, Duration::from_secs(3600)).unwrap();
    for round in 1..=50u64 {
        let event = hub.publish(context(round as usize));
        hub.logged(event.seq).await.unwrap();
        // Read back while the writer still runs.
        assert_eq!(seqs(writer.dir()), (1..=round).collect::<Vec<_>>());
    }
    hub.close_corpus();
    finish(writer).await.unwrap();
}

#[tokio::test]
async fn after_the_writer_stopped_an_acknowledgement_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let (hub, feed) = Hub::new();
    let writer = CorpusWriter::start(dir.path(), feed, DEFAULT_SYNC_INTERVAL).unwrap();
    hub.close_corpus();
    finish(writer).await.unwrap();
    let late = hub.publish(context(1));
    let refused = hub.logged(late.seq).await.unwrap_err();
    assert!(
        refused
            .to_string()
            .contains("the corpus writer has stopped")
    );
    assert!(hub.log_failure().is_some());
}

#[tokio::test]
async fn a_failure_the_writer_reports_refuses_acknowledgements_in_words() {
    let (hub, feed) = Hub::new();
    let event = hub.publish(context(1));
    feed.report(Logged {
        through: 0,
        failure: Some("No space left on device (os error 28)".into()),
        ..Logged::default()
    });
    let refused = hub.logged(event.seq).await.unwrap_err();
    assert!(
        refused.to_string().contains("No space left on device"),
        "{refused}"
    );
    let failure = hub.log_failure().expect("triggers are refused");
    assert!(
        failure
            .refusal()
            .starts_with("not triggered: the corpus log cannot be written")
    );
}
