//! Translators' tables as Excel, LibreOffice and CAT tools save them (issue 26): a table is
//! never imported half-right. Excel's CSV with `;`, a byte order mark, CRLF and line breaks in
//! quoted cells is imported; a column slid by a row, spreadsheet error values, a line break
//! where the original has none, a copied original and targets a CAT tool marks unfinished
//! (XLIFF 1.2 and 2.0) each refuse the whole table, named by file, row and cell (CSV) or unit
//! line (XLIFF), and the acts file stays byte for byte as it was. `docent check` warns about a
//! translation that is its original (`translation-same-as-original`), at its line.

use crate::common;

use std::path::Path;

use common::TempBundle;
use common::process::run_docent;

const ACTS: &str = "\
- Label: WELCOME
  Text: Welcome to the museum!
  Text@de: Willkommen im Museum!
- Label: ROOM
  Text: [This room shows the Dutch masters., The Night Watch is next door.]
  Text@de: [Dieser Saal zeigt die niederländischen Meister., Die Nachtwache ist nebenan.]
- Label: ADDRESS
  Text: \"Museum Street 1\\nAmsterdam\"
- Label: PAINTING
  Text: Mona Lisa
- Label: BYE
  Text: Good bye, see you soon!
";

fn bundle() -> TempBundle {
    TempBundle::new(ACTS).with_file("docent.yaml", "languages: [en, de]\n")
}

fn path(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// Imports `table`, written as `name` beside the bundle: status, stdout, stderr and the
/// table's path as messages print it.
fn import(bundle: &TempBundle, name: &str, table: &[u8]) -> (i32, String, String, String) {
    let file = bundle.path().join(format!("../{name}"));
    std::fs::write(&file, table).expect("table");
    let args = ["translations", "import", path(bundle.path()), path(&file)];
    let (code, out, err) = run_docent(&args);
    std::fs::remove_file(&file).expect("table removed");
    (code, out, err, file.display().to_string())
}

fn acts(bundle: &TempBundle) -> Vec<u8> {
    std::fs::read(bundle.path().join("acts.yaml")).expect("acts")
}

/// The refusal's first line, for a table of `file` with `n` cells refused.
fn refused(file: &str, n: usize) -> String {
    format!(
        "docent: {file}: the table is not imported, and nothing was written: {n} cell(s) would \
         put a text under the wrong act or write one that is no translation. Correct them in the \
         table and import it again:\n"
    )
}

/// Excel's "CSV UTF-8" in a German locale: a byte order mark, `;` between cells, CRLF after
/// each row, a line feed inside a quoted cell (Alt+Enter).
const EXCEL: &str = "\u{FEFF}key;en;de;where\r\n\
WELCOME/Text/1;Welcome to the museum!;Willkommen im Museum!;acts.yaml:2\r\n\
ROOM/Text/1;This room shows the Dutch masters.;Dieser Saal zeigt die niederländischen Meister.;acts.yaml:5\r\n\
ROOM/Text/2;The Night Watch is next door.;Die Nachtwache ist nebenan.;acts.yaml:5\r\n\
ADDRESS/Text/1;\"Museum Street 1\nAmsterdam\";\"Museumstraße 1\nAmsterdam\";acts.yaml:8\r\n\
PAINTING/Text/1;Mona Lisa;Mona Lisa;acts.yaml:10\r\n\
BYE/Text/1;Good bye, see you soon!;Auf Wiedersehen, bis bald!;acts.yaml:12\r\n";

#[test]
fn an_excel_table_with_semicolons_a_bom_crlf_and_a_line_break_in_a_cell_is_imported() {
    let bundle = bundle();
    let (code, out, err, file) = import(&bundle, "excel.csv", EXCEL.as_bytes());
    assert_eq!((code, err.as_str()), (0, ""), "{out}");
    assert_eq!(
        out,
        format!(
            "German (de) from {file}: 3 translation(s) added, 0 replaced, 2 unchanged.\n\
             Written: acts.yaml.\n"
        )
    );
    let written = String::from_utf8(acts(&bundle)).expect("utf-8");
    for added in [
        "  Text: \"Museum Street 1\\nAmsterdam\"\n  Text@de: \"Museumstraße 1\\nAmsterdam\"\n",
        "  Text: Mona Lisa\n  Text@de: Mona Lisa\n",
        "  Text: Good bye, see you soon!\n  Text@de: Auf Wiedersehen, bis bald!\n",
    ] {
        assert!(written.contains(added), "{added:?} in {written}");
    }
    let (code, out, _) = run_docent(&["check", path(bundle.path())]);
    assert_eq!(code, 0, "{out}");
    assert!(
        !out.contains("translation-same-as-original"),
        "a name: {out}"
    );
}

/// The first translation cell deleted with "shift cells up" in Excel: every translation
/// below it moved up a row, each now beside the act above its own.
#[test]
fn a_translation_column_shifted_by_a_row_refuses_the_table() {
    let bundle = bundle();
    let shifted = "\u{FEFF}key;en;de;where\r\n\
WELCOME/Text/1;Welcome to the museum!;Dieser Saal zeigt die niederländischen Meister.;acts.yaml:2\r\n\
ROOM/Text/1;This room shows the Dutch masters.;Die Nachtwache ist nebenan.;acts.yaml:5\r\n\
ROOM/Text/2;The Night Watch is next door.;\"Museumstraße 1\nAmsterdam\";acts.yaml:5\r\n\
ADDRESS/Text/1;\"Museum Street 1\nAmsterdam\";Mona Lisa;acts.yaml:8\r\n\
PAINTING/Text/1;Mona Lisa;Auf Wiedersehen, bis bald!;acts.yaml:10\r\n\
BYE/Text/1;Good bye, see you soon!;;acts.yaml:12\r\n";
    let (code, out, err, file) = import(&bundle, "shifted.csv", shifted.as_bytes());
    assert_eq!((code, out.as_str()), (1, ""));
    let slid = |line: usize, key: &str, text: &str, other: &str| {
        format!(
            "  {file}:{line}:3: row {line}, cell C{line}: the German cell of {key} holds \
             \"{text}\", the bundle's translation of {other}, the row below: the translations \
             look shifted against the keys by a row (a cell deleted or inserted with \"shift \
             cells up/down\", or one column sorted on its own). Undo that in the spreadsheet so \
             that each translation stands beside its own original.\n"
        )
    };
    assert_eq!(
        err,
        format!(
            "{}{}{}  {file}:4:3: row 4, cell C4: the German translation of ROOM/Text/2 has a \
             line break, and its English original has none: often two cells pasted into one, or \
             Alt+Enter (Excel) or Ctrl+Enter (LibreOffice) pressed by mistake. Remove the line \
             break, and check the rows below it.\n",
            refused(&file, 3),
            slid(
                2,
                "WELCOME/Text/1",
                "Dieser Saal zeigt die niederländischen Meister.",
                "ROOM/Text/1"
            ),
            slid(
                3,
                "ROOM/Text/1",
                "Die Nachtwache ist nebenan.",
                "ROOM/Text/2"
            ),
        )
    );
    assert_eq!(acts(&bundle), ACTS.as_bytes(), "byte for byte");
}

/// LibreOffice Calc's CSV (commas, no byte order mark, LF): error values where formulas
/// failed (Excel's `#REF!`, LibreOffice's `Err:502`), a cell with a line break where the
/// original has none (after a quoted two-line cell, so the row's line is not its number), a
/// sentence copied from the original; the name copied stays allowed.
#[test]
fn error_values_line_breaks_and_copied_originals_refuse_the_table_by_their_cells() {
    let bundle = bundle();
    let table = "key,en,de,where\n\
ADDRESS/Text/1,\"Museum Street 1\nAmsterdam\",\"Museumstraße 1\nAmsterdam\",acts.yaml:8\n\
WELCOME/Text/1,Welcome to the museum!,#REF!,acts.yaml:2\n\
ROOM/Text/1,This room shows the Dutch masters.,Err:502,acts.yaml:5\n\
ROOM/Text/2,The Night Watch is next door.,\"Die Nachtwache\nist nebenan.\",acts.yaml:5\n\
PAINTING/Text/1,Mona Lisa,Mona Lisa,acts.yaml:10\n\
BYE/Text/1,\"Good bye, see you soon!\",\"Good bye, see you soon!\",acts.yaml:12\n";
    let (code, out, err, file) = import(&bundle, "calc.csv", table.as_bytes());
    assert_eq!((code, out.as_str()), (1, ""));
    assert_eq!(
        err,
        format!(
            "{}  {file}:5:3: row 3, cell C3: the German translation of WELCOME/Text/1 is `#REF!`, \
             the error a spreadsheet shows where a formula failed (often because a row or column \
             it read was moved or deleted), not a text. Type the translation itself into the \
             cell, or paste it with \"paste special → values only\".\n  \
             {file}:6:3: row 4, cell C4: the German translation of ROOM/Text/1 is `Err:502`, the \
             error a spreadsheet shows where a formula failed (often because a row or column it \
             read was moved or deleted), not a text. Type the translation itself into the cell, \
             or paste it with \"paste special → values only\".\n  \
             {file}:7:3: row 5, cell C5: the German translation of ROOM/Text/2 has a line break, \
             and its English original has none: often two cells pasted into one, or Alt+Enter \
             (Excel) or Ctrl+Enter (LibreOffice) pressed by mistake. Remove the line break, and \
             check the rows below it.\n  \
             {file}:10:3: row 7, cell C7: the German translation of BYE/Text/1 is its English \
             original itself (\"Good bye, see you soon!\"): copied, not translated. Translate it, \
             or empty the cell to leave the text untranslated for now (a name or a number may \
             stay the same).\n",
            refused(&file, 4)
        )
    );
    assert_eq!(acts(&bundle), ACTS.as_bytes(), "byte for byte");
}

/// Units a CAT tool marks unfinished though their target holds text (XLIFF 1.2's
/// `needs-translation` and `new`, XLIFF 2.0's `initial`) and a target copied from its source
/// refuse the file by the unit's line; an empty unfinished target is only not translated yet.
#[test]
fn unfinished_and_copied_xliff_targets_refuse_the_file_by_their_unit() {
    let bundle = bundle();
    let xliff = r#"<?xml version="1.0" encoding="UTF-8"?>
<xliff version="1.2" xmlns="urn:oasis:names:tc:xliff:document:1.2">
  <file original="b" source-language="en" target-language="de" datatype="plaintext">
    <body>
      <trans-unit id="ROOM/Text/1">
        <source>This room shows the Dutch masters.</source>
        <target state="needs-translation">Dieser Raum zeigt die Holländer.</target>
      </trans-unit>
      <trans-unit id="ROOM/Text/2">
        <source>The Night Watch is next door.</source>
        <target state="new">Die Nachtwache ist nebenan.</target>
      </trans-unit>
      <trans-unit id="BYE/Text/1">
        <source>Good bye, see you soon!</source>
        <target state="translated">Good bye, see you soon!</target>
      </trans-unit>
      <trans-unit id="PAINTING/Text/1">
        <source>Mona Lisa</source>
        <target state="needs-translation"/>
      </trans-unit>
    </body>
  </file>
</xliff>
"#;
    let (code, out, err, file) = import(&bundle, "cat.xlf", xliff.as_bytes());
    assert_eq!((code, out.as_str()), (1, ""));
    let unfinished = |file: &str, line: usize, key: &str, state: &str| {
        format!(
            "  {file}:{line}: unit {key}: the target of {key} is marked state=\"{state}\": the \
             CAT tool says it is not translated yet, though it holds a text. Finish (confirm) \
             the segment in the CAT tool, or empty its target, and export the file from the \
             tool again.\n"
        )
    };
    assert_eq!(
        err,
        format!(
            "{}{}{}  {file}:13: unit BYE/Text/1: the German translation of BYE/Text/1 is its \
             English original itself (\"Good bye, see you soon!\"): copied, not translated. \
             Translate it, or empty the cell to leave the text untranslated for now (a name or a \
             number may stay the same).\n",
            refused(&file, 3),
            unfinished(&file, 5, "ROOM/Text/1", "needs-translation"),
            unfinished(&file, 9, "ROOM/Text/2", "new"),
        )
    );
    assert_eq!(acts(&bundle), ACTS.as_bytes(), "byte for byte");

    let xliff2 = r#"<?xml version="1.0" encoding="UTF-8"?>
<xliff version="2.0" xmlns="urn:oasis:names:tc:xliff:document:2.0" srcLang="en" trgLang="de">
  <file id="f1">
    <unit id="BYE/Text/1">
      <segment state="initial">
        <source>Good bye, see you soon!</source>
        <target>Auf Wiedersehen!</target>
      </segment>
    </unit>
  </file>
</xliff>
"#;
    let (code, out, err, file) = import(&bundle, "cat2.xlf", xliff2.as_bytes());
    assert_eq!((code, out.as_str()), (1, ""));
    assert_eq!(
        err,
        format!(
            "{}{}",
            refused(&file, 1),
            unfinished(&file, 4, "BYE/Text/1", "initial")
        )
    );
    assert_eq!(acts(&bundle), ACTS.as_bytes(), "byte for byte");

    let finished = xliff2.replace("state=\"initial\"", "state=\"translated\"");
    let (code, out, err, _) = import(&bundle, "cat2.xlf", finished.as_bytes());
    assert_eq!((code, err.as_str()), (0, ""), "{out}");
    let written = String::from_utf8(acts(&bundle)).expect("utf-8");
    assert!(
        written.ends_with("  Text: Good bye, see you soon!\n  Text@de: Auf Wiedersehen!\n"),
        "{written}"
    );
}

#[test]
fn check_warns_at_a_translation_that_is_its_original_but_not_at_a_name() {
    let bundle = TempBundle::new(
        "- Label: HELLO\n  Text: [Welcome to the museum!, Mona Lisa]\n  \
         Text@de: [Welcome to the museum!, Mona Lisa]\n",
    )
    .with_file("docent.yaml", "languages: [en, de]\n");
    let (code, out, _) = run_docent(&["check", path(bundle.path())]);
    assert_eq!(code, 0, "a warning: {out}");
    let warning = "warning[translation-same-as-original]: Text 1 of `Text@de` is its `en` \
                   original itself (\"Welcome to the museum!\"): copied, not translated, so a \
                   visitor in this language hears the original.\n --> acts.yaml:3:13\n";
    assert!(out.contains(warning), "{out}");
    assert!(
        out.contains(
            "= help: Write the translation here (only a name, a number or a single \
                      word may stay the same)."
        ),
        "{out}"
    );
    assert_eq!(
        out.matches("[translation-same-as-original]").count(),
        1,
        "not at Mona Lisa: {out}"
    );
}

/// Not a shift: the row below has the same original, so the same translation is right.
#[test]
fn two_texts_with_the_same_original_may_share_a_translation() {
    let bundle = TempBundle::new(
        "- Label: THANKS\n  Text: Thank you very much\n  Text@de: Vielen herzlichen Dank\n\
         - Label: THANKS_AGAIN\n  Text: Thank you very much\n",
    )
    .with_file("docent.yaml", "languages: [en, de]\n");
    let table = "key,en,de\n\
                 THANKS/Text/1,Thank you very much,Vielen herzlichen Dank\n\
                 THANKS_AGAIN/Text/1,Thank you very much,Vielen herzlichen Dank\n";
    let (code, out, err, _) = import(&bundle, "same.csv", table.as_bytes());
    assert_eq!((code, err.as_str()), (0, ""), "{out}");
    assert!(
        out.contains(": 1 translation(s) added, 0 replaced, 1 unchanged."),
        "{out}"
    );
}

/// A heading dragged to another place without its column: the `de` heading now stands over
/// the places of the originals.
#[test]
fn headings_moved_apart_from_their_columns_refuse_the_table() {
    let bundle = bundle();
    let table = "key,en,where,de\n\
                 BYE/Text/1,\"Good bye, see you soon!\",Auf Wiedersehen!,acts.yaml:12\n";
    let (code, out, err, file) = import(&bundle, "moved.csv", table.as_bytes());
    assert_eq!((code, out.as_str()), (1, ""));
    assert_eq!(
        err,
        format!(
            "{}  {file}:2:4: row 2, cell D2: the German cell of BYE/Text/1 holds `acts.yaml:12`, \
             a key or the place of an original (the `key` or `where` column), not a translation: \
             the headings and the columns under them look moved apart. Keep each heading above \
             its own column, as Docent wrote the table.\n",
            refused(&file, 1)
        )
    );
    assert_eq!(acts(&bundle), ACTS.as_bytes(), "byte for byte");
}

/// An XLIFF unit without its `<source>` cannot be checked against the bundle, and one whose
/// id the bundle no longer has is stale: each refuses the file by the unit's line.
#[test]
fn xliff_units_without_a_source_or_with_a_stale_id_refuse_the_file() {
    let bundle = bundle();
    let xliff = r#"<?xml version="1.0" encoding="UTF-8"?>
<xliff version="1.2" xmlns="urn:oasis:names:tc:xliff:document:1.2">
  <file original="b" source-language="en" target-language="de" datatype="plaintext">
    <body>
      <trans-unit id="BYE/Text/1">
        <target state="translated">Auf Wiedersehen!</target>
      </trans-unit>
      <trans-unit id="FAREWELL/Text/1">
        <source>Farewell</source>
        <target state="translated">Lebewohl</target>
      </trans-unit>
    </body>
  </file>
</xliff>
"#;
    let (code, out, err, file) = import(&bundle, "old.xlf", xliff.as_bytes());
    assert_eq!((code, out.as_str()), (1, ""));
    assert_eq!(
        err,
        format!(
            "{}  {file}:5: unit BYE/Text/1: BYE/Text/1 has no English original (`<source>`), so \
             Docent cannot check that the translation belongs to it. Keep each unit's source as \
             exported.\n  {file}:8: unit FAREWELL/Text/1: FAREWELL/Text/1: the bundle has no act \
             `FAREWELL` (renamed or removed since the table was made?); the table is older than \
             the bundle. Export the table again and copy the translations into it, or correct \
             the key as Docent wrote it.\n",
            refused(&file, 2)
        )
    );
    assert_eq!(acts(&bundle), ACTS.as_bytes(), "byte for byte");
}

/// A cell inserted with "shift cells down" pushes the last translation below the last key.
#[test]
fn a_translation_below_the_last_key_refuses_the_table() {
    let bundle = bundle();
    let table = "key,en,de\n\
                 BYE/Text/1,\"Good bye, see you soon!\",\n\
                 ,,Auf Wiedersehen!\n";
    let (code, out, err, file) = import(&bundle, "down.csv", table.as_bytes());
    assert_eq!((code, out.as_str()), (1, ""));
    assert_eq!(
        err,
        format!(
            "{}  {file}:3:1: row 3, cell A3: this row has a translation but no key: the rows or \
             columns look shifted in the spreadsheet. Undo the move, so that each translation \
             stands in the row of its key and original.\n",
            refused(&file, 1)
        )
    );
    assert_eq!(acts(&bundle), ACTS.as_bytes(), "byte for byte");
}
