//! The text of a page, `.css` or `.js` file: UTF-8 (a byte-order mark and CRLF line ends
//! are fine), or else a problem saying how to save it as UTF-8; and positions in it.

use std::sync::Arc;

use crate::DiagnosticCode;
use crate::diagnostic::Diagnostic;
use crate::encoding::not_utf8;
use crate::model::Pos;

/// The text of a file, with the byte-order mark removed, and how to find positions in it.
pub(crate) struct SourceText {
    /// The file, named from the bundle root.
    pub file: Arc<str>,
    /// The text; bytes that are not UTF-8 are replaced by `�` (one character each).
    pub text: String,
    /// Byte offsets where lines start.
    line_starts: Vec<usize>,
}

impl SourceText {
    /// The text of `bytes`, reporting a file that is not UTF-8. `None` for UTF-16 files,
    /// whose text cannot be read as UTF-8 at all.
    pub fn decode(file: Arc<str>, bytes: &[u8], out: &mut Vec<Diagnostic>) -> Option<Self> {
        let bytes = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
        let Some(found) = not_utf8(bytes) else {
            let text = std::str::from_utf8(bytes).unwrap_or_default().to_owned();
            return Some(Self::new(file, text));
        };
        if found.utf16 {
            let pos = Pos::new(file, 1, 1);
            out.push(Diagnostic::error(
                DiagnosticCode::PageEncoding,
                &pos,
                found.message,
            ));
            return None;
        }
        let valid = String::from_utf8_lossy(&bytes[..found.at]);
        let pos = Self::new(file.clone(), valid.into_owned()).pos(found.at);
        out.push(Diagnostic::error(
            DiagnosticCode::PageEncoding,
            &pos,
            found.message,
        ));
        let text = String::from_utf8_lossy(bytes).into_owned();
        Some(Self::new(file, text))
    }

    /// A text that is already UTF-8.
    pub fn new(file: Arc<str>, text: String) -> Self {
        let line_starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        SourceText {
            file,
            text,
            line_starts,
        }
    }

    /// The line and column (in characters) of the byte offset `at`.
    pub fn pos(&self, at: usize) -> Pos {
        let at = at.min(self.text.len());
        let line = self.line_starts.partition_point(|&start| start <= at);
        let start = self.line_starts[line.saturating_sub(1)];
        let column = self
            .text
            .get(start..at)
            .map_or(0, |before| before.chars().count());
        Pos::new(
            self.file.clone(),
            u32::try_from(line).unwrap_or(u32::MAX),
            u32::try_from(column + 1).unwrap_or(u32::MAX),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decoded(bytes: &[u8]) -> (Option<String>, Vec<(u32, u32)>) {
        let mut out = Vec::new();
        let text = SourceText::decode(Arc::from("pages/a.html"), bytes, &mut out);
        (
            text.map(|t| t.text),
            out.iter().map(|d| (d.line, d.column)).collect(),
        )
    }

    #[test]
    fn a_bom_and_crlf_are_accepted() {
        assert_eq!(
            decoded(b"\xef\xbb\xbf<p>\r\n\xc3\xa9</p>"),
            (Some("<p>\r\né</p>".into()), vec![])
        );
    }

    #[test]
    fn windows_1252_is_reported_at_its_first_byte() {
        let (text, at) = decoded(b"<p>\r\n  \xd6ffnungszeiten \xe9</p>");
        assert_eq!(at, [(2, 3)]);
        assert_eq!(text.as_deref(), Some("<p>\r\n  �ffnungszeiten �</p>"));
    }

    #[test]
    fn utf16_is_reported_at_the_start() {
        assert_eq!(decoded(b"\xff\xfe<\0p\0>\0"), (None, vec![(1, 1)]));
        assert_eq!(decoded(b"<\0h\0t\0m\0l\0>\0"), (None, vec![(1, 1)]));
    }

    #[test]
    fn positions_count_characters() {
        let text = SourceText::new(Arc::from("f"), "ab\néé<x".into());
        let p = text.pos(text.text.find('<').expect("tag"));
        assert_eq!((p.line, p.column), (2, 3));
        assert_eq!((text.pos(0).line, text.pos(0).column), (1, 1));
    }
}
