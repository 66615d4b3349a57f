//! ARCHITECTURE.md stays the true map of the code: every file under `server/`, `static/` and
//! `pages/` is named in it, and every file path it writes in backticks still exists. A file
//! added without its clause in the codemap, or a file renamed or deleted under the map's feet,
//! fails here with the list of what to fix.
//!
//! Unit-test files (`tests.rs`, `*_tests.rs`) are exempt: the codemap says in one sentence
//! where unit tests live. A `mod.rs` is covered by its folder (`access/`); a file name that two
//! mapped files share (`writer.rs` in `corpus/` and `ws/`) must be written with its folder
//! (`corpus/writer.rs`), since the bare name would not tell which one the map describes.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};

/// The folders whose every file the codemap must name.
const MAPPED: [&str; 3] = ["server", "static", "pages"];

/// Extensions of the backticked paths in ARCHITECTURE.md that must name a real file.
const CODE_EXTENSIONS: [&str; 7] = ["rs", "js", "mjs", "html", "css", "sh", "py"];

/// Folders never walked: build output, installed packages, git and editor state.
fn skipped_dir(name: &str) -> bool {
    name == "target" || name == "node_modules" || name.starts_with('.')
}

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn architecture() -> String {
    let path = repo().join("ARCHITECTURE.md");
    fs::read_to_string(&path).unwrap_or_else(|e| panic!("reading {}: {e}", path.display()))
}

/// Every file under `dir` (recursively), as paths relative to the repository with `/`.
fn files_under(dir: &Path) -> Vec<String> {
    let mut found = Vec::new();
    let mut pending: Vec<PathBuf> = vec![dir.to_path_buf()];
    while let Some(dir) = pending.pop() {
        let entries =
            fs::read_dir(&dir).unwrap_or_else(|e| panic!("listing {}: {e}", dir.display()));
        for entry in entries {
            let entry = entry.unwrap_or_else(|e| panic!("listing {}: {e}", dir.display()));
            let name = entry.file_name().to_string_lossy().into_owned();
            let kind = entry
                .file_type()
                .unwrap_or_else(|e| panic!("file type of {}: {e}", entry.path().display()));
            if kind.is_dir() {
                if !skipped_dir(&name) {
                    pending.push(entry.path());
                }
            } else if kind.is_file() && !name.starts_with('.') {
                let relative = entry
                    .path()
                    .strip_prefix(repo())
                    .unwrap_or_else(|e| panic!("{} is outside the repo: {e}", dir.display()))
                    .to_string_lossy()
                    .replace('\\', "/");
                found.push(relative);
            }
        }
    }
    found.sort();
    found
}

fn file_name(path: &str) -> &str {
    path.rsplit('/').next().unwrap_or(path)
}

fn is_unit_test_file(path: &str) -> bool {
    let name = file_name(path);
    name == "tests.rs" || name.ends_with("_tests.rs")
}

/// What ARCHITECTURE.md must contain for `path`: its folder for a `mod.rs`, its folder and name
/// for a name another mapped file shares, else its name.
fn needle(path: &str, shared: &BTreeMap<&str, usize>) -> String {
    let name = file_name(path);
    let mut parts = path.rsplit('/');
    parts.next();
    let parent = parts.next().unwrap_or("");
    let at_top = MAPPED.contains(&parent) && parts.next().is_none();
    if name == "mod.rs" {
        return format!("{parent}/");
    }
    if shared.get(name).copied().unwrap_or(0) > 1 {
        // A top-level file is written bare (`sync.rs`), so ask for it in backticks, where a
        // deeper file's path (`corpus/sync.rs`) cannot stand in for it.
        return if at_top {
            format!("`{name}`")
        } else {
            format!("{parent}/{name}")
        };
    }
    name.to_string()
}

/// The files under the mapped folders that ARCHITECTURE.md does not name, each with what it
/// was looked for as.
fn unmapped(map: &str) -> Vec<String> {
    let files: Vec<String> = MAPPED
        .iter()
        .flat_map(|dir| files_under(&repo().join(dir)))
        .filter(|path| !is_unit_test_file(path))
        .collect();
    let mut shared: BTreeMap<&str, usize> = BTreeMap::new();
    for path in &files {
        *shared.entry(file_name(path)).or_default() += 1;
    }
    files
        .iter()
        .filter_map(|path| {
            let needle = needle(path, &shared);
            (!map.contains(&needle)).then(|| format!("{path} (looked for `{needle}`)"))
        })
        .collect()
}

/// `map` without its fenced blocks (the diagram), whose triple backticks would otherwise pair
/// with the inline ones.
fn without_fences(map: &str) -> String {
    let mut inside = false;
    let mut kept = String::new();
    for line in map.lines() {
        if line.trim_start().starts_with("```") {
            inside = !inside;
        } else if !inside {
            kept.push_str(line);
            kept.push('\n');
        }
    }
    kept
}

/// The backticked spans of `map` that look like a path to a code file: no spaces, no
/// wildcard, a code extension (`ws/writer.rs`, `lib/projector.mjs`, `kiosk.css`).
fn written_paths(map: &str) -> Vec<String> {
    without_fences(map)
        .split('`')
        .skip(1)
        .step_by(2)
        .filter(|span| {
            let plain = span
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.' | '/'));
            let extension = span.rsplit_once('.').map(|(_, ext)| ext);
            plain && extension.is_some_and(|ext| CODE_EXTENSIONS.contains(&ext))
        })
        .map(str::to_string)
        .collect()
}

/// The paths written in `map` that no file of the repository ends with.
fn stale(map: &str) -> Vec<String> {
    let all = files_under(repo());
    let mut missing: Vec<String> = written_paths(map)
        .into_iter()
        .filter(|written| {
            let tail = format!("/{written}");
            !all.iter()
                .any(|file| file == written || file.ends_with(&tail))
        })
        .collect();
    missing.sort();
    missing.dedup();
    missing
}

#[test]
fn every_file_under_server_static_and_pages_is_named_in_the_codemap() {
    let missing = unmapped(&architecture());
    assert!(
        missing.is_empty(),
        "{} file(s) missing from ARCHITECTURE.md: add it to ARCHITECTURE.md's codemap, one \
         clause saying what it owns:\n  {}",
        missing.len(),
        missing.join("\n  ")
    );
}

#[test]
fn every_code_path_written_in_the_codemap_exists() {
    let map = architecture();
    let written = written_paths(&map);
    // The scan must see the map's paths at all, or this test would pass on nothing.
    for known in ["ws/session.rs", "static/kiosk.js", "lib/projector.mjs"] {
        assert!(
            written.iter().any(|w| w == known),
            "ARCHITECTURE.md's `{known}` was not read as a path; the scan is broken"
        );
    }
    let missing = stale(&map);
    assert!(
        missing.is_empty(),
        "ARCHITECTURE.md names {} file(s) that no longer exist: fix or remove them in \
         ARCHITECTURE.md's codemap:\n  {}",
        missing.len(),
        missing.join("\n  ")
    );
}

#[test]
fn a_file_left_out_of_the_map_or_gone_from_the_repo_is_reported() {
    // `server/lib.rs` is the library's root (Cargo.toml), so it is always there to leave out.
    let map = architecture();
    let without = map.replace("lib.rs", "(left out)");
    let missing = unmapped(&without);
    assert!(
        missing.iter().any(|m| m.starts_with("server/lib.rs ")),
        "server/lib.rs left out of the map was not reported: {missing:?}"
    );
    let renamed = format!("{map}\n`ws/no_such_file.rs` and `no-such-script.js`\n");
    let gone = stale(&renamed);
    for name in ["ws/no_such_file.rs", "no-such-script.js"] {
        assert!(
            gone.iter().any(|g| g == name),
            "`{name}` named in the map but absent from the repo was not reported: {gone:?}"
        );
    }
}

/// The packages of the workspace's dependency graph that `package` depends on, directly or
/// not (normal dependencies, as built for the target), read from `cargo metadata`.
fn dependency_closure(package: &str) -> Vec<String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = std::process::Command::new(cargo)
        .args(["metadata", "--format-version", "1", "--locked"])
        .current_dir(repo())
        .output()
        .expect("running cargo metadata");
    assert!(
        out.status.success(),
        "cargo metadata: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let meta: serde_json::Value = serde_json::from_slice(&out.stdout).expect("metadata JSON");
    let name_of = |id: &str| -> String {
        meta["packages"]
            .as_array()
            .into_iter()
            .flatten()
            .find(|p| p["id"] == id)
            .and_then(|p| p["name"].as_str())
            .unwrap_or(id)
            .to_string()
    };
    let nodes = meta["resolve"]["nodes"].as_array().expect("resolve nodes");
    let start = nodes
        .iter()
        .find(|n| name_of(n["id"].as_str().unwrap_or_default()) == package)
        .unwrap_or_else(|| panic!("{package} is not in the workspace"));
    let mut seen: Vec<String> = Vec::new();
    let mut pending = vec![start];
    while let Some(node) = pending.pop() {
        for dep in node["deps"].as_array().into_iter().flatten() {
            let normal = dep["dep_kinds"]
                .as_array()
                .into_iter()
                .flatten()
                .any(|k| k["kind"].is_null());
            let id = dep["pkg"].as_str().unwrap_or_default();
            if !normal || seen.iter().any(|s| s == id) {
                continue;
            }
            seen.push(id.to_string());
            if let Some(next) = nodes.iter().find(|n| n["id"] == id) {
                pending.push(next);
            }
        }
    }
    let mut names: Vec<String> = seen.iter().map(|id| name_of(id)).collect();
    names.sort();
    names.dedup();
    names
}

/// The async runtime, HTTP and MQTT: what the runtime crate alone may bring in.
const RUNTIME_STACK: [&str; 7] = [
    "tokio",
    "axum",
    "hyper",
    "rumqttc",
    "tungstenite",
    "tower",
    "mio",
];

/// What of the runtime stack, and which workspace crates beyond `allowed`, `package` depends
/// on (directly or not).
fn forbidden_dependencies(package: &str, allowed: &[&str]) -> Vec<String> {
    let closure = dependency_closure(package);
    // The scan must see real dependencies, or this test would pass on nothing.
    assert!(
        closure.iter().any(|n| n == "serde"),
        "{package}'s dependencies were not read: {closure:?}"
    );
    closure
        .into_iter()
        .filter(|n| {
            (n.starts_with("docent") && !allowed.contains(&n.as_str()))
                || RUNTIME_STACK
                    .iter()
                    .any(|f| n == f || n.starts_with(&format!("{f}-")))
        })
        .collect()
}

#[test]
fn the_format_crates_have_no_async_runtime_and_depend_only_downward() {
    // ARCHITECTURE.md: docent-content depends on nothing in the workspace, docent-protocol
    // only on docent-content, docent-corpus on both; none has an async runtime or a command
    // line.
    for (package, allowed) in [
        ("docent-content", &[][..]),
        ("docent-protocol", &["docent-content"][..]),
        ("docent-corpus", &["docent-content", "docent-protocol"][..]),
    ] {
        let forbidden = forbidden_dependencies(package, allowed);
        assert!(
            forbidden.is_empty(),
            "{package} may depend on {allowed:?} in the workspace and on no async runtime, HTTP \
             or MQTT (ARCHITECTURE.md), but its dependencies now include {forbidden:?}"
        );
    }
}

#[test]
fn a_runtime_dependency_of_a_format_crate_would_be_reported() {
    // The root crate has them all: the check must see them.
    let found = forbidden_dependencies(
        "docent",
        &["docent-content", "docent-protocol", "docent-corpus"],
    );
    for expected in ["tokio", "axum", "rumqttc"] {
        assert!(
            found.iter().any(|f| f == expected),
            "{expected} not seen in docent's dependencies: {found:?}"
        );
    }
}
