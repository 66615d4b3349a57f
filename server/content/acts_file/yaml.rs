//! Reading a YAML file into a tree where every node knows its place, for both acts files and
//! `docent.yaml`. All structural checks happen on this tree in our own code, so one file can
//! report many problems (serde stops at the first).
//!
//! YAML guesses types: `yes` is a boolean, `3.5` a number. Such plain scalars are kept as the
//! text written ([`Kind::Guessed`], taken from the source bytes) so callers can accept them as
//! text and suggest quotes. Duplicate keys are passed through for the caller to report.
//!
//! A syntax error stops the parser; for acts files we then blank the top-level list item that
//! holds the error (keeping byte offsets) and parse again, so the other acts are still read.

use std::sync::Arc;

use serde_saphyr::{DuplicateKeyPolicy, NonFiniteFloatPolicy, Options, Spanned};

use crate::content::diagnostic::Diagnostic;
use crate::content::model::Pos;

mod raw;
mod wording;

/// The largest YAML file read, in bytes. A real acts file of 100,000 acts is about 25 MB.
pub(crate) const MAX_FILE_BYTES: usize = 32 * 1024 * 1024;

/// How many syntax errors one file may report before reading it is abandoned.
const MAX_SYNTAX_ERRORS: usize = 20;

/// A YAML node and where it starts.
#[derive(Debug)]
pub(crate) struct Node {
    /// Where the node starts (for an alias: where the alias is used).
    pub pos: Pos,
    /// What it is.
    pub kind: Kind,
}

/// The shape of a node.
#[derive(Debug)]
pub(crate) enum Kind {
    /// Text. `verbatim_at` is the character offset from `pos` where `value` appears word for
    /// word in the source (0 when plain, 1 when quoted), if it does.
    Str {
        value: String,
        verbatim_at: Option<u32>,
    },
    /// A plain scalar YAML took for a number or yes/no value, as written.
    Guessed(String),
    /// `~`, `null` or nothing at all.
    Null,
    /// A list.
    Seq(Vec<Node>),
    /// Key-value pairs in written order, duplicates included.
    Map(Vec<(Node, Node)>),
}

impl Node {
    /// The node as text, if it is a scalar other than null.
    pub fn as_text(&self) -> Option<&str> {
        match &self.kind {
            Kind::Str { value, .. } | Kind::Guessed(value) => Some(value),
            _ => None,
        }
    }

    /// What the node is, in words for a message ("a list", "a set of keys", ...).
    pub fn describe(&self) -> &'static str {
        match &self.kind {
            Kind::Str { .. } | Kind::Guessed(_) => "a single value",
            Kind::Null => "empty",
            Kind::Seq(_) => "a list",
            Kind::Map(_) => "a set of keys and values",
        }
    }
}

/// The result of reading one YAML file.
pub(crate) struct YamlFile {
    /// The tree, unless the file could not be read at all.
    pub root: Option<Node>,
    /// Syntax, encoding, size and tab problems.
    pub diagnostics: Vec<Diagnostic>,
    /// 1-based line ranges (start inclusive, end exclusive) left out to get past errors.
    pub skipped_lines: Vec<(u32, u32)>,
}

/// Whether to skip a broken top-level list item and read the rest.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Recovery {
    /// Acts files: a top-level list of independent items.
    SkipBrokenItems,
    /// Settings: one mapping; a partial read would only mislead.
    None,
}

/// Reads `bytes` (the content of `file`, named relative to the bundle root). Syntax and
/// encoding problems are reported under `syntax_code` (`yaml-syntax` or `config-syntax`).
pub(crate) fn parse(
    file: &Arc<str>,
    bytes: &[u8],
    syntax_code: &'static str,
    recovery: Recovery,
) -> YamlFile {
    let whole_file = Pos::new(file.clone(), 0, 0);
    let mut out = YamlFile {
        root: None,
        diagnostics: Vec::new(),
        skipped_lines: Vec::new(),
    };
    if bytes.len() > MAX_FILE_BYTES {
        let message = format!(
            "This file is larger than {} MB, the most Docent reads from one YAML file. Split the acts into several files.",
            MAX_FILE_BYTES / (1024 * 1024)
        );
        out.diagnostics
            .push(Diagnostic::error("file-too-large", &whole_file, message));
        return out;
    }
    let source = match std::str::from_utf8(bytes) {
        Ok(text) => text,
        Err(e) => {
            let pos = position_of_byte(file, bytes, e.valid_up_to());
            let message = "This file is not saved as UTF-8 text (the character here cannot be read). \
                           Save it again choosing the UTF-8 encoding.";
            out.diagnostics
                .push(Diagnostic::error(syntax_code, &pos, message));
            return out;
        }
    };
    let tabs = tab_positions(source);
    let mut text = source.to_owned();
    let mut errors = 0;
    loop {
        match serde_saphyr::from_str_with_options::<Spanned<raw::Raw>>(&text, options()) {
            Ok(tree) => {
                out.root = Some(raw::into_node(tree, file, &text));
                break;
            }
            Err(err) => {
                errors += 1;
                let line = err
                    .location()
                    .map(|l| u32::try_from(l.line()).unwrap_or(u32::MAX));
                let near_tab =
                    line.is_some_and(|l| tabs.iter().any(|&(t, _)| t == l || t == l + 1));
                if !near_tab {
                    let pos = err
                        .location()
                        .map_or(whole_file.clone(), |l| raw::pos(file, &l));
                    out.diagnostics.push(Diagnostic::error(
                        syntax_code,
                        &pos,
                        wording::describe(&err),
                    ));
                }
                let item = match (recovery, line) {
                    (Recovery::SkipBrokenItems, Some(line))
                        if errors < MAX_SYNTAX_ERRORS && wording::recoverable(&err) =>
                    {
                        enclosing_item(&text, line)
                    }
                    _ => None,
                };
                let Some((start, end)) = item else { break };
                text = blank_lines(&text, start, end);
                out.skipped_lines.push((start, end));
            }
        }
    }
    out.diagnostics
        .extend(tab_diagnostics(file, &tabs, errors > 0));
    out
}

fn options() -> Options {
    serde_saphyr::options! {
        // Sized for 100,000 rich acts per file (about 30 nodes each); measured in the tests.
        budget: serde_saphyr::budget! { max_nodes: 4_000_000, max_events: 10_000_000 },
        // Duplicates reach our visitor, which reports every one of them with both places.
        duplicate_keys: DuplicateKeyPolicy::PassThrough,
        // `.inf` arrives as a float; we keep the text written instead of refusing the file.
        non_finite_float_policy: NonFiniteFloatPolicy::PassThrough,
        // We write our own messages; the snippet would only cost time.
        with_snippet: false,
    }
}

/// The position of byte `offset` (1-based line, column in characters).
fn position_of_byte(file: &Arc<str>, bytes: &[u8], offset: usize) -> Pos {
    let before = &bytes[..offset.min(bytes.len())];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let line_start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let column = String::from_utf8_lossy(&before[line_start..])
        .chars()
        .count()
        + 1;
    Pos::new(file.clone(), to_u32(line), to_u32(column))
}

fn to_u32(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// (line, column) of the first tab in each line's leading whitespace.
fn tab_positions(source: &str) -> Vec<(u32, u32)> {
    source
        .lines()
        .enumerate()
        .filter_map(|(i, line)| {
            let indent = line
                .find(|c: char| c != ' ' && c != '\t')
                .unwrap_or(line.len());
            let column = line[..indent].find('\t')?;
            Some((to_u32(i + 1), to_u32(column + 1)))
        })
        .collect()
}

/// Tabs are an error when the file did not parse (they are the likely cause); when YAML
/// still read the file they sit inside text or were ignored, so a warning suffices.
fn tab_diagnostics(file: &Arc<str>, tabs: &[(u32, u32)], failed: bool) -> Vec<Diagnostic> {
    let message = "This line is indented with a tab. YAML allows only spaces for indentation: \
                   replace the tab with spaces (for example two spaces per level).";
    tabs.iter()
        .map(|&(line, column)| {
            let pos = Pos::new(file.clone(), line, column);
            if failed {
                Diagnostic::error("yaml-tab", &pos, message)
            } else {
                Diagnostic::warning("yaml-tab", &pos, message)
            }
        })
        .collect()
}

/// The line range of the top-level list item (a line starting with `- ` at column 1)
/// containing `line`, if the file is laid out that way.
fn enclosing_item(text: &str, line: u32) -> Option<(u32, u32)> {
    let starts: Vec<u32> = text
        .lines()
        .enumerate()
        .filter(|(_, l)| {
            l.starts_with('-')
                && !l.starts_with("--")
                && l[1..].chars().next().is_none_or(char::is_whitespace)
        })
        .map(|(i, _)| to_u32(i + 1))
        .collect();
    let last_line = to_u32(text.lines().count());
    let line = line.min(last_line.max(1));
    let start = *starts.iter().rev().find(|&&s| s <= line)?;
    let end = starts
        .iter()
        .copied()
        .find(|&s| s > line)
        .unwrap_or(last_line + 1);
    Some((start, end))
}

/// `text` with lines `start..end` turned into spaces, keeping every byte offset and line.
fn blank_lines(text: &str, start: u32, end: u32) -> String {
    let mut out = String::with_capacity(text.len());
    for (i, line) in text.split_inclusive('\n').enumerate() {
        let number = to_u32(i + 1);
        if number < start || number >= end {
            out.push_str(line);
            continue;
        }
        for c in line.chars() {
            match c {
                '\n' | '\r' => out.push(c),
                _ => out.extend(std::iter::repeat_n(' ', c.len_utf8())),
            }
        }
    }
    out
}
