//! Cells a spreadsheet would run as a formula (CSV injection, as OWASP describes it): Excel,
//! LibreOffice and Google Sheets take a cell that starts with `=`, `+`, `-` or `@` (and, in
//! some versions, one that starts with a tab or a carriage return before one of these) as a
//! formula, and a formula can fetch a URL, start a program (DDE) or send the sheet's data
//! away. Docent's CSVs carry text that others wrote: a kiosk's refused act label, a robot's
//! words, a translator's cells. So every CSV Docent writes (`corpus export --format csv`,
//! `translations export --format csv`) goes through [`neutralise`], which puts a `'` before
//! such a cell, as OWASP advises: spreadsheets show the text instead of running it. A
//! translations table read back goes through [`restore`], which takes that `'` away again,
//! and [`formula_start`] tells the import which cells are still formulas.

use std::borrow::Cow;

/// The characters that make a spreadsheet read a cell as a formula when it starts with one.
pub const FORMULA_STARTS: [char; 6] = ['=', '+', '-', '@', '\t', '\r'];

/// What Docent puts before a cell that starts with one of [`FORMULA_STARTS`].
pub const NEUTRALISER: char = '\'';

/// `cell` as it is safe to write into a CSV: with a `'` before it when it starts with one of
/// [`FORMULA_STARTS`], unchanged otherwise (and not copied).
pub fn neutralise(cell: &str) -> Cow<'_, str> {
    if formula_start(cell).is_some() {
        Cow::Owned(format!("{NEUTRALISER}{cell}"))
    } else {
        Cow::Borrowed(cell)
    }
}

/// `cell` as it was before [`neutralise`]: without the `'` when one of [`FORMULA_STARTS`]
/// follows it. A `'` before anything else is the cell's own and stays.
pub fn restore(cell: &str) -> &str {
    match cell.strip_prefix(NEUTRALISER) {
        Some(rest) if formula_start(rest).is_some() => rest,
        _ => cell,
    }
}

/// The error values Excel and LibreOffice show (and save into a CSV) where a formula failed,
/// in English and as a German, French or Spanish Excel writes them (`#NV`, `#BEZUG!`,
/// `#VALEUR!`, `#¡REF!`).
pub const ERROR_VALUES: [&str; 27] = [
    "#N/A",
    "#REF!",
    "#VALUE!",
    "#NAME?",
    "#DIV/0!",
    "#NULL!",
    "#NUM!",
    "#SPILL!",
    "#CALC!",
    "#GETTING_DATA",
    "#FIELD!",
    "#NV",
    "#BEZUG!",
    "#WERT!",
    "#ZAHL!",
    "#ÜBERLAUF!",
    "#VALEUR!",
    "#NOM?",
    "#NUL!",
    "#NOMBRE!",
    "#N/D",
    "#¡REF!",
    "#¡VALOR!",
    "#¿NOMBRE?",
    "#¡DIV/0!",
    "#¡NULO!",
    "#¡NUM!",
];

/// The spreadsheet error value `cell` holds (`#N/A`, `#REF!`, LibreOffice's `Err:502`), if
/// it holds nothing else: what a formula leaves in a cell when a row or column it read was
/// moved or deleted.
pub fn error_value(cell: &str) -> Option<&str> {
    let cell = cell.trim();
    let known = ERROR_VALUES.iter().any(|e| e.eq_ignore_ascii_case(cell));
    let libreoffice = cell
        .strip_prefix("Err:")
        .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()));
    (known || libreoffice).then_some(cell)
}

/// The character of [`FORMULA_STARTS`] that `cell` starts with, if any.
pub fn formula_start(cell: &str) -> Option<char> {
    cell.chars().next().filter(|c| FORMULA_STARTS.contains(c))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formula_cells_get_a_quote_and_lose_it_when_read_back() {
        for cell in [
            "=HYPERLINK(\"http://x\",\"y\")",
            "+1",
            "-2",
            "@SUM(A1)",
            "\tx",
            "\rx",
        ] {
            let written = neutralise(cell);
            assert_eq!(written, format!("'{cell}"));
            assert_eq!(restore(&written), cell);
        }
    }

    #[test]
    fn error_values_are_told_from_texts() {
        for cell in [
            "#N/A",
            " #ref! ",
            "#NAME?",
            "Err:502",
            "#BEZUG!",
            "#NV",
            "#¡VALOR!",
        ] {
            assert_eq!(error_value(cell), Some(cell.trim()), "{cell:?}");
        }
        for cell in ["", "#1 in the hall", "N/A", "Err:", "Err:x", "#N/A or not"] {
            assert_eq!(error_value(cell), None, "{cell:?}");
        }
    }

    #[test]
    fn other_cells_are_left_alone_both_ways() {
        for cell in ["", "Hello", "'quoted'", "'s Morgens", "1,5", " =x", "'"] {
            assert!(matches!(neutralise(cell), Cow::Borrowed(_)), "{cell:?}");
            assert_eq!(restore(cell), cell, "{cell:?}");
        }
    }
}
