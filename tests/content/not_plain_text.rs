//! A document that is not plain text saved as an acts file or as `docent.yaml`: a Word
//! document (`.docx`, `.doc`), a LibreOffice text (`.odt`), RTF, PDF, a picture. Told what the
//! file is and how to get plain text out of it, at line 1 (`not-plain-text`), never blamed on
//! the encoding (`file-encoding`, "save it as UTF-8", was the message before, at a byte in the
//! middle of the archive). The `.docx` and `.odt` are real ZIP files written by Python's
//! zipfile; the others are built from their published layouts.

use crate::common;

use std::path::Path;
use std::process::Command;

use common::check::{bundle, check, places, yaml};
use docent_content::Severity;

/// Writes, with Python's zipfile, a Word document (`docx`) or an OpenDocument text (`odt`)
/// holding two lines of acts, as Word and LibreOffice lay them out.
fn zipped_document(kind: &str, path: &Path) {
    const SCRIPT: &str = r#"
import sys, zipfile
kind, path = sys.argv[1], sys.argv[2]
lines = ["- Label: WELCOME", "  Text: Welcome to the museum!"]
with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
    if kind == "docx":
        z.writestr("[Content_Types].xml", '<?xml version="1.0" encoding="UTF-8"?><Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types"><Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/><Override PartName="/word/document.xml" ContentType="application/vnd.openxmlformats-officedocument.wordprocessingml.document.main+xml"/></Types>')
        z.writestr("_rels/.rels", '<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships"><Relationship Id="rId1" Type="http://schemas.openxmlformats.org/officeDocument/2006/relationships/officeDocument" Target="word/document.xml"/></Relationships>')
        body = "".join("<w:p><w:r><w:t xml:space=\"preserve\">%s</w:t></w:r></w:p>" % l for l in lines)
        z.writestr("word/document.xml", '<?xml version="1.0" encoding="UTF-8"?><w:document xmlns:w="http://schemas.openxmlformats.org/wordprocessingml/2006/main"><w:body>%s</w:body></w:document>' % body)
    else:
        # OpenDocument: `mimetype` first and stored, as the format requires.
        z.writestr(zipfile.ZipInfo("mimetype"), "application/vnd.oasis.opendocument.text", compress_type=zipfile.ZIP_STORED)
        body = "".join("<text:p>%s</text:p>" % l for l in lines)
        z.writestr("content.xml", '<?xml version="1.0" encoding="UTF-8"?><office:document-content xmlns:office="urn:oasis:names:tc:opendocument:xmlns:office:1.0" xmlns:text="urn:oasis:names:tc:opendocument:xmlns:text:1.0"><office:body><office:text>%s</office:text></office:body></office:document-content>' % body)
        z.writestr("META-INF/manifest.xml", '<?xml version="1.0" encoding="UTF-8"?><manifest:manifest xmlns:manifest="urn:oasis:names:tc:opendocument:xmlns:manifest:1.0"><manifest:file-entry manifest:full-path="/" manifest:media-type="application/vnd.oasis.opendocument.text"/></manifest:manifest>')
"#;
    let status = Command::new("python3")
        .args(["-c", SCRIPT, kind])
        .arg(path)
        .status()
        .expect("python3 runs");
    assert!(status.success(), "python3 wrote no {kind}");
}

/// A Word 97-2003 `.doc`: an OLE2 compound file (its signature, a 512-byte header) whose
/// directory names the `Root Entry` and the `WordDocument` stream, in UTF-16 as Word writes
/// them.
fn word_97_document() -> Vec<u8> {
    let mut bytes = b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1".to_vec();
    bytes.resize(512, 0);
    for name in ["Root Entry", "WordDocument", "1Table"] {
        let mut entry: Vec<u8> = name.encode_utf16().flat_map(u16::to_le_bytes).collect();
        entry.resize(128, 0);
        bytes.extend(entry);
    }
    bytes.extend(b"- Label: WELCOME\r  Text: Welcome to the museum!\r");
    bytes
}

/// The problems of a bundle whose `acts.yaml` holds `bytes` (and a good second acts file).
fn acts_file_of(bytes: &[u8]) -> docent_content::LoadReport {
    let good = yaml(&["- Label: GOODBYE", "  Text: Goodbye!"]);
    let dir = bundle(&[("more.yaml", &good)]);
    std::fs::write(dir.path().join("acts.yaml"), bytes).expect("write");
    check(dir.path())
}

#[test]
fn a_word_document_saved_as_yaml_is_named_with_how_to_save_it_as_plain_text() {
    let dir = tempfile::tempdir().expect("temp dir");
    let docx = dir.path().join("acts.docx");
    zipped_document("docx", &docx);
    let report = acts_file_of(&std::fs::read(&docx).expect("docx"));
    // Before: `file-encoding` at acts.yaml:1:18, "not saved as UTF-8".
    assert_eq!(
        places(&report),
        [("not-plain-text", "acts.yaml:1:1".to_owned())]
    );
    let told = &report.diagnostics[0];
    assert_eq!(told.severity, Severity::Error);
    for words in [
        "This file is a Word document (.docx), not plain text",
        "\"Plain Text (*.txt)\"",
        "\"Unicode (UTF-8)\"",
        "write the file in a text editor",
    ] {
        assert!(told.message.contains(words), "{words}: {}", told.message);
    }
    // Word 97 to 2003, an OLE2 file.
    let report = acts_file_of(&word_97_document());
    assert_eq!(
        places(&report),
        [("not-plain-text", "acts.yaml:1:1".to_owned())]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("a Word document (.doc, Word 97 to 2003)"),
        "{}",
        report.diagnostics[0].message
    );
}

#[test]
fn an_opendocument_rtf_pdf_or_picture_saved_as_yaml_is_told_what_it_is() {
    let dir = tempfile::tempdir().expect("temp dir");
    let odt = dir.path().join("acts.odt");
    zipped_document("odt", &odt);
    let rtf =
        b"{\\rtf1\\ansi\\deff0 {\\fonttbl {\\f0 Calibri;}}\\f0 - Label: WELCOME\\par }".to_vec();
    let pdf = b"%PDF-1.4\n%\xe2\xe3\xcf\xd3\n1 0 obj\n<< /Type /Catalog >>\nendobj\n".to_vec();
    let png = b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0\0\x01\0\0\0\x01\x08\x06\0\0\0".to_vec();
    // Before: `file-encoding` (odt, pdf, png) or a `yaml-syntax` about a bracket (rtf).
    for (bytes, what, how) in [
        (
            std::fs::read(&odt).expect("odt"),
            "a LibreOffice or OpenOffice Writer document (.odt)",
            "file type \"Text (.txt)\"",
        ),
        (rtf, "a Rich Text document (RTF", "Make Plain Text"),
        (pdf, "a PDF document", "cannot be saved back as text"),
        (png, "not text at all", "the file you meant"),
    ] {
        let report = acts_file_of(&bytes);
        assert_eq!(
            places(&report),
            [("not-plain-text", "acts.yaml:1:1".to_owned())],
            "{what}"
        );
        let message = &report.diagnostics[0].message;
        assert!(
            message.contains(what) && message.contains(how),
            "{what}: {message}"
        );
    }
}

#[test]
fn docent_yaml_saved_as_a_word_document_is_told_once_and_the_acts_still_checked() {
    let dir = tempfile::tempdir().expect("temp dir");
    let docx = dir.path().join("docent.docx");
    zipped_document("docx", &docx);
    let acts = yaml(&["- Label: WELCOME", "  Text: Welcome!"]);
    let bundle = bundle(&[("acts.yaml", &acts)]);
    std::fs::copy(&docx, bundle.path().join("docent.yaml")).expect("copy");
    let report = check(bundle.path());
    assert_eq!(
        places(&report),
        [("not-plain-text", "docent.yaml:1:1".to_owned())]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("a Word document (.docx)")
    );
    // Plain text that is not UTF-8 is still an encoding, with its own advice.
    std::fs::write(
        bundle.path().join("docent.yaml"),
        b"home: \xd6ffnung.html\n",
    )
    .expect("1252");
    let codes: Vec<&str> = (check(bundle.path()).diagnostics.iter())
        .map(|d| d.code.as_str())
        .collect();
    assert_eq!(codes, ["file-encoding"]);
}
