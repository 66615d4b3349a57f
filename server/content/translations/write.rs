//! The edit of one acts file: a translation list (`TextChild@de:`) put directly after its
//! original's list, or written over the existing list of that language where it stands.
//! Everything else in the file stays as it was, byte for byte: comments, order, blank lines,
//! the quoting of other texts, the line endings.
//!
//! The file is read as lines around the places the loader reported: an entry is its key's
//! line and the lines below it indented deeper (or, for a list written at the key's own
//! indent, its `- ` items); comments and blank lines after its last line stay outside it.
//! The new list copies its original's shape: `[a, b]` on one line, a single text after the
//! key, or a list of `- ` items at the original's indent.

use std::ops::Range;

use crate::Pos;

use super::quote::{Context, yaml_text};

/// One translation to write into a file.
#[derive(Clone, Debug)]
pub struct Edit {
    /// Where the original's key (`TextChild:`) is written.
    pub original: Pos,
    /// Where this language's list (`TextChild@de:`) is written already, if it is.
    pub existing: Option<Pos>,
    /// The key to write (`TextChild@de`).
    pub key: String,
    /// The texts, as many as the original has.
    pub texts: Vec<String>,
}

/// Why a file cannot be edited.
#[derive(Debug, PartialEq, Eq, thiserror::Error)]
pub enum EditError {
    /// The key is not at the start of its line (a `{Text: ...}` mapping written inline).
    #[error(
        "{file}:{line}:{column}: `{key}` is written inside a mapping on one line ({{...}}); \
         write the act with one key per line, then import again"
    )]
    Inline {
        /// The file.
        file: String,
        /// The original's line.
        line: u32,
        /// The original's column.
        column: u32,
        /// The key being written.
        key: String,
    },
    /// The reported place is not in the file (it changed since it was loaded).
    #[error("{file}:{line}: the file changed while the import ran; import again")]
    Moved {
        /// The file.
        file: String,
        /// The line expected.
        line: u32,
    },
}

/// An entry of an act's mapping as the text has it.
struct Entry {
    /// Byte where the key starts.
    key_start: usize,
    /// Byte after the entry's last line (after its line break, if it has one).
    end: usize,
    /// Whether its last line ends with a line break.
    ends_with_break: bool,
    /// The key's column, 0-based: the indent of the act's keys.
    indent: usize,
    /// How the value is written.
    shape: Shape,
}

/// How a list of texts is written.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Shape {
    /// `Key: [a, b]` on one line.
    Flow,
    /// `Key: text` on one line.
    Single,
    /// `Key:` then `- text` lines at this indent.
    Items(usize),
}

/// An acts file's text with the edits made, and where each written text landed in it.
#[derive(Debug)]
pub struct Edited {
    /// The file's new text.
    pub text: String,
    /// For each edit (in the order given), the byte range of each of its texts in `text`, as
    /// written (with its quotes): a diagnostic of the new text is traced to its row by these.
    pub texts: Vec<Vec<Range<usize>>>,
}

/// A part of the file replaced: (start, end, the new text, the edit's index, its texts'
/// ranges within the new text).
type Span = (usize, usize, String, usize, Vec<Range<usize>>);

/// `source` (an acts file's text) with `edits` made.
pub fn edit_file(source: &str, edits: &[Edit]) -> Result<Edited, EditError> {
    let lines = line_starts(source);
    let newline = if source.contains("\r\n") {
        "\r\n"
    } else {
        "\n"
    };
    let mut spans: Vec<Span> = Vec::new();
    for (index, edit) in edits.iter().enumerate() {
        let original = entry(source, &lines, &edit.original, &edit.key)?;
        let (list, ranges) = render(&edit.key, &edit.texts, original.shape, newline);
        match &edit.existing {
            Some(pos) => {
                let old = entry(source, &lines, pos, &edit.key)?;
                let list = if old.ends_with_break {
                    list
                } else {
                    list.trim_end_matches(newline).to_owned()
                };
                spans.push((old.key_start, old.end, list, index, ranges));
            }
            None => {
                let indent = " ".repeat(original.indent);
                let (text, lead) = if original.ends_with_break {
                    (format!("{indent}{list}"), indent.len())
                } else {
                    let lead = newline.len() + indent.len();
                    let list = list.trim_end_matches(newline);
                    (format!("{newline}{indent}{list}"), lead)
                };
                let ranges = ranges.iter().map(|r| r.start + lead..r.end + lead);
                spans.push((original.end, original.end, text, index, ranges.collect()));
            }
        }
    }
    // Built from the start, so each text's place in the new file is known.
    spans.sort_by_key(|(start, ..)| *start);
    let mut out = String::with_capacity(source.len());
    let mut placed = vec![Vec::new(); edits.len()];
    let mut copied = 0;
    for (start, end, text, index, ranges) in spans {
        let start = start.max(copied);
        out.push_str(&source[copied..start]);
        let at = out.len();
        placed[index] = ranges.iter().map(|r| r.start + at..r.end + at).collect();
        out.push_str(&text);
        copied = end.max(start);
    }
    out.push_str(&source[copied..]);
    Ok(Edited {
        text: out,
        texts: placed,
    })
}

/// The byte where each line starts, and the text's length at the end.
fn line_starts(source: &str) -> Vec<usize> {
    let mut starts = vec![0];
    starts.extend(source.match_indices('\n').map(|(i, _)| i + 1));
    if starts.last() != Some(&source.len()) {
        starts.push(source.len());
    }
    starts
}

/// The entry whose key the loader placed at `pos`.
fn entry(source: &str, starts: &[usize], pos: &Pos, key: &str) -> Result<Entry, EditError> {
    let moved = || EditError::Moved {
        file: pos.file.to_string(),
        line: pos.line,
    };
    let index = usize::try_from(pos.line)
        .map_err(|_| moved())?
        .saturating_sub(1);
    let line_text = |i: usize| -> Option<&str> {
        let text = source.get(*starts.get(i)?..*starts.get(i + 1)?)?;
        Some(text.trim_end_matches('\n').trim_end_matches('\r'))
    };
    let line = line_text(index).ok_or_else(moved)?;
    let column = usize::try_from(pos.column)
        .map_err(|_| moved())?
        .saturating_sub(1);
    let prefix: String = line.chars().take(column).collect();
    if !prefix.chars().all(|c| c == ' ' || c == '-') || prefix.chars().count() < column {
        return Err(EditError::Inline {
            file: pos.file.to_string(),
            line: pos.line,
            column: pos.column,
            key: key.to_owned(),
        });
    }
    let indent = prefix.len();
    let after_key = &line[indent..];
    let rest = after_key.split_once(':').map_or("", |(_, r)| r).trim();
    let items_follow = rest.is_empty() || rest.starts_with('#');
    let mut last = index;
    let mut item_indent = None;
    let mut i = index + 1;
    while let Some(text) = line_text(i) {
        let trimmed = text.trim_start_matches(' ');
        let own = text.len() - trimmed.len();
        let item = trimmed == "-" || trimmed.starts_with("- ");
        if trimmed.is_empty() || trimmed.starts_with('#') {
            // blank or a comment: inside only if a line of the value follows
        } else if own > indent || (own == indent && item && items_follow) {
            last = i;
            if item && item_indent.is_none() {
                item_indent = Some(own);
            }
        } else {
            break;
        }
        i += 1;
    }
    let one_line = last == index;
    let shape = match rest.chars().next() {
        Some('[') if one_line => Shape::Flow,
        Some(c) if one_line && !"#|>&!*".contains(c) => Shape::Single,
        _ => Shape::Items(item_indent.unwrap_or(indent + 2)),
    };
    let end = starts[last + 1];
    Ok(Entry {
        key_start: starts[index] + indent,
        end,
        ends_with_break: source[..end].ends_with('\n'),
        indent,
        shape,
    })
}

/// The entry `key: texts` in `shape`, ending with a line break; its first line without the
/// indent (the caller places it). With it, each text's byte range in it.
fn render(key: &str, texts: &[String], shape: Shape, newline: &str) -> (String, Vec<Range<usize>>) {
    let context = match shape {
        Shape::Flow => Context::Flow,
        Shape::Single if texts.len() > 1 => Context::Flow,
        Shape::Single | Shape::Items(_) => Context::Block,
    };
    let quoted: Vec<_> = texts.iter().map(|t| yaml_text(t, context)).collect();
    let mut out = String::new();
    let mut ranges = Vec::with_capacity(quoted.len());
    let mut push = |out: &mut String, text: &str| {
        ranges.push(out.len()..out.len() + text.len());
        out.push_str(text);
    };
    match (shape, quoted.as_slice()) {
        (Shape::Single, [one]) => {
            out.push_str(&format!("{key}: "));
            push(&mut out, one);
        }
        (Shape::Flow | Shape::Single, _) => {
            out.push_str(&format!("{key}: ["));
            for (i, text) in quoted.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                push(&mut out, text);
            }
            out.push(']');
        }
        (Shape::Items(indent), _) => {
            let pad = " ".repeat(indent);
            out.push_str(&format!("{key}:"));
            for text in &quoted {
                out.push_str(&format!("{newline}{pad}- "));
                push(&mut out, text);
            }
        }
    }
    out.push_str(newline);
    (out, ranges)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn edit(line: u32, column: u32, existing: Option<(u32, u32)>, texts: &[&str]) -> Edit {
        Edit {
            original: Pos::new("acts.yaml", line, column),
            existing: existing.map(|(l, c)| Pos::new("acts.yaml", l, c)),
            key: "Text@de".to_owned(),
            texts: texts.iter().map(|t| (*t).to_owned()).collect(),
        }
    }

    #[test]
    fn a_translation_goes_right_after_its_original_in_the_same_shape() {
        let source = "- Label: A\n  Text: [Hello, Hi]  # greeting\n\n  # commands\n  Cmds: []\n";
        let out = edit_file(source, &[edit(2, 3, None, &["Hallo", "Servus"])])
            .expect("edited")
            .text;
        assert_eq!(
            out,
            "- Label: A\n  Text: [Hello, Hi]  # greeting\n  Text@de: [Hallo, Servus]\n\n  # \
             commands\n  Cmds: []\n"
        );
    }

    #[test]
    fn a_list_of_items_keeps_its_indent_and_crlf() {
        let source = "- Label: A\r\n  Text:\r\n    - Hello\r\n    # second\r\n    - \"Hi\"\r\n- Label: B\r\n";
        let out = edit_file(source, &[edit(2, 3, None, &["Hallo", "yes"])])
            .expect("edited")
            .text;
        assert_eq!(
            out,
            "- Label: A\r\n  Text:\r\n    - Hello\r\n    # second\r\n    - \"Hi\"\r\n  Text@de:\r\n    \
             - Hallo\r\n    - \"yes\"\r\n- Label: B\r\n"
        );
    }

    #[test]
    fn an_existing_translation_is_replaced_where_it_stands() {
        let source = "- Text: Hello\n  Text@de: Hallihallo # old\n  Label: A";
        let out = edit_file(source, &[edit(1, 3, Some((2, 3)), &["Hallo: du"])])
            .expect("edited")
            .text;
        assert_eq!(out, "- Text: Hello\n  Text@de: \"Hallo: du\"\n  Label: A");
    }

    #[test]
    fn the_last_line_without_a_break_gets_the_translation_after_it() {
        let source = "- Label: A\n  Text: Hello";
        let out = edit_file(source, &[edit(2, 3, None, &["Hallo"])])
            .expect("edited")
            .text;
        assert_eq!(out, "- Label: A\n  Text: Hello\n  Text@de: Hallo");
    }

    #[test]
    fn each_written_text_is_found_where_it_landed() {
        let source =
            "- Label: A\n  Text: [Hello, Hi]\n- Label: B\n  Text:\n    - Bye\n    - Ciao\n";
        let edits = [
            edit(4, 3, None, &["Tschüss", "yes"]),
            edit(2, 3, None, &["Hallo", "Servus"]),
        ];
        let out = edit_file(source, &edits).expect("edited");
        let texts: Vec<Vec<&str>> = (out.texts.iter())
            .map(|ranges| ranges.iter().map(|r| &out.text[r.clone()]).collect())
            .collect();
        assert_eq!(texts, [vec!["Tschüss", "\"yes\""], vec!["Hallo", "Servus"]]);
    }

    #[test]
    fn an_inline_mapping_is_refused() {
        let source = "- {Label: A, Text: Hello}\n";
        let e = edit_file(source, &[edit(1, 14, None, &["Hallo"])]).expect_err("refused");
        assert!(matches!(e, EditError::Inline { line: 1, .. }), "{e}");
    }
}
