//! `docent schema`: the committed schemas in `docs/schema/` are exactly what the command
//! prints (so they are never stale), `--out` writes both, and every shipped bundle names its
//! schema on its first line for VS Code while still passing `docent check`.
//! The schemas themselves are checked by an independent validator in
//! `tests/e2e/schema.test.mjs` (ajv).

use crate::common;

use std::process::Command;

use common::repo;
use docent::content::schema::{acts_schema, config_schema, to_file_text};

fn docent(args: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_docent"))
        .args(args)
        .current_dir(repo())
        .output()
        .expect("docent runs");
    (
        out.status.success(),
        String::from_utf8(out.stdout).expect("utf-8"),
    )
}

#[test]
fn the_committed_schemas_are_what_docent_schema_prints() {
    let committed = |name: &str| {
        std::fs::read_to_string(repo().join("docs/schema").join(name))
            .unwrap_or_else(|e| panic!("docs/schema/{name}: {e}"))
    };
    let (ok, acts) = docent(&["schema", "acts"]);
    assert!(ok);
    assert_eq!(
        acts,
        committed("acts.schema.json"),
        "docs/schema/acts.schema.json is stale: run `docent schema --out docs/schema`"
    );
    let (ok, config) = docent(&["schema", "config"]);
    assert!(ok);
    assert_eq!(
        config,
        committed("docent.schema.json"),
        "docs/schema/docent.schema.json is stale: run `docent schema --out docs/schema`"
    );
    assert_eq!(acts, to_file_text(&acts_schema()));
    assert_eq!(config, to_file_text(&config_schema()));
}

#[test]
fn schema_out_writes_both_files() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("schema");
    let (ok, said) = docent(&["schema", "--out", out.to_str().expect("utf-8 path")]);
    assert!(ok, "{said}");
    let acts = std::fs::read_to_string(out.join("acts.schema.json")).expect("acts schema");
    let config = std::fs::read_to_string(out.join("docent.schema.json")).expect("config schema");
    assert_eq!(acts, to_file_text(&acts_schema()));
    assert_eq!(config, to_file_text(&config_schema()));
    assert!(said.contains("acts.schema.json") && said.contains("docent.schema.json"));
}

#[test]
fn schema_without_a_kind_or_folder_is_refused() {
    let (ok, _) = docent(&["schema"]);
    assert!(!ok);
}

#[test]
fn every_shipped_yaml_file_names_its_schema_first_and_still_loads() {
    let mut seen = 0;
    for entry in std::fs::read_dir(repo().join("dialogs")).expect("dialogs") {
        let dir = entry.expect("entry").path();
        if !dir.is_dir() {
            continue;
        }
        for file in std::fs::read_dir(&dir).expect("bundle") {
            let path = file.expect("entry").path();
            let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
            if !(name.ends_with(".yaml") || name.ends_with(".yml")) {
                continue;
            }
            let schema = if name == "docent.yaml" {
                "docent.schema.json"
            } else {
                "acts.schema.json"
            };
            let text = std::fs::read_to_string(&path).expect("read");
            let first = text.lines().next().unwrap_or("");
            assert_eq!(
                first,
                format!("# yaml-language-server: $schema=../../docs/schema/{schema}"),
                "{}",
                path.display()
            );
            assert!(repo().join("docs/schema").join(schema).is_file());
            seen += 1;
        }
        let report = docent::content::load_bundle(&dir);
        // Notes are no problem (the paper's MPEG-1 film, converted when served).
        let problems: Vec<_> = (report.diagnostics.iter())
            .filter(|d| d.severity != docent::content::Severity::Note)
            .collect();
        assert!(
            problems.is_empty(),
            "{}: {:?}",
            dir.display(),
            report.diagnostics
        );
    }
    assert!(seen >= 8, "only {seen} shipped YAML files");
}
