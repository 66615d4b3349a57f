//! Documents that are not plain text, saved under a `.yaml` name: a Word document (`.docx`,
//! a ZIP holding `word/`; `.doc`, an OLE2 compound file), an OpenDocument text (a ZIP whose
//! `mimetype` says `application/vnd.oasis.opendocument...`), RTF (`{\rtf`), PDF (`%PDF`), a
//! spreadsheet, any other archive or binary file. Read as text they would be blamed on the
//! encoding (`file-encoding`: "save it as UTF-8"), which no word processor's "Save as UTF-8"
//! fixes; told instead what the file is and how to get plain text out of it
//! (`not-plain-text`, at line 1).

/// What a word processor or other program wrote, by the file's first bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Document {
    /// Word 2007 and later (`.docx`).
    Docx,
    /// Word 97 to 2003 (`.doc`), an OLE2 compound file naming a `WordDocument` stream.
    Doc,
    /// LibreOffice or OpenOffice Writer (`.odt`).
    OpenDocumentText,
    /// Excel, LibreOffice Calc (`.xlsx`, `.xls`, `.ods`).
    Spreadsheet,
    /// Another ZIP archive (a compressed folder, Apple Pages, PowerPoint...).
    Zip,
    /// Another OLE2 compound file (older Office files).
    OfficeFile,
    /// Rich Text Format (WordPad, TextEdit).
    Rtf,
    /// PDF.
    Pdf,
    /// Bytes no text editor writes (a picture, a program...).
    Binary,
}

/// How far into a file the names of a ZIP's or OLE2's parts are looked for.
const LOOK_BYTES: usize = 64 * 1024;

/// Why `bytes` are not a plain-text file, in words for the person who saved it; `None` for
/// text (UTF-16 included: told as an encoding by `encoding::not_utf8`).
pub(crate) fn not_plain_text(bytes: &[u8]) -> Option<String> {
    let document = document_kind(bytes)?;
    let (what, how) = match document {
        Document::Docx | Document::Doc => (
            if document == Document::Docx {
                "a Word document (.docx)"
            } else {
                "a Word document (.doc, Word 97 to 2003)"
            },
            "In Word, choose File, Save as, file type \"Plain Text (*.txt)\", and in the next \
             window \"Unicode (UTF-8)\"; then rename the file to end in .yaml.",
        ),
        Document::OpenDocumentText => (
            "a LibreOffice or OpenOffice Writer document (.odt)",
            "In Writer, choose File, Save as, file type \"Text (.txt)\", tick \"Edit filter \
             settings\" and choose \"Unicode (UTF-8)\"; then rename the file to end in .yaml.",
        ),
        Document::Rtf => (
            "a Rich Text document (RTF, from WordPad or TextEdit)",
            "In WordPad, choose Save as, \"Plain text document\"; in TextEdit, Format, Make \
             Plain Text, then save with the encoding Unicode (UTF-8).",
        ),
        Document::Pdf => (
            "a PDF document",
            "A PDF cannot be saved back as text: open the document it was made from, or copy \
             the text into a text editor.",
        ),
        Document::Spreadsheet => (
            "a spreadsheet (Excel or LibreOffice Calc)",
            "Acts are written as text, not as a table; a translator's table is imported with \
             `docent translations import` after saving it as CSV.",
        ),
        Document::Zip => (
            "a ZIP archive (a compressed folder, or a document of a program that packs its \
             files, such as Apple Pages)",
            "Unpack it, or open it in its program and save it as plain text (UTF-8).",
        ),
        Document::OfficeFile => (
            "an older Microsoft Office file",
            "Open it in its program and save it as plain text (UTF-8).",
        ),
        Document::Binary => (
            "not text at all (it holds bytes no text editor writes: a picture, a program, a \
             damaged file)",
            "Check that this is the file you meant.",
        ),
    };
    Some(format!(
        "This file is {what}, not plain text, so Docent cannot read it as YAML. {how} Or, \
         better, write the file in a text editor (Notepad, TextEdit in plain-text mode, VS \
         Code): word processors add formatting and change quotes and dashes."
    ))
}

fn document_kind(bytes: &[u8]) -> Option<Document> {
    let head = &bytes[..bytes.len().min(LOOK_BYTES)];
    let has = |needle: &[u8]| head.windows(needle.len()).any(|w| w == needle);
    let utf16 =
        |text: &str| -> Vec<u8> { text.encode_utf16().flat_map(u16::to_le_bytes).collect() };
    if head.starts_with(b"PK\x03\x04") {
        return Some(if has(b"application/vnd.oasis.opendocument.text") {
            Document::OpenDocumentText
        } else if has(b"application/vnd.oasis.opendocument.spreadsheet") || has(b"xl/") {
            Document::Spreadsheet
        } else if has(b"word/") {
            Document::Docx
        } else {
            Document::Zip
        });
    }
    if head.starts_with(b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1") {
        return Some(if has(&utf16("WordDocument")) {
            Document::Doc
        } else if has(&utf16("Workbook")) || has(&utf16("Book")) {
            Document::Spreadsheet
        } else {
            Document::OfficeFile
        });
    }
    let text = head.strip_prefix(b"\xef\xbb\xbf").unwrap_or(head);
    if text.starts_with(b"{\\rtf") {
        return Some(Document::Rtf);
    }
    if text.starts_with(b"%PDF") {
        return Some(Document::Pdf);
    }
    // A NUL byte is in no text but UTF-16 (told as an encoding); nor are most control bytes.
    let control = |b: &u8| *b < 0x20 && !matches!(b, b'\t' | b'\n' | b'\r' | 0x0c | 0x1b);
    let binary = head.contains(&0) || head.iter().filter(|b| control(b)).count() * 20 > head.len();
    (binary && !utf16_text(bytes)).then_some(Document::Binary)
}

/// UTF-16 text, told as an encoding: a byte-order mark, or (as `encoding::is_utf16` finds it)
/// many NUL bytes, here all on even or all on odd places as in letters of UTF-16, where a
/// picture's or a program's NULs fall anywhere.
fn utf16_text(bytes: &[u8]) -> bool {
    if !crate::encoding::is_utf16(bytes) {
        return false;
    }
    let head = &bytes[..bytes.len().min(64)];
    let nuls = |parity: usize| (head.iter().enumerate()).any(|(i, b)| *b == 0 && i % 2 == parity);
    bytes.starts_with(b"\xff\xfe") || bytes.starts_with(b"\xfe\xff") || nuls(0) != nuls(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn documents_are_told_by_their_first_bytes_and_text_is_left_alone() {
        let kind = |bytes: &[u8]| document_kind(bytes);
        assert_eq!(kind(b"- Label: A\n  Text: Hi\n"), None);
        assert_eq!(kind("- Label: Ä\n".as_bytes()), None);
        assert_eq!(
            kind(b"- Label: A\n  Text: \xd6ffnungszeiten\n"),
            None,
            "Windows-1252"
        );
        let utf16: Vec<u8> = "- Label: A"
            .encode_utf16()
            .flat_map(u16::to_le_bytes)
            .collect();
        assert_eq!(kind(&utf16), None, "UTF-16 is an encoding");
        assert_eq!(kind(b"{\\rtf1\\ansi - Label: A\\par}"), Some(Document::Rtf));
        assert_eq!(kind(b"%PDF-1.7\n%\xe2\xe3\xcf\xd3\n"), Some(Document::Pdf));
        assert_eq!(
            kind(b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR"),
            Some(Document::Binary)
        );
        assert_eq!(
            kind(b"PK\x03\x04\x14\0\0\0word/document.xml"),
            Some(Document::Docx)
        );
        let message = not_plain_text(b"PK\x03\x04\x14\0\0\0word/document.xml").expect("docx");
        assert!(message.contains("a Word document (.docx)"), "{message}");
    }
}
