//! `docent translations export|import`: the bundle's texts as a table a translator fills in a
//! spreadsheet (CSV) or a CAT tool (XLIFF 1.2), and the filled table written back into the
//! acts files as `Text@de:` lists beside the originals.
//!
//! - `table.rs`: the rows (one per text alternative), keyed `LABEL/Variant/N`.
//! - `csv.rs` and `xliff.rs`: each format written and read back into [`Entry`]s.
//! - `import.rs`: the entries checked against the bundle into whole translations to write.
//! - `refuse.rs`: the cells that refuse a whole import (a shifted row or column, a stale or
//!   repeated key, a spreadsheet's error value or formula, an unfinished or copied target).
//! - `same.rs`: when a translation may equal its original (a name, a number).
//! - `quote.rs`: a text as YAML must spell it to read back exactly.
//! - `write.rs`: the edit of one acts file's text, touching nothing else.
//! - `save.rs`: the result loaded in memory and checked, then written atomically.
//! - `located.rs`: a diagnostic of that load inside a written text, told by its row and key.
//! - `cli.rs`: the command line, what it prints and its exit codes (docs/AUTHORING.md,
//!   "Working with a translator").

pub mod csv;
pub mod import;
pub mod located;
pub mod quote;
pub mod refuse;
pub mod same;
pub mod save;
pub mod table;
pub mod write;
pub mod xliff;

use std::fmt;
use std::path::Path;

/// The file formats a table is written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Comma-separated values (RFC 4180, UTF-8 with a byte order mark), for spreadsheets.
    Csv,
    /// XLIFF 1.2, for CAT tools.
    Xliff,
}

impl Format {
    /// The format a file's name says (`.csv`, `.xlf`, `.xliff`; any case), if any.
    pub fn of_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "csv" => Some(Format::Csv),
            "xlf" | "xliff" => Some(Format::Xliff),
            _ => None,
        }
    }

    /// The format of a table read back: by its name, else by its first bytes (XML starts
    /// with `<`).
    pub fn of_table(path: &Path, bytes: &[u8]) -> Format {
        Format::of_path(path).unwrap_or_else(|| {
            let start = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
            match start.iter().find(|b| !b.is_ascii_whitespace()) {
                Some(b'<') => Format::Xliff,
                _ => Format::Csv,
            }
        })
    }
}

/// Where an entry was read, for messages: a spreadsheet row or an XLIFF unit's line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Place {
    /// The spreadsheet's row number (the header is row 1).
    Row(usize),
    /// The line of an XLIFF `<trans-unit>`.
    Line(usize),
}

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Place::Row(n) => write!(f, "row {n}"),
            Place::Line(n) => write!(f, "line {n}"),
        }
    }
}

/// Which column of a CSV table holds what (0-based), so a message can name the cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Columns {
    /// The keys' column.
    pub key: usize,
    /// The originals' column, if the table has one.
    pub source: Option<usize>,
    /// The translations' column.
    pub target: usize,
}

/// One text of a table read back: its key as written, the original it was made from (when
/// the table carries it) and the translation (empty when the cell is).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Entry {
    /// Where it was read.
    pub place: Place,
    /// The line of the file its row or unit starts on (a CSV row may span several lines).
    pub line: usize,
    /// Its columns (CSV), to name a cell as the spreadsheet does (`C4`).
    pub columns: Option<Columns>,
    /// The XLIFF `state` that says its target is not finished (`needs-translation`, `new`,
    /// XLIFF 2's `initial`), if the file says so.
    pub unfinished: Option<String>,
    /// The key as written (`GREETING/TextChild/2`).
    pub key: String,
    /// The default language's text as exported, if the table has it.
    pub source: Option<String>,
    /// The translation.
    pub translation: String,
}

/// A table read back: the language its translations are in (as written) and its entries.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReadTable {
    /// The translations' language as the table names it (`de`).
    pub language: String,
    /// The entries in the table's order.
    pub entries: Vec<Entry>,
    /// Said once about the table as a whole (a missing source column).
    pub notes: Vec<String>,
}

/// Why a table cannot be read at all (nothing is imported).
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The bytes are not UTF-8.
    #[error(
        "the table is not UTF-8 text (line {line}). Save it as \"CSV UTF-8\" (Excel) or with \
         the character set \"Unicode (UTF-8)\" (LibreOffice), then import it again"
    )]
    NotUtf8 {
        /// The line of the first byte that is not.
        line: usize,
    },
    /// The table's shape is not one Docent writes (columns, elements, languages).
    #[error("{0}")]
    Shape(String),
}

/// The 1-based line of byte `offset` in `bytes`.
pub(crate) fn line_of(bytes: &[u8], offset: usize) -> usize {
    let end = offset.min(bytes.len());
    bytes[..end].iter().filter(|&&b| b == b'\n').count() + 1
}
