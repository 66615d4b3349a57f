//! The crate graph that ARCHITECTURE.md draws, read from `cargo metadata`: each format crate
//! depends only on the workspace crates below it, and none of them brings in an async runtime,
//! HTTP, MQTT or a command line. Cargo itself refuses a cycle between crates.

use crate::common;

/// The packages of the workspace's dependency graph that `package` depends on, directly or
/// not (normal dependencies, as built for the target), read from `cargo metadata`.
fn dependency_closure(package: &str) -> Vec<String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = std::process::Command::new(cargo)
        .args(["metadata", "--format-version", "1", "--locked"])
        .current_dir(common::repo())
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

/// The async runtime, HTTP, MQTT and the command line: what the runtime crate alone may
/// bring in.
const RUNTIME_STACK: [&str; 9] = [
    "tokio",
    "axum",
    "hyper",
    "rumqttc",
    "tungstenite",
    "tower",
    "mio",
    "clap",
    "indicatif",
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
            "{package} may depend on {allowed:?} in the workspace and on no async runtime, HTTP, \
             MQTT or command line (ARCHITECTURE.md), but its dependencies now include \
             {forbidden:?}"
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
    for expected in ["tokio", "axum", "rumqttc", "clap"] {
        assert!(
            found.iter().any(|f| f == expected),
            "{expected} not seen in docent's dependencies: {found:?}"
        );
    }
}
