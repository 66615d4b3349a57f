//! The table as CSV for spreadsheets: RFC 4180 (the `csv` crate), UTF-8 with a byte order
//! mark so that Excel and LibreOffice open it as UTF-8 rather than guess a local code page.
//! Columns: `key`, the default language's tag (the original), the translated language's tag
//! (the translation, empty when missing) and `where` (the original's file and line).
//!
//! Read back, the columns are found by their headings in any order (a translator may add a
//! column for remarks), and a table saved with `;` or tabs between cells (Excel in many
//! locales) is read too. The originals' column must be there: each row's original is
//! compared with the bundle's (`import.rs`), which is what tells a moved row.
//!
//! A cell a spreadsheet would run as a formula (one that starts with `=`, `+`, `-`, `@`, a tab
//! or a carriage return) is written with a `'` before it (`crate::spreadsheet`), and that `'`
//! is taken away again when the table is read back. A translation that still starts with
//! `=`, `@`, a tab or a carriage return is refused by the import (`import.rs`).

use std::io::{self, Write};

use crate::Language;
use crate::spreadsheet::{neutralise, restore};

use super::table::Row;
use super::{Columns, Entry, Place, ReadError, ReadTable, line_of};

/// The byte order mark that tells spreadsheets the file is UTF-8.
const BOM: &[u8] = b"\xEF\xBB\xBF";
/// The heading of the key column.
const KEY: &str = "key";
/// The heading of the column saying where the original is written.
const WHERE: &str = "where";

/// Writes `rows` as CSV: the original in `source`, translations into `target`.
pub fn write_csv(
    rows: &[Row],
    source: &Language,
    target: &Language,
    out: &mut dyn Write,
) -> io::Result<()> {
    out.write_all(BOM)?;
    let mut writer = ::csv::WriterBuilder::new()
        .terminator(::csv::Terminator::CRLF)
        .from_writer(out);
    writer.write_record([KEY, source.as_str(), target.as_str(), WHERE])?;
    for row in rows {
        let key = row.key.to_string();
        let translation = row.translation.as_deref().unwrap_or_default();
        let cells = [key.as_str(), &row.source, translation, &row.place];
        writer.write_record(cells.map(|cell| neutralise(cell).into_owned()))?;
    }
    writer.flush()
}

/// Reads a CSV table back. `default` is the bundle's default language (the originals'
/// column); `wanted` the language asked for, else the table's one other language column.
pub fn read_csv(
    bytes: &[u8],
    default: &Language,
    wanted: Option<&Language>,
) -> Result<ReadTable, ReadError> {
    let bytes = bytes.strip_prefix(BOM).unwrap_or(bytes);
    if let Err(e) = std::str::from_utf8(bytes) {
        let line = line_of(bytes, e.valid_up_to());
        return Err(ReadError::NotUtf8 { line });
    }
    let delimiter = delimiter(bytes);
    let mut reader = ::csv::ReaderBuilder::new()
        .delimiter(delimiter)
        .flexible(true)
        .has_headers(false)
        .from_reader(bytes);
    let mut header = ::csv::StringRecord::new();
    match reader.read_record(&mut header) {
        Ok(true) => {}
        Ok(false) => return Err(ReadError::Shape("the table is empty".to_owned())),
        Err(e) => return Err(ReadError::Shape(format!("the table cannot be read: {e}"))),
    }
    let headings: Vec<String> = header.iter().map(|h| h.trim().to_owned()).collect();
    let columns = find_columns(&headings, default, wanted)?;
    let mut table = ReadTable {
        language: headings[columns.target].clone(),
        entries: Vec::new(),
        notes: Vec::new(),
    };
    let mut record = ::csv::StringRecord::new();
    for row in 2.. {
        // Where the reader stands before the row: its start, once the line break that ended
        // the row before is passed (the record's own position is not its first byte).
        let before = usize::try_from(reader.position().byte()).unwrap_or(usize::MAX);
        let skipped = bytes.get(before..).unwrap_or_default();
        let start = before
            + skipped
                .iter()
                .take_while(|b| matches!(b, b'\r' | b'\n'))
                .count();
        match reader.read_record(&mut record) {
            Ok(true) => {}
            Ok(false) => break,
            Err(e) => {
                return Err(ReadError::Shape(format!(
                    "row {row} of the table cannot be read: {e}"
                )));
            }
        }
        if record.iter().all(|cell| cell.trim().is_empty()) {
            continue; // a blank row a spreadsheet kept at the end
        }
        // A line break inside a cell is a line feed, as Excel and LibreOffice type it; one
        // saved as CRLF reads the same.
        let cell = |i: usize| restore(record.get(i).unwrap_or_default()).replace("\r\n", "\n");
        table.entries.push(Entry {
            place: Place::Row(row),
            line: line_of(bytes, start),
            columns: Some(columns),
            unfinished: None,
            key: cell(columns.key).trim().to_owned(),
            source: columns.source.map(cell),
            translation: cell(columns.target),
        });
    }
    Ok(table)
}

/// The cell separator: the one of `,`, `;` and tab that makes a `key` heading.
fn delimiter(bytes: &[u8]) -> u8 {
    let first_line = bytes.split(|&b| b == b'\n').next().unwrap_or_default();
    let heads_key = |d: u8| {
        (first_line.split(|&b| b == d)).any(|cell| {
            let cell = cell.trim_ascii();
            let cell = cell.strip_prefix(b"\"").unwrap_or(cell);
            let cell = cell.strip_suffix(b"\"").unwrap_or(cell);
            cell.eq_ignore_ascii_case(KEY.as_bytes())
        })
    };
    [b',', b';', b'\t']
        .into_iter()
        .find(|&d| heads_key(d))
        .unwrap_or(b',')
}

/// Finds the columns by their headings.
fn find_columns(
    headings: &[String],
    default: &Language,
    wanted: Option<&Language>,
) -> Result<Columns, ReadError> {
    let listed = headings.join(", ");
    let position = |name: &str| headings.iter().position(|h| h.eq_ignore_ascii_case(name));
    let Some(key) = position(KEY) else {
        return Err(ReadError::Shape(format!(
            "the table has no `key` column (its first row has: {listed}). Keep the first \
                 row as Docent wrote it: key, {default}, the translated language, where"
        )));
    };
    let source = position(default.as_str());
    let languages: Vec<usize> = (headings.iter().enumerate())
        .filter(|(i, h)| *i != key && Some(*i) != source && Language::parse(h).is_some())
        .map(|(i, _)| i)
        .collect();
    let target = match wanted {
        Some(wanted) => position(wanted.as_str()).ok_or_else(|| {
            ReadError::Shape(format!(
                "the table has no `{wanted}` column (its first row has: {listed})"
            ))
        })?,
        None => match languages.as_slice() {
            [one] => *one,
            [] => {
                return Err(ReadError::Shape(format!(
                    "the table has no column of translations: its first row has {listed}, \
                         and no heading other than `{default}` is a language tag such as `de`"
                )));
            }
            _ => {
                return Err(ReadError::Shape(format!(
                    "the table has several columns of translations ({listed}): say which \
                         to import with --language"
                )));
            }
        },
    };
    let Some(source) = source else {
        return Err(ReadError::Shape(format!(
            "the table has no `{default}` column with the original texts (its first row has: \
                 {listed}). Docent compares each row's original with the bundle's, so that a row \
                 moved in the spreadsheet is never imported under the wrong act: keep the \
                 `{default}` column and its heading as Docent wrote them (or export the table \
                 again and copy the translations into it)"
        )));
    };
    Ok(Columns {
        key,
        source: Some(source),
        target,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::translations::table::TextKey;

    fn lang(tag: &str) -> Language {
        Language::parse(tag).expect("tag")
    }

    #[test]
    fn a_table_is_written_with_a_bom_and_read_back_the_same() {
        let rows = vec![Row {
            key: TextKey::parse("A/Text/1").expect("key"),
            source: "Hello, \"you\"\nthere".to_owned(),
            translation: None,
            place: "acts.yaml:3".to_owned(),
        }];
        let mut bytes = Vec::new();
        write_csv(&rows, &lang("en"), &lang("de"), &mut bytes).expect("written");
        assert!(bytes.starts_with(BOM));
        let text = String::from_utf8(bytes[3..].to_vec()).expect("utf-8");
        assert_eq!(
            text,
            "key,en,de,where\r\nA/Text/1,\"Hello, \"\"you\"\"\nthere\",,acts.yaml:3\r\n"
        );
        let table = read_csv(&bytes, &lang("en"), None).expect("read");
        assert_eq!(table.language, "de");
        assert_eq!(
            table.entries[0].source.as_deref(),
            Some(rows[0].source.as_str())
        );
        assert_eq!(table.entries[0].place, Place::Row(2));
    }

    #[test]
    fn semicolons_and_extra_columns_are_read() {
        let text = "remark;DE;key;en\nok;Hallo;A/Text/1;Hello\n;;;\n";
        let table = read_csv(text.as_bytes(), &lang("en"), None).expect("read");
        assert_eq!(table.language, "DE");
        assert_eq!(table.entries.len(), 1, "the blank row is skipped");
        assert_eq!(table.entries[0].translation, "Hallo");
        assert_eq!(table.entries[0].key, "A/Text/1");
    }

    #[test]
    fn a_table_in_a_local_code_page_is_refused_with_how_to_save_it() {
        let latin1 = b"key,en,de\nA/Text/1,Hello,Gr\xfc\xdf dich\n";
        let e = read_csv(latin1, &lang("en"), None).expect_err("refused");
        assert!(matches!(e, ReadError::NotUtf8 { line: 2 }), "{e}");
    }
}
