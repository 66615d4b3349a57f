//! `docent translations export|import` end to end with the real binary: a table exported,
//! filled by a translator's tools (Python's csv module for a spreadsheet, translate-toolkit
//! for a CAT tool), imported, and the bundle serving the new German text; an import that
//! changes nothing but the translations, byte for byte; awkward texts that read back exactly.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::TestServer;
use common::process::run_docent;
use serde_json::{Value, json};

fn path(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// A copy of the two-language fixture with TOUR's German text removed.
fn fixture_without_tour_translation(dir: &Path) -> PathBuf {
    let bundle = dir.join("two-languages");
    let fixture = common::repo().join("tests/fixtures/two-languages");
    let status = Command::new("cp")
        .arg("-r")
        .arg(&fixture)
        .arg(&bundle)
        .status()
        .expect("cp runs");
    assert!(status.success());
    let acts = bundle.join("acts.yaml");
    let text = std::fs::read_to_string(&acts).expect("acts");
    let without = text.replace("  Text@de: [Folgen Sie mir in den ersten Raum.]\n", "");
    assert_ne!(text, without, "the fixture translates TOUR");
    std::fs::write(&acts, without).expect("write");
    bundle
}

/// Fills `table` into `filled` with the translator's tool for its format; what it read.
fn fill(table: &Path, filled: &Path, fills: Value) -> Value {
    let python = common::repo().join("tests/readers/.venv/bin/python");
    assert!(
        python.is_file(),
        "{} is missing: run scripts/install-test-deps.sh (it installs translate-toolkit)",
        python.display()
    );
    let output = Command::new(python)
        .arg(common::repo().join("tests/readers/fill_translations.py"))
        .args([table, filled])
        .arg(fills.to_string())
        .output()
        .expect("python runs");
    assert!(
        output.status.success(),
        "fill_translations.py failed:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).expect("JSON")
}

/// The text the dispatcher speaks for `label` to a German visitor.
async fn german_text(bundle: &Path, label: &str) -> Value {
    let server = TestServer::start(bundle).await;
    let mut op = server.operator().await;
    op.send(json!({"type": "language", "language": "de"})).await;
    op.event("language.changed").await;
    let triggered = server.trigger(label, json!({})).await;
    assert_eq!(triggered["language"], "de", "{triggered}");
    server.stop().await;
    triggered["text"].clone()
}

async fn round_trip(extension: &str) {
    let dir = tempfile::tempdir().expect("temp dir");
    let bundle = fixture_without_tour_translation(dir.path());
    let table = dir.path().join(format!("de.{extension}"));
    let (code, out, err) = run_docent(&[
        "translations",
        "export",
        path(&bundle),
        "--language",
        "de",
        "--output",
        path(&table),
    ]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        out,
        format!(
            "Wrote {}: 5 texts for German (de): 4 translated, 1 to translate.\n",
            table.display()
        )
    );
    let tour = "Bitte folgen Sie mir: hier # entlang";
    let filled = dir.path().join(format!("filled.{extension}"));
    let read = fill(&table, &filled, json!({"TOUR/Text/1": tour}));
    assert_eq!(
        (&read["source_language"], &read["target_language"]),
        (&json!("en"), &json!("de"))
    );
    let texts = read["texts"].as_array().expect("texts");
    let keys: Vec<&str> = texts.iter().filter_map(|t| t["key"].as_str()).collect();
    assert_eq!(
        keys,
        [
            "GREETING/Text/1",
            "GREETING/TextChild/1",
            "GREETING/TextChild/2",
            "TOUR/Text/1",
            "GOODBYE/Text/1"
        ]
    );
    assert_eq!(
        (&texts[0]["source"], &texts[0]["target"]),
        (
            &json!("Welcome to the museum!"),
            &json!("Willkommen im Museum!")
        )
    );
    assert_eq!(
        (&texts[3]["target"], &texts[4]["target"]),
        (&json!(""), &json!("Danke für Ihren Besuch."))
    );
    assert!(
        texts[3]["note"]
            .as_str()
            .unwrap_or_default()
            .contains("acts.yaml:11"),
        "{}",
        texts[3]
    );

    let (code, out, err) = run_docent(&["translations", "import", path(&bundle), path(&filled)]);
    assert_eq!((code, err.as_str()), (0, ""), "{out}");
    assert_eq!(
        out,
        format!(
            "German (de) from {}: 1 translation(s) added, 0 replaced, 3 unchanged.\nWritten: acts.yaml.\n",
            filled.display()
        )
    );
    let acts = std::fs::read_to_string(bundle.join("acts.yaml")).expect("acts");
    assert!(
        acts.contains("  Text: [Follow me to the first room.]\n  Text@de: [\"Bitte folgen Sie mir: hier # entlang\"]\n"),
        "{acts}"
    );
    assert_eq!(german_text(&bundle, "TOUR").await, tour);
    assert_eq!(
        german_text(&bundle, "GOODBYE").await,
        "Danke für Ihren Besuch."
    );
}

#[tokio::test]
async fn a_csv_filled_with_pythons_csv_module_gives_the_german_visitor_the_new_text() {
    round_trip("csv").await;
}

#[tokio::test]
async fn an_xliff_filled_with_translate_toolkit_gives_the_german_visitor_the_new_text() {
    round_trip("xlf").await;
}

#[test]
fn the_csv_starts_with_a_bom_and_holds_key_original_translation_and_place() {
    let dir = tempfile::tempdir().expect("temp dir");
    let bundle = fixture_without_tour_translation(dir.path());
    let output = Command::new(env!("CARGO_BIN_EXE_docent"))
        .args(["translations", "export", path(&bundle), "--language", "DE"])
        .output()
        .expect("docent runs");
    assert!(output.status.success());
    assert_eq!(
        String::from_utf8(output.stdout).expect("utf-8"),
        "\u{feff}key,en,de,where\r\n\
         GREETING/Text/1,Welcome to the museum!,Willkommen im Museum!,acts.yaml:3\r\n\
         GREETING/TextChild/1,Hello there,Hallo,acts.yaml:5\r\n\
         GREETING/TextChild/2,explorer!,kleine Entdecker!,acts.yaml:5\r\n\
         TOUR/Text/1,Follow me to the first room.,,acts.yaml:11\r\n\
         GOODBYE/Text/1,Thank you for visiting.,Danke für Ihren Besuch.,acts.yaml:16\r\n"
    );
    assert_eq!(
        String::from_utf8(output.stderr).expect("utf-8"),
        "docent: 5 texts for German (de): 4 translated, 1 to translate.\n"
    );
}

/// A hand-written acts file: comments, quoting, a list at the key's indent, a German list to
/// replace, one to add in flow style, one to add after a single text at the end of the file.
const HAND_WRITTEN: &str = "\
# Acts of a museum tour, written by hand.
- Label: WELCOME   # the first act
  Text:
  - Welcome!
  # a second greeting
  - 'Hello, visitor.'
  Text@de:
    - Willkommen!
    - Alte Übersetzung
  TextChild: [Hi kids, \"Hey: you\"]
  Cmds:
    - DISPLAY_PAGE index.html

- Label: BYE
  Text: \"Good bye.\"";

const BUNDLE_SETTINGS: &str = "languages: [en, de]\ncontexts: [TextChild]\n";

#[test]
fn an_import_writes_the_translations_and_changes_nothing_else_byte_for_byte() {
    let bundle = common::TempBundle::new(HAND_WRITTEN).with_file("docent.yaml", BUNDLE_SETTINGS);
    let table = bundle.path().join("../de-table.csv");
    std::fs::write(
        &table,
        "key,en,de,where\n\
         WELCOME/Text/1,Welcome!,Willkommen!,acts.yaml:4\n\
         WELCOME/Text/2,\"Hello, visitor.\",\"Hallo, Besucher.\",acts.yaml:6\n\
         WELCOME/TextChild/1,Hi kids,Hallo Kinder,acts.yaml:10\n\
         WELCOME/TextChild/2,Hey: you,He: du,acts.yaml:10\n\
         BYE/Text/1,Good bye.,Auf Wiedersehen.,acts.yaml:15\n",
    )
    .expect("table");
    let (code, out, err) =
        run_docent(&["translations", "import", path(bundle.path()), path(&table)]);
    std::fs::remove_file(&table).expect("remove table");
    assert_eq!((code, err.as_str()), (0, ""), "{out}");
    assert!(
        out.contains(": 2 translation(s) added, 1 replaced, 0 unchanged.\n"),
        "{out}"
    );
    let acts = std::fs::read_to_string(bundle.path().join("acts.yaml")).expect("acts");
    assert_eq!(
        acts,
        "\
# Acts of a museum tour, written by hand.
- Label: WELCOME   # the first act
  Text:
  - Welcome!
  # a second greeting
  - 'Hello, visitor.'
  Text@de:
  - Willkommen!
  - Hallo, Besucher.
  TextChild: [Hi kids, \"Hey: you\"]
  TextChild@de: [Hallo Kinder, \"He: du\"]
  Cmds:
    - DISPLAY_PAGE index.html

- Label: BYE
  Text: \"Good bye.\"
  Text@de: Auf Wiedersehen."
    );
}

/// Texts YAML would read as something else, or change, unless written with care.
const AWKWARD: [&str; 40] = [
    "Note: this is splendid",
    "yes",
    "No",
    "ON",
    "off",
    "~",
    "null",
    "1984",
    "3.14",
    "0x1F",
    ".inf",
    "- dash first",
    "-dash",
    "# hash first",
    "a #hash",
    "C# works",
    "\"double\" quoted",
    "'single' quoted",
    "it's",
    "[brackets]",
    "}close {open",
    "a, b",
    "+plus",
    "`tick`",
    "%percent",
    "!bang",
    "&anchor",
    "*alias",
    "|pipe",
    ">fold",
    "? question",
    ": colon",
    "ends:",
    "back\\slash",
    "tab\there",
    "line\nbreak",
    " leading",
    "trailing ",
    "Grüße „aus“ München",
    "Ünïcödé — ½",
];

#[test]
fn awkward_texts_read_back_exactly_in_every_shape_of_list() {
    // A translation with a line break is imported only where its original has one too
    // (issue 26: elsewhere it is two cells pasted into one), so that original has one.
    let broken = |n: usize| {
        if AWKWARD[n - 1].contains('\n') {
            "\\nmore"
        } else {
            ""
        }
    };
    let originals: Vec<String> = (1..=AWKWARD.len())
        .map(|n| format!("\"text {n}{}\"", broken(n)))
        .collect();
    let items: String = originals.iter().map(|t| format!("    - {t}\n")).collect();
    let acts = format!(
        "- Label: FLOW\n  Text: [{}]\n- Label: ITEMS\n  Text:\n{items}",
        originals.join(", ")
    );
    let mut singles = String::new();
    for (i, _) in AWKWARD.iter().enumerate() {
        let more = broken(i + 1);
        singles.push_str(&format!("- Label: ONE{i}\n  Text: \"single {i}{more}\"\n"));
    }
    let bundle = common::TempBundle::new(&format!("{acts}{singles}"))
        .with_file("docent.yaml", "languages: [en, de]\n");
    let mut table = String::from("key,en,de\n");
    let quoted = |t: &str| format!("\"{}\"", t.replace('"', "\"\""));
    for (i, text) in AWKWARD.iter().enumerate() {
        let n = i + 1;
        let more = if text.contains('\n') { "\nmore" } else { "" };
        let text = quoted(text);
        let (flow, single) = (
            quoted(&format!("text {n}{more}")),
            quoted(&format!("single {i}{more}")),
        );
        table.push_str(&format!(
            "FLOW/Text/{n},{flow},{text}\nITEMS/Text/{n},{flow},{text}\n"
        ));
        table.push_str(&format!("ONE{i}/Text/1,{single},{text}\n"));
    }
    let file = bundle.path().join("../awkward.csv");
    std::fs::write(&file, table).expect("table");
    let (code, out, err) =
        run_docent(&["translations", "import", path(bundle.path()), path(&file)]);
    std::fs::remove_file(&file).expect("remove table");
    assert_eq!(code, 0, "{out}{err}");
    let loaded = docent::content::load_bundle(bundle.path())
        .bundle
        .expect("loads");
    let de = docent::content::Language::parse("de").expect("de");
    let texts = |label: &str| -> Vec<String> {
        let variant = loaded
            .act(label)
            .and_then(|a| a.variant("Text"))
            .expect("variant");
        variant.translations[&de]
            .alternatives
            .iter()
            .map(|t| t.value.clone())
            .collect()
    };
    assert_eq!(texts("FLOW"), AWKWARD);
    assert_eq!(texts("ITEMS"), AWKWARD);
    for (i, text) in AWKWARD.iter().enumerate() {
        assert_eq!(texts(&format!("ONE{i}")), [*text]);
    }
}
