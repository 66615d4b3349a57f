//! Differential tests: the fast reader must build exactly the tree the serde-saphyr path
//! builds (positions, byte spans, kinds), and must give up wherever that path fails or
//! sees something the fast reader does not handle.

use std::path::Path;
use std::sync::Arc;

use serde_saphyr::Spanned;

use super::{Node, fast, options, raw};

/// The tree from the serde-saphyr path, or `None` when it refuses the text.
fn slow(file: &Arc<str>, source: &str) -> Option<Node> {
    serde_saphyr::from_str_with_options::<Spanned<raw::Raw>>(source, options())
        .ok()
        .map(|tree| raw::into_node(tree, file, source, raw::Origin::START))
}

/// Compares both readers on `source`; returns whether the fast reader handled it.
fn same_tree(name: &str, source: &str) -> bool {
    let file: Arc<str> = Arc::from(name);
    let fast = fast::read(&file, source);
    let slow = slow(&file, source);
    if let Some(fast) = &fast {
        let Some(slow) = &slow else {
            panic!("{name}: the fast reader accepted what serde-saphyr refuses:\n{source}")
        };
        assert_eq!(fast, slow, "{name}: trees differ for:\n{source}");
    }
    fast.is_some()
}

fn yaml_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            yaml_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "yaml" || e == "yml") {
            out.push(path);
        }
    }
}

#[test]
fn every_bundled_and_fixture_file_reads_the_same() {
    // This crate is `server/content/`; the bundles are the repository's.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut files = Vec::new();
    yaml_files(&root.join("dialogs"), &mut files);
    yaml_files(&root.join("tests/fixtures"), &mut files);
    assert!(files.len() >= 10, "found only {files:?}");
    let mut fast_count = 0;
    for path in &files {
        let Ok(source) = std::fs::read_to_string(path) else {
            continue;
        };
        if same_tree(&path.display().to_string(), &source) {
            fast_count += 1;
        }
    }
    // The real dialogs are the common case the fast reader is for.
    assert_eq!(fast_count, files.len(), "some files fell back");
}

/// Snippets the fast reader handles itself, each compared with the serde path.
const HANDLED: &[&str] = &[
    "- Label: A\n  Text: hi\n",
    "- [yes, no, on, off, y, n, True, FALSE, 3.5, 0x1F, 010, 0o17, 0b101, 1_000, .inf, -.inf, \
     .NaN, +12, -7, 1e999, 1e3, ~, null, Null, NULL, 'q', \"d\", plain, -x, .hidden, 3 apples]\n",
    "a: |\n  line one\n  line two\n\nb: |-\n  kept\n\nc: |+\n  keep\n\n\nd: >\n  folded\n  text\n\n  \
     para\ne: >-\n  x\n",
    "a: \"esc \\t \\\" \\u00e9 \\n end\"\nb: 'it''s'\nc: \"multi\n  line\"\n",
    "a: plain text\n  that goes on\n  over lines\nb: x\n",
    "a: {x: 1, y: [a, b, {c: d}], z: }\nb: []\nc: {}\n",
    "\u{feff}- Label: A\n  Text: bom\n",
    "- Label: A\r\n  Text: crlf\r\n- Label: B\r\n",
    "# comment\n- Label: A # trailing\n  # between\n  Text: hi\n",
    "a:\nb: ~\nc: null\nd: ''\ne: \"\"\n",
    "- Text: café — ünïcödé ✓ 日本語\n  Label: Ω\n",
    "a: 1\na: 2\n",
    "---\n- x\n...\n",
    "- - nested\n  - - deeper\n- key: value\n  other:\n    - 1\n",
    "[a: b, c: 1, {d: e}]\n",
    "? explicit\n: value\n",
    "a: b\n c\n: d\n",
    "- -1\n- - -2\n- 0.5e-3\n- 12:30\n- 2024-01-01\n",
    "a: \"\"\nb: ''\nc: |\n\nd: >\n",
    "- \"quoted key\": v\n  'single': w\n  3: number key\n  yes: bool key\n",
    "plain\n",
    "%YAML 1.2\n---\na: b\n",
    "---\n",
    "--- |\n  x\n",
    "? \n: v\n",
    ": v\n",
    "[a, [b, [c]]]\n",
    "{a: {b: {c: d}}}\n",
    "a: 'multi\n  line single'\nb: >+\n  x\n\n",
    "- |2\n   indented\n",
    "a: \"\\x41\\U0001F600\"\n",
    "- é: [ü, ö, 1.5]\n  日本: {語: yes}\n",
];

/// Snippets the fast reader leaves to serde-saphyr (which may accept or refuse them).
const LEFT_TO_SERDE: &[&str] = &[
    "",
    "# only a comment\n",
    "a: &x 1\nb: *x\n",
    "base: &b {x: 1}\nother:\n  <<: *b\n  y: 2\n",
    "a: !!str 1\n",
    "a: !custom x\n",
    "? [a, b]\n: c\n",
    "a: 1\n---\nb: 2\n",
    "- Label: A\n  Text: \"open\n",
    "- [a, b\n",
    "a:\n\t- x\n",
    "Text: hi: there\n",
    "a: ...\n",
    "- ---\n",
];

#[test]
fn tricky_snippets_read_the_same() {
    for (i, source) in HANDLED.iter().enumerate() {
        assert!(
            same_tree(&format!("handled-{i}.yaml"), source),
            "the fast reader gave up on:\n{source}"
        );
    }
    for (i, source) in LEFT_TO_SERDE.iter().enumerate() {
        assert!(
            !same_tree(&format!("left-{i}.yaml"), source),
            "the fast reader should leave this to serde-saphyr:\n{source}"
        );
    }
}

#[test]
fn a_large_generated_file_reads_the_same() {
    let source: String = (0..2_000)
        .map(|i| {
            format!(
                "- Label: A{i}\n  Text:\n    - \"Hello {i}\"\n    - 'it''s {i}'\n  \
                 Variant: {{Text: [x, {i}], Cue: yes}}\n  Commands:\n    - Go: {i}.5\n"
            )
        })
        .collect();
    assert!(same_tree("big.yaml", &source));
}

#[test]
fn deep_nesting_is_left_to_the_serde_budget() {
    // Only the fast side here: the serde path recurses so deep that it overflows a debug
    // test thread's stack at this depth.
    let file: Arc<str> = Arc::from("deep.yaml");
    let deep = format!("{}x{}\n", "[".repeat(70), "]".repeat(70));
    assert!(fast::read(&file, &deep).is_none());
    let fine = format!("{}x{}\n", "[".repeat(30), "]".repeat(30));
    assert!(same_tree("fine.yaml", &fine));
}
