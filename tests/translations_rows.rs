//! A translation the bundle would refuse, told by its row: the in-memory load of an import
//! finds an unfilled placeholder or a CAT tool's inline markup in a translated text; that
//! text's variant is left out (untranslated, or keeping its old texts) and reported by the
//! table's row (CSV) or unit line (XLIFF) and key with the problem's own words, the rest is
//! written and loads, exit status 3. A warning a new text brings is told the same way.

use crate::common;

use std::path::Path;
use std::process::Command;

use common::TempBundle;

const ACTS: &str = "\
- Label: WELCOME
  Text: Here is today's programme. At ten there is a demonstration.
- Label: GOODBYE
  Text:
    - Good bye!
    - See you soon!
- Label: THANKS
  Text: Thank you
  Text@fr: Merci bien
- Label: VISIT
  Text: [Enjoy your visit, Have fun]
";

fn bundle() -> TempBundle {
    TempBundle::new(ACTS).with_file("docent.yaml", "languages: [en, fr]\n")
}

/// Runs `docent ARGS`: exit status, stdout, stderr.
fn docent(args: &[&str]) -> (i32, String, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_docent"))
        .args(args)
        .output()
        .expect("docent runs");
    let text = |b: &[u8]| String::from_utf8(b.to_vec()).expect("utf-8");
    (
        output.status.code().expect("exit status"),
        text(&output.stdout),
        text(&output.stderr),
    )
}

fn path(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// Imports `table`, written as `name` beside the bundle (not in it: the check below reads
/// the bundle's folder); status, stdout, stderr and the table's path.
fn import(bundle: &TempBundle, name: &str, table: &str) -> (i32, String, String, String) {
    let folder = tempfile::tempdir().expect("temp dir");
    let file = folder.path().join(name);
    std::fs::write(&file, table).expect("table");
    let (code, out, err) = docent(&["translations", "import", path(bundle.path()), path(&file)]);
    (code, out, err, file.display().to_string())
}

fn acts(bundle: &TempBundle) -> String {
    std::fs::read_to_string(bundle.path().join("acts.yaml")).expect("acts")
}

/// `docent check` on the bundle as imported: its exit status and stdout.
fn check(bundle: &TempBundle) -> (i32, String) {
    let (code, out, _) = docent(&["check", path(bundle.path())]);
    (code, out)
}

#[test]
fn a_csv_cell_with_a_placeholder_is_left_out_by_its_row_and_the_rest_imported() {
    let bundle = bundle();
    let table = "\
key,en,fr,where
WELCOME/Text/1,Here is today's programme. At ten there is a demonstration.,Voici le programme du jour. À {heure} il y a une démonstration.,acts.yaml:2
GOODBYE/Text/1,Good bye!,Au revoir !,acts.yaml:5
GOODBYE/Text/2,See you soon!,À bientôt %s !,acts.yaml:6
THANKS/Text/1,Thank you,Merci beaucoup,acts.yaml:8
VISIT/Text/1,Enjoy your visit,Bonne visite sur https://musee.example.fr,acts.yaml:11
VISIT/Text/2,Have fun,Amusez-vous bien,acts.yaml:11
";
    let (code, out, err, file) = import(&bundle, "fr.csv", table);
    assert_eq!((code, err.as_str()), (3, ""), "{out}");
    assert_eq!(
        out,
        format!(
            "French (fr) from {file}: 1 translation(s) added, 1 replaced, 0 unchanged.
Written: acts.yaml.
3 problem(s):
  row 2 (WELCOME/Text/1): error[speech-placeholder]: `{{heure}}` looks like a placeholder that was never filled in. Docent does not replace anything in a text: the robot would say it as written. Write the real words. WELCOME/Text is not imported: it stays untranslated.
  row 4 (GOODBYE/Text/2): error[speech-placeholder]: `%s` looks like a placeholder that was never filled in. Docent does not replace anything in a text: the robot would say it as written. Write the real words. GOODBYE/Text is not imported: it stays untranslated.
  row 6 (VISIT/Text/1): warning[speech-address]: The robot spells out `https://musee.example.fr` sign by sign (\"h t t p s colon slash slash…\"). Write it the way it should sound, for example \"our website, museum dot org\", and show the address on a page instead.
"
        )
    );
    let written = ACTS.replace("Merci bien", "Merci beaucoup")
        + "  Text@fr: [Bonne visite sur https://musee.example.fr, Amusez-vous bien]\n";
    assert_eq!(acts(&bundle), written);
    let (code, out) = check(&bundle);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("0 error(s)"), "{out}");
    assert!(out.contains("warning[speech-address]"), "{out}");
    assert!(
        out.contains(" --> acts.yaml:12:30\n"),
        "the bundle's own line now: {out}"
    );
}

#[test]
fn xliff_markup_is_left_out_by_its_unit_line_and_the_rest_imported() {
    let bundle = bundle();
    // A CAT tool that writes its inline codes as text (escaped) and one that writes elements.
    let xliff = r#"<?xml version="1.0" encoding="UTF-8"?>
<xliff version="1.2" xmlns="urn:oasis:names:tc:xliff:document:1.2">
  <file original="b" source-language="en" target-language="fr" datatype="plaintext">
    <body>
      <trans-unit id="WELCOME/Text/1">
        <source>Here is today's programme. At ten there is a demonstration.</source>
        <target>Voici le programme du jour. &lt;g id="1"&gt;À dix heures&lt;/g&gt; il y a une démonstration.</target>
      </trans-unit>
      <trans-unit id="THANKS/Text/1">
        <source>Thank you</source>
        <target>Merci <g id="2">beaucoup</g></target>
      </trans-unit>
      <trans-unit id="VISIT/Text/1">
        <source>Enjoy your visit</source>
        <target>Bonne visite</target>
      </trans-unit>
      <trans-unit id="VISIT/Text/2">
        <source>Have fun</source>
        <target>Amusez-vous bien</target>
      </trans-unit>
    </body>
  </file>
</xliff>
"#;
    let (code, out, err, file) = import(&bundle, "fr.xlf", xliff);
    assert_eq!((code, err.as_str()), (3, ""), "{out}");
    assert_eq!(
        out,
        format!(
            "French (fr) from {file}: 1 translation(s) added, 0 replaced, 0 unchanged.
Written: acts.yaml.
2 problem(s):
  line 9 (THANKS/Text/1): the target contains markup (<g>), which a spoken text cannot hold; it is not imported. Write it as plain text.
  line 5 (WELCOME/Text/1): error[speech-markup]: `<g id=\"1\">` is formatting (HTML or Markdown), not words: the robot reads its signs out or stumbles over them. Remove it; speech has no bold or links. WELCOME/Text is not imported: it stays untranslated.
"
        )
    );
    let written = format!("{ACTS}  Text@fr: [Bonne visite, Amusez-vous bien]\n");
    assert_eq!(acts(&bundle), written, "THANKS keeps Merci bien");
    let (code, out) = check(&bundle);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("0 error(s)"), "{out}");
}
