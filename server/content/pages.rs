//! Finding the act labels that touchscreen pages trigger: `data-act="LABEL"` attributes in
//! `pages/**/*.html` (and `.htm`).
//!
//! This is a small tag scanner, not an HTML parser: it looks at attributes inside tags only
//! (so text, comments and script selectors such as `[data-act="X"]` are ignored) and accepts
//! double, single or no quotes, as browsers do.

use std::path::Path;
use std::sync::Arc;

use crate::content::model::{Located, Pos};
use crate::content::paths::{BundleArea, list_files, resolve_in_bundle};

/// Pages larger than this are not scanned; no real touchscreen page comes near it.
const MAX_PAGE_BYTES: u64 = 8 * 1024 * 1024;

/// Every `data-act` value in the bundle's pages, in file order, with the position of the
/// value (after its opening quote) in the page file.
pub(crate) fn page_act_references(root: &Path) -> Vec<Located<String>> {
    let mut found = Vec::new();
    for rel in list_files(root, BundleArea::Pages) {
        let lower = rel.to_ascii_lowercase();
        if !(lower.ends_with(".html") || lower.ends_with(".htm")) {
            continue;
        }
        // Through the gate: a page symlinked from outside the bundle is never read.
        let Ok(path) = resolve_in_bundle(root, BundleArea::Pages, &rel) else {
            continue;
        };
        if std::fs::metadata(&path).map_or(true, |m| m.len() > MAX_PAGE_BYTES) {
            continue;
        }
        let Ok(bytes) = std::fs::read(&path) else {
            continue;
        };
        let file: Arc<str> = Arc::from(format!("pages/{rel}"));
        found.extend(scan(&file, &String::from_utf8_lossy(&bytes)));
    }
    found
}

/// The `data-act` values in one HTML text.
fn scan(file: &Arc<str>, html: &str) -> Vec<Located<String>> {
    let mut found = Vec::new();
    let mut cursor = Cursor {
        text: html,
        at: 0,
        line: 1,
        column: 1,
    };
    while let Some(c) = cursor.peek() {
        if cursor.rest().starts_with("<!--") {
            cursor.skip_past("-->");
        } else if c == '<' && cursor.rest()[1..].starts_with(|n: char| n.is_ascii_alphabetic()) {
            cursor.bump();
            let name = scan_tag(&mut cursor, file, &mut found);
            // Script and style bodies are code: `a<b` there is not a tag.
            for raw_text in ["script", "style"] {
                if name.eq_ignore_ascii_case(raw_text) {
                    cursor.skip_to_ignoring_case(&format!("</{raw_text}"));
                }
            }
        } else {
            cursor.bump();
        }
    }
    found
}

/// Reads the attributes of one tag, up to and including its `>`; returns the tag name.
fn scan_tag<'t>(
    cursor: &mut Cursor<'t>,
    file: &Arc<str>,
    found: &mut Vec<Located<String>>,
) -> &'t str {
    let tag = cursor.take_while(|c| !c.is_whitespace() && c != '>' && c != '/');
    loop {
        cursor.take_while(|c| c.is_whitespace() || c == '/');
        match cursor.peek() {
            None => return tag,
            Some('>') => {
                cursor.bump();
                return tag;
            }
            Some(_) => {}
        }
        let name = cursor.take_while(|c| !c.is_whitespace() && c != '=' && c != '>' && c != '/');
        if name.is_empty() {
            // A stray `=` or quote: step over it so the loop always advances.
            cursor.bump();
            continue;
        }
        cursor.take_while(char::is_whitespace);
        if cursor.peek() != Some('=') {
            continue;
        }
        cursor.bump();
        cursor.take_while(char::is_whitespace);
        let (value, pos) = read_value(cursor, file);
        if name.eq_ignore_ascii_case("data-act") {
            found.push(Located {
                value: value.to_owned(),
                pos,
            });
        }
    }
}

/// An attribute value in double, single or no quotes, and where it starts.
fn read_value<'t>(cursor: &mut Cursor<'t>, file: &Arc<str>) -> (&'t str, Pos) {
    let quote = cursor.peek().filter(|&q| q == '"' || q == '\'');
    if quote.is_some() {
        cursor.bump();
    }
    let pos = Pos::new(file.clone(), cursor.line, cursor.column);
    let value = match quote {
        Some(q) => {
            let value = cursor.take_while(|c| c != q);
            cursor.bump();
            value
        }
        None => cursor.take_while(|c| !c.is_whitespace() && c != '>'),
    };
    (value, pos)
}

/// A position in the text that keeps line and column (in characters) as it moves.
struct Cursor<'t> {
    text: &'t str,
    at: usize,
    line: u32,
    column: u32,
}

impl<'t> Cursor<'t> {
    fn rest(&self) -> &'t str {
        &self.text[self.at..]
    }

    fn peek(&self) -> Option<char> {
        self.rest().chars().next()
    }

    fn bump(&mut self) {
        let Some(c) = self.peek() else { return };
        self.at += c.len_utf8();
        if c == '\n' {
            self.line += 1;
            self.column = 1;
        } else {
            self.column += 1;
        }
    }

    fn take_while(&mut self, keep: impl Fn(char) -> bool) -> &'t str {
        let start = self.at;
        while self.peek().is_some_and(&keep) {
            self.bump();
        }
        &self.text[start..self.at]
    }

    fn skip_past(&mut self, end: &str) {
        while !self.rest().is_empty() && !self.rest().starts_with(end) {
            self.bump();
        }
        for _ in end.chars() {
            self.bump();
        }
    }

    /// Moves to the start of `end` (ASCII, any case), or to the end of the text.
    fn skip_to_ignoring_case(&mut self, end: &str) {
        while !self.rest().is_empty()
            && !self
                .rest()
                .get(..end.len())
                .is_some_and(|r| r.eq_ignore_ascii_case(end))
        {
            self.bump();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn values(html: &str) -> Vec<(String, u32, u32)> {
        let file: Arc<str> = Arc::from("pages/index.html");
        scan(&file, html)
            .into_iter()
            .map(|l| (l.value, l.pos.line, l.pos.column))
            .collect()
    }

    #[test]
    fn finds_values_in_any_quoting_with_their_positions() {
        let html = [
            "<p>",
            "  <button data-act=\"WELCOME\">Hi</button>",
            "<a data-act='OK' href=x>ok</a>",
            "<div class=c DATA-ACT=WHERE_FROM>",
        ];
        assert_eq!(
            values(&html.join("\n")),
            [
                ("WELCOME".into(), 2, 21),
                ("OK".into(), 3, 14),
                ("WHERE_FROM".into(), 4, 23)
            ]
        );
    }

    #[test]
    fn ignores_text_comments_scripts_and_similar_names() {
        let html = [
            "data-act=\"TEXT\" <!-- <b data-act=\"OLD\"> --> <b data-action=\"NO\" data-acts=NO>",
            "<script>if (a<b data-act=\"JS\") {}</script> <i data-act = \"SPACED\" />",
        ];
        assert_eq!(values(&html.join("\n")), [("SPACED".into(), 2, 59)]);
    }

    #[test]
    fn survives_broken_markup() {
        assert_eq!(
            values("<b data-act=\"UNCLOSED"),
            [("UNCLOSED".into(), 1, 14)]
        );
        assert!(values("<b = ' \" data-act").is_empty());
        assert!(values("<").is_empty());
        assert_eq!(values("<b data-act=é>"), [("é".into(), 1, 13)]);
    }
}
