//! Reading a corpus folder back as a researcher would: every line of one run in `seq` order,
//! the session folders, a JSON Lines file.

use std::path::{Path, PathBuf};

use serde_json::Value;

/// Every line of a corpus folder holding one run (its day logs and session logs), parsed, in
/// `seq` order.
pub fn read_corpus(corpus: &Path) -> Vec<Value> {
    let mut lines: Vec<Value> = corpus_text(corpus)
        .lines()
        .map(|l| {
            serde_json::from_str(l).unwrap_or_else(|e| panic!("corpus line is not JSON ({e}): {l}"))
        })
        .collect();
    lines.sort_by_key(|e| e["seq"].as_u64());
    lines
}

/// The session folders of a corpus folder, oldest first (none before the first session).
pub fn session_dirs(corpus: &Path) -> Vec<PathBuf> {
    let mut dirs: Vec<PathBuf> = match std::fs::read_dir(corpus.join("sessions")) {
        Ok(entries) => entries.map(|e| e.expect("entry").path()).collect(),
        Err(_) => Vec::new(),
    };
    dirs.sort();
    dirs
}

/// Every line of a JSON Lines file, parsed.
pub fn json_lines(path: &Path) -> Vec<Value> {
    std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{path:?}: {e}"))
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("not JSON ({e}): {l}")))
        .collect()
}

/// The text of every event log in a corpus folder, one after the other.
pub fn corpus_text(corpus: &Path) -> String {
    (docent::corpus::layout::event_logs(corpus).expect("corpus folder"))
        .iter()
        .map(|log| std::fs::read_to_string(log).expect("corpus log"))
        .collect()
}
