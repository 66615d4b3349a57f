//! Every refusal and every reported row of `docent translations`, with its exact words and
//! exit status, and the acts file untouched where nothing may be written: a bundle with
//! errors, a language not translated into, a table that cannot be read, an act written
//! inline, a stale key, a moved original, a repeated key, a formula (status 1, each cell
//! named, nothing written); empty cells, incomplete lists and markup (status 3, the rest
//! written). Tables as Excel and LibreOffice save them are in `translations_sheets.rs`. A translation the loader refuses is told by its row
//! in `translations_rows.rs`.

use crate::common;

use std::path::Path;

use common::TempBundle;
use common::process::run_docent;

const ACTS: &str = "\
- Label: HELLO
  Text: [Hello, Hi, Hey]
  Text@de: [Hallo, Servus, He]
- Label: BYE
  Text: Good bye
- Label: THANKS
  Text: Thank you
";

fn bundle() -> TempBundle {
    TempBundle::new(ACTS).with_file("docent.yaml", "languages: [en, de]\n")
}

fn path(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// Imports `table` (written as a file named `name` in the bundle's folder) into `bundle`.
fn import(bundle: &TempBundle, name: &str, table: &[u8], extra: &[&str]) -> (i32, String, String) {
    let file = bundle.path().join(name);
    std::fs::write(&file, table).expect("table");
    let mut args = vec!["translations", "import", path(bundle.path()), path(&file)];
    args.extend(extra);
    run_docent(&args)
}

fn acts(bundle: &TempBundle) -> String {
    std::fs::read_to_string(bundle.path().join("acts.yaml")).expect("acts")
}

#[test]
fn a_bundle_with_errors_is_refused() {
    let broken = TempBundle::new("- Label: A\n  Text: [Hello]\n  Cmds: [FLY high]\n");
    let dir = path(broken.path());
    let (code, out, err) = run_docent(&["translations", "export", dir, "--language", "de"]);
    assert_eq!((code, out.as_str()), (1, ""));
    let first = format!(
        "docent: {dir} has errors, so its texts cannot be exported or imported (`docent check \
         {dir}` shows them with their lines):\n  acts.yaml:3:10: error[unknown-verb]"
    );
    assert!(err.starts_with(&first), "{err}");
}

#[test]
fn a_language_the_texts_are_not_translated_into_is_refused() {
    let bundle = bundle();
    let dir = path(bundle.path());
    for (language, message) in [
        (
            "fr",
            "`fr` is not one of the bundle's languages (en, de). Add it to `languages:` in \
             docent.yaml first. Name one it is translated into: de.",
        ),
        (
            "EN",
            "`en` is the bundle's default language: its texts are the originals (`Text:`), not \
             translations. Name one it is translated into: de.",
        ),
        (
            "german",
            "`german` is not a language tag. A language is a short language tag: two or three \
             letters (`en`, `de`, `fr`), optionally a hyphen and a region (`pt-br`, `en-gb`).",
        ),
    ] {
        let export = run_docent(&["translations", "export", dir, "--language", language]);
        assert_eq!(export, (1, String::new(), format!("docent: {message}\n")));
        let table = b"key,en,de\nBYE/Text/1,Good bye,Tschuess\n";
        let imported = import(&bundle, "t.csv", table, &["--language", language]);
        assert_eq!(imported, (1, String::new(), format!("docent: {message}\n")));
    }
    let (code, _, err) = import(
        &bundle,
        "fr.csv",
        b"key,en,fr\nBYE/Text/1,Good bye,Au revoir\n",
        &[],
    );
    let file = bundle.path().join("fr.csv");
    assert_eq!(
        (code, err),
        (
            1,
            format!(
                "docent: {}: the table's translations: `fr` is not one of the bundle's languages \
                 (en, de). Add it to `languages:` in docent.yaml first. Name one it is \
                 translated into: de.\n",
                file.display()
            )
        )
    );
    assert_eq!(acts(&bundle), ACTS);
}

#[test]
fn an_output_without_a_known_extension_needs_a_format() {
    let bundle = bundle();
    let out = bundle.path().join("table.txt");
    let (code, _, err) = run_docent(&[
        "translations",
        "export",
        path(bundle.path()),
        "--language",
        "de",
        "--output",
        path(&out),
    ]);
    let expected = format!(
        "docent: {} does not end in .csv, .xlf or .xliff: say the format with --format csv or \
         --format xliff\n",
        out.display()
    );
    assert_eq!((code, err), (1, expected));
    assert!(!out.exists());
}

#[test]
fn tables_that_cannot_be_read_are_refused_with_how_to_fix_them() {
    let bundle = bundle();
    let cases: [(&str, &[u8], &[&str], &str); 6] = [
        (
            "latin1.csv",
            b"key,en,de\nBYE/Text/1,Good bye,Tsch\xfcss\n",
            &[],
            "the table is not UTF-8 text (line 2). Save it as \"CSV UTF-8\" (Excel) or with the \
             character set \"Unicode (UTF-8)\" (LibreOffice), then import it again",
        ),
        (
            "nokey.csv",
            b"id,en,de\nBYE/Text/1,Good bye,Tschuess\n",
            &[],
            "the table has no `key` column (its first row has: id, en, de). Keep the first row \
             as Docent wrote it: key, en, the translated language, where",
        ),
        (
            "nosource.csv",
            b"key,English,de\nBYE/Text/1,Good bye,Tschuess\n",
            &[],
            "the table has no `en` column with the original texts (its first row has: key, \
             English, de). Docent compares each row's original with the bundle's, so that a row \
             moved in the spreadsheet is never imported under the wrong act: keep the `en` \
             column and its heading as Docent wrote them (or export the table again and copy \
             the translations into it)",
        ),
        (
            "two.csv",
            b"key,en,de,fr\nBYE/Text/1,Good bye,Tschuess,Salut\n",
            &[],
            "the table has several columns of translations (key, en, de, fr): say which to \
             import with --language",
        ),
        (
            "fr.xlf",
            b"<xliff version=\"1.2\"><file source-language=\"en\" target-language=\"fr\"><body/></file></xliff>",
            &["--language", "de"],
            "the XLIFF file's translations are in `fr` (target-language), not `de` as \
             --language says",
        ),
        (
            "broken.xlf",
            b"<xliff version=\"1.2\">\n<file>\n</xliff>",
            &[],
            "the XLIFF file is not well-formed XML at line 3: ",
        ),
    ];
    for (name, table, extra, message) in cases {
        let (code, out, err) = import(&bundle, name, table, extra);
        let file = bundle.path().join(name);
        let start = format!("docent: {}: {message}", file.display());
        assert_eq!((code, out.as_str()), (1, ""), "{name}");
        assert!(err.starts_with(&start), "{name}: {err}");
        assert!(err.ends_with("; nothing was imported\n"), "{name}: {err}");
    }
    assert_eq!(acts(&bundle), ACTS);
}

#[test]
fn an_act_written_inline_cannot_take_a_translation() {
    let bundle = TempBundle::new("- {Label: A, Text: Hello}\n")
        .with_file("docent.yaml", "languages: [en, de]\n");
    let (code, _, err) = import(&bundle, "t.csv", b"key,en,de\nA/Text/1,Hello,Hallo\n", &[]);
    assert_eq!(
        (code, err.as_str()),
        (
            1,
            "docent: acts.yaml:1:14: `Text@de` is written inside a mapping on one line ({...}); \
             write the act with one key per line, then import again\n"
        )
    );
}

#[test]
fn empty_cells_and_incomplete_lists_are_reported_and_the_rest_written() {
    let bundle = bundle();
    let table = "\
key,en,de,where
HELLO/Text/1,Hello,Grüß dich,acts.yaml:2
HELLO/Text/3,Hey,Na,acts.yaml:2
THANKS/Text/1,Thank you,,acts.yaml:7
,,,a remark without a key
BYE/Text/1,Good bye,Tschuess,acts.yaml:5
";
    let (code, out, err) = import(&bundle, "t.csv", table.as_bytes(), &[]);
    let file = bundle.path().join("t.csv");
    assert_eq!((code, err.as_str()), (3, ""));
    assert_eq!(
        out,
        format!(
            "German (de) from {}: 1 translation(s) added, 0 replaced, 0 unchanged.
Written: acts.yaml.
2 problem(s):
  row 4: THANKS/Text/1 has no German translation (the cell is empty).
  HELLO/Text keeps its current German texts: it has 3 texts, and a translation needs all of them, but the table has none for HELLO/Text/2.
",
            file.display()
        )
    );
    assert_eq!(
        acts(&bundle),
        ACTS.replace(
            "  Text: Good bye\n",
            "  Text: Good bye\n  Text@de: Tschuess\n"
        )
    );
}

/// A stale or edited key, an original that is not the bundle's and a key given twice each
/// refuse the whole table with its cell: nothing is written, even for the rows that are fine.
#[test]
fn stale_keys_moved_rows_and_repeated_keys_refuse_the_whole_table() {
    let bundle = bundle();
    let table = "\
key,en,de,where
HELLO/Text/1,Hello,Grüß dich,acts.yaml:2
BYE/Text/1,Goodbye,Tschüss,acts.yaml:5
NOPE/Text/1,x,y,
HELLO/Other/1,x,y,
BYE/Text/2,x,y,
garbage,x,y,
THANKS/Text/1,Thank you,Danke,acts.yaml:7
THANKS/Text/1,Thank you,Vielen Dank,acts.yaml:7
";
    let (code, out, err) = import(&bundle, "t.csv", table.as_bytes(), &[]);
    let file = bundle.path().join("t.csv");
    let f = file.display();
    assert_eq!((code, out.as_str()), (1, ""));
    assert_eq!(
        err,
        format!(
            "docent: {f}: the table is not imported, and nothing was written: 6 cell(s) would put a text under the wrong act or write one that is no translation. Correct them in the table and import it again:
  {f}:3:2: row 3, cell B3: the English original of BYE/Text/1 in the table is \"Goodbye\", the bundle's is \"Good bye\": the row was moved or sorted apart from its key, or the original changed since the table was made. Put the row back beside its key, or export the table again and check this translation against the new original.
  {f}:4:1: row 4, cell A4: NOPE/Text/1: the bundle has no act `NOPE` (renamed or removed since the table was made?); the table is older than the bundle. Export the table again and copy the translations into it, or correct the key as Docent wrote it.
  {f}:5:1: row 5, cell A5: HELLO/Other/1: the act `HELLO` has no `Other`; the table is older than the bundle. Export the table again and copy the translations into it, or correct the key as Docent wrote it.
  {f}:6:1: row 6, cell A6: BYE/Text/2: `Text` of `BYE` has 1 text(s), so there is no number 2; the table is older than the bundle. Export the table again and copy the translations into it, or correct the key as Docent wrote it.
  {f}:7:1: row 7, cell A7: `garbage` is not a text key (keys look like LABEL/Variant/N, e.g. GREETING/Text/1): the columns look shifted, or the key was edited. Keep the `key` column as Docent wrote it.
  {f}:9:1: row 9, cell A9: THANKS/Text/1 is given a second time (first in row 8): a row copied or moved in the spreadsheet. Keep one row for each key and delete the other.
"
        )
    );
    assert_eq!(acts(&bundle), ACTS, "nothing written");
}

#[test]
fn xliff_units_are_reported_by_their_line() {
    let bundle = bundle();
    let xliff = r#"<?xml version="1.0" encoding="UTF-8"?>
<xliff version="1.2" xmlns="urn:oasis:names:tc:xliff:document:1.2">
  <file original="b" source-language="en" target-language="de" datatype="plaintext">
    <body>
      <trans-unit id="BYE/Text/1">
        <source>Good bye</source>
        <target>Auf <g id="1">Wiedersehen</g></target>
      </trans-unit>
      <trans-unit id="THANKS/Text/1">
        <source>Thank you</source>
        <target state="needs-translation"/>
        <alt-trans><target>Merci</target></alt-trans>
      </trans-unit>
    </body>
  </file>
</xliff>
"#;
    let (code, out, _) = import(&bundle, "t.xlf", xliff.as_bytes(), &[]);
    let file = bundle.path().join("t.xlf");
    assert_eq!(
        (code, out),
        (
            3,
            format!(
                "German (de) from {}: 0 translation(s) added, 0 replaced, 0 unchanged.
2 problem(s):
  line 5 (BYE/Text/1): the target contains markup (<g>), which a spoken text cannot hold; it is not imported. Write it as plain text.
  line 9: THANKS/Text/1 has no German translation (its target is empty).
",
                file.display()
            )
        )
    );
    assert_eq!(acts(&bundle), ACTS);
}

#[test]
fn a_bundle_of_one_language_is_told_how_to_add_another() {
    let bundle = TempBundle::new("- Label: BYE\n  Text: Good bye\n");
    let dir = path(bundle.path());
    let (code, _, err) = run_docent(&["translations", "export", dir, "--language", "de"]);
    assert_eq!(
        (code, err.as_str()),
        (
            1,
            "docent: `de` is not one of the bundle's languages (en). Add it to `languages:` in \
             docent.yaml (`languages: [en, de]`).\n"
        )
    );
    let (code, _, err) = run_docent(&["translations", "export", dir, "--language", "en"]);
    assert_eq!(
        (code, err.as_str()),
        (
            1,
            "docent: `en` is the bundle's default language: its texts are the originals \
             (`Text:`), not translations. The bundle has no other language yet: add one to \
             `languages:` in docent.yaml (`languages: [en, de]`).\n"
        )
    );
}

/// Regression (issue 24): formula cells went raw into the translations CSV and came back raw
/// from it. Now every cell that starts with `=`, `+`, `-`, `@`, a tab or a carriage return is
/// written with a `'` before it; read back, that `'` goes; a translation that still starts
/// with `=`, `@`, a tab or a carriage return refuses the table by its cell (issue 26: nothing
/// is written), one with `-` or `+` is a text like any other.
#[test]
fn formula_cells_are_neutralised_in_the_csv_and_refused_on_import() {
    let acts = "\
- Label: SALE
  Text: '-20 % for members'
  Text@de: '=HYPERLINK(\"http://attacker.invalid\",\"Rabatt\")'
- Label: PLUS
  Text: '+1 more room upstairs'
- Label: MORE
  Text: Two more rooms
- Label: BYE
  Text: Good bye
- Label: THANKS
  Text: Thank you
";
    let bundle = TempBundle::new(acts).with_file("docent.yaml", "languages: [en, de]\n");
    let dir = path(bundle.path());
    let export = || {
        let args = ["translations", "export", dir, "--language", "de"];
        let (code, out, err) = run_docent(&args);
        assert_eq!(code, 0, "{err}");
        out
    };
    let table = export();
    for row in [
        "SALE/Text/1,'-20 % for members,\"'=HYPERLINK(\"\"http://attacker.invalid\"\",\"\"Rabatt\"\")\",acts.yaml:2\r\n",
        "PLUS/Text/1,'+1 more room upstairs,,acts.yaml:5\r\n",
    ] {
        assert!(table.contains(row), "{row:?} in {table}");
    }

    let filled = "key,en,de\r\n\
                  SALE/Text/1,'-20 % for members,'-20 % für Mitglieder\r\n\
                  PLUS/Text/1,'+1 more room upstairs,\"=HYPERLINK(\"\"http://attacker.invalid\"\",\"\"x\"\")\"\r\n\
                  MORE/Text/1,Two more rooms,+2 Räume oben\r\n\
                  BYE/Text/1,Good bye,@SUM(1+1)\r\n\
                  THANKS/Text/1,Thank you,\"\tDanke\"\r\n";
    let (code, out, err) = import(&bundle, "t.csv", filled.as_bytes(), &[]);
    let file = bundle.path().join("t.csv");
    let f = file.display();
    assert_eq!((code, out.as_str()), (1, ""), "{err}");
    assert_eq!(
        err,
        format!(
            "docent: {f}: the table is not imported, and nothing was written: 3 cell(s) would put a text under the wrong act or write one that is no translation. Correct them in the table and import it again:
  {f}:3:3: row 3, cell C3: the German translation of PLUS/Text/1 starts with `=`, which a spreadsheet runs as a formula (a spoken text never starts so). Write the text without it.
  {f}:5:3: row 5, cell C5: the German translation of BYE/Text/1 starts with `@`, which a spreadsheet runs as a formula (a spoken text never starts so). Write the text without it.
  {f}:6:3: row 6, cell C6: the German translation of THANKS/Text/1 starts with a tab, which a spreadsheet runs as a formula (a spoken text never starts so). Write the text without it.
"
        )
    );
    let now = std::fs::read_to_string(bundle.path().join("acts.yaml")).expect("acts");
    assert_eq!(now, acts, "nothing written");
    let corrected = "key,en,de\r\n\
                     SALE/Text/1,'-20 % for members,'-20 % für Mitglieder\r\n\
                     MORE/Text/1,Two more rooms,+2 Räume oben\r\n";
    let (code, out, err) = import(&bundle, "t.csv", corrected.as_bytes(), &[]);
    assert_eq!((code, err.as_str()), (0, ""));
    assert!(
        out.ends_with(": 1 translation(s) added, 1 replaced, 0 unchanged.\nWritten: acts.yaml.\n"),
        "{out}"
    );
    std::fs::remove_file(&file).expect("table removed");
    let again = export();
    for row in [
        "SALE/Text/1,'-20 % for members,'-20 % für Mitglieder,acts.yaml:2\r\n",
        "PLUS/Text/1,'+1 more room upstairs,,acts.yaml:5\r\n",
        "MORE/Text/1,Two more rooms,'+2 Räume oben,acts.yaml:7\r\n",
        "BYE/Text/1,Good bye,,acts.yaml:10\r\n",
        "THANKS/Text/1,Thank you,,acts.yaml:12\r\n",
    ] {
        assert!(again.contains(row), "{row:?} in {again}");
    }
}

/// Regression (issue 24): deep nesting made the XLIFF reader's time grow with the square of
/// the file. A file nested deeper than 64 elements is refused whole, by its line, and nothing
/// is written.
#[test]
fn an_xliff_file_nested_too_deep_is_refused_by_its_line() {
    let bundle = bundle();
    let mut xliff = String::from(
        "<?xml version=\"1.0\"?>\n<xliff version=\"1.2\"><file source-language=\"en\" \
         target-language=\"de\"><body><trans-unit id=\"BYE/Text/1\"><source>Good bye</source>\
         <target>",
    );
    let depth = 100_000;
    xliff.push_str(&"<g>Tschüss\n".repeat(depth));
    xliff.push_str(&"</g>".repeat(depth));
    xliff.push_str("</target></trans-unit></body></file></xliff>\n");
    let (code, out, err) = import(&bundle, "deep.xlf", xliff.as_bytes(), &[]);
    let file = bundle.path().join("deep.xlf");
    assert_eq!(
        (code, out.as_str(), err),
        (
            1,
            "",
            format!(
                "docent: {}: line 61: elements are nested more than 64 deep, which no XLIFF file \
                 of translations needs (Docent's nest 5 deep); export the table again and fill \
                 that in; nothing was imported\n",
                file.display()
            )
        )
    );
    assert_eq!(acts(&bundle), ACTS);
}
