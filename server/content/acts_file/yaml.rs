//! Reading a YAML file into a tree where every node knows its place, for both acts files and
//! `docent.yaml`. All structural checks happen on this tree in our own code, so one file can
//! report many problems (serde stops at the first).
//!
//! YAML guesses types: `yes` is a boolean, `3.5` a number. Such plain scalars are kept as the
//! text written ([`Kind::Guessed`], taken from the source bytes) so callers can accept them as
//! text and suggest quotes. Duplicate keys are passed through for the caller to report.
//!
//! A syntax error stops the parser; for acts files we then parse each top-level list item on
//! its own, so one broken act costs only itself and every error in the file is reported.

use std::ops::Range;
use std::sync::Arc;

use serde_saphyr::{DuplicateKeyPolicy, NonFiniteFloatPolicy, Options, Spanned};

use crate::DiagnosticCode;
use crate::diagnostic::Diagnostic;
use crate::encoding::not_utf8;
use crate::model::Pos;
use crate::plain_text::not_plain_text;

mod fast;
mod layout;
mod raw;
mod recovery;
mod slips;
mod wording;

use layout::{
    odd_space_diagnostics, odd_space_positions, position_of_byte, tab_diagnostics, tab_positions,
    top_level_items,
};
use recovery::{Scope, parse_items, report_error};

/// The largest YAML file read, in bytes. A real acts file of 100,000 acts is about 25 MB.
pub(crate) const MAX_FILE_BYTES: usize = 32 * 1024 * 1024;

/// A YAML node and where it starts.
#[derive(Debug, PartialEq)]
pub(crate) struct Node {
    /// Where the node starts (for an alias: where the alias is used).
    pub pos: Pos,
    /// The bytes of the file the node was read from, when the parser reported them (scalars).
    pub span: Option<Range<usize>>,
    /// What it is.
    pub kind: Kind,
}

/// The shape of a node.
#[derive(Debug, PartialEq)]
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
    syntax_code: DiagnosticCode,
    recovery: Recovery,
) -> YamlFile {
    let whole_file = Pos::start_of(file.clone());
    let mut out = YamlFile {
        root: None,
        diagnostics: Vec::new(),
        skipped_lines: Vec::new(),
    };
    if bytes.len() > MAX_FILE_BYTES {
        let message = format!(
            "This file is larger than {} MB, the most Docent reads from one YAML file. \
             Split the acts into several files.",
            MAX_FILE_BYTES / (1024 * 1024)
        );
        out.diagnostics.push(Diagnostic::error(
            DiagnosticCode::FileTooLarge,
            &whole_file,
            message,
        ));
        return out;
    }
    if let Some(message) = not_plain_text(bytes) {
        (out.diagnostics).push(Diagnostic::error(
            DiagnosticCode::NotPlainText,
            &whole_file,
            message,
        ));
        return out;
    }
    if let Some(found) = not_utf8(bytes) {
        let pos = position_of_byte(file, bytes, found.at);
        out.diagnostics.push(Diagnostic::error(
            DiagnosticCode::FileEncoding,
            &pos,
            found.message,
        ));
        return out;
    }
    let source = std::str::from_utf8(bytes).unwrap_or_default();
    // Parse errors on these lines are explained better by the layout problem found there.
    let odd_spaces = odd_space_positions(source);
    let tabs = tab_positions(source);
    let explained: Vec<(u32, u32)> = tabs.iter().chain(&odd_spaces).copied().collect();
    let mut failed = false;
    // The fast reader handles the common case; anything else (errors included) goes through
    // serde-saphyr, for its exact messages and positions.
    let parsed = match fast::read(file, source) {
        Some(root) => Ok(root),
        None => serde_saphyr::from_str_with_options::<Spanned<raw::Raw>>(source, options())
            .map(|tree| raw::into_node(tree, file, source, raw::Origin::START)),
    };
    match parsed {
        Ok(root) => out.root = Some(root),
        Err(err) => {
            failed = true;
            let items = match recovery {
                Recovery::SkipBrokenItems if wording::recoverable(&err) => top_level_items(source),
                _ => None,
            };
            if let Some(items) = items {
                parse_items(file, source, &items, syntax_code, &explained, &mut out);
            }
            // Not split into items, or the problem lies between them: report it as found.
            if out.skipped_lines.is_empty() {
                let scope = Scope {
                    source,
                    text: source,
                    first_line: 0,
                };
                report_error(
                    file,
                    &scope,
                    &err,
                    syntax_code,
                    &explained,
                    &mut out.diagnostics,
                );
            }
        }
    }
    out.diagnostics.extend(tab_diagnostics(file, &tabs, failed));
    out.diagnostics
        .extend(odd_space_diagnostics(file, &odd_spaces));
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

#[cfg(test)]
mod fast_tests;

#[cfg(test)]
mod tests;
