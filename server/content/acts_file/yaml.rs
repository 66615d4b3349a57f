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

use crate::content::diagnostic::Diagnostic;
use crate::content::encoding::not_utf8;
use crate::content::model::Pos;

mod fast;
#[cfg(test)]
mod fast_tests;
mod layout;
mod raw;
mod wording;

use layout::{
    Item, odd_space_diagnostics, odd_space_positions, position_of_byte, tab_diagnostics,
    tab_positions, top_level_items, unclosed_bracket_before,
};

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
    syntax_code: &'static str,
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
        out.diagnostics
            .push(Diagnostic::error("file-too-large", &whole_file, message));
        return out;
    }
    if let Some(found) = not_utf8(bytes) {
        let pos = position_of_byte(file, bytes, found.at);
        out.diagnostics
            .push(Diagnostic::error("file-encoding", &pos, found.message));
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
                report_error(
                    file,
                    source,
                    &err,
                    0,
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

/// Parses each top-level item on its own, so an error (even an unclosed bracket) stays
/// inside its item and every other act is read.
fn parse_items(
    file: &Arc<str>,
    source: &str,
    items: &[Item],
    syntax_code: &'static str,
    explained: &[(u32, u32)],
    out: &mut YamlFile,
) {
    let mut nodes = Vec::with_capacity(items.len());
    for item in items {
        let text = &source[item.bytes.clone()];
        let line_offset = item.lines.0 - 1;
        let origin = raw::Origin {
            line: line_offset,
            byte: item.bytes.start,
        };
        match serde_saphyr::from_str_with_options::<Spanned<raw::Raw>>(text, options()) {
            Ok(tree) => match raw::into_node(tree, file, text, origin) {
                Node {
                    kind: Kind::Seq(parsed),
                    ..
                } => nodes.extend(parsed),
                other => nodes.push(other),
            },
            Err(err) => {
                report_error(
                    file,
                    source,
                    &err,
                    line_offset,
                    syntax_code,
                    explained,
                    &mut out.diagnostics,
                );
                out.skipped_lines.push(item.lines);
            }
        }
    }
    let pos = Pos::new(file.clone(), items.first().map_or(1, |i| i.lines.0), 1);
    out.root = Some(Node {
        pos,
        span: None,
        kind: Kind::Seq(nodes),
    });
}

/// Adds the diagnostic for a parse error, unless a layout problem (a tab, a no-break space) on
/// that line (or the next, where the parser tends to notice it) already explains it.
fn report_error(
    file: &Arc<str>,
    source: &str,
    err: &serde_saphyr::Error,
    line_offset: u32,
    syntax_code: &'static str,
    explained: &[(u32, u32)],
    out: &mut Vec<Diagnostic>,
) {
    let pos = match err.location() {
        Some(location) => {
            let mut pos = raw::pos(file, &location);
            pos.line = pos.line.saturating_add(line_offset);
            pos
        }
        None => Pos::start_of(file.clone()),
    };
    let explained_by_tab = explained
        .iter()
        .any(|&(line, _)| line.abs_diff(pos.line) <= 1);
    if !explained_by_tab {
        // A bracket left open is noticed only lines later: report it where it was opened.
        if wording::about_brackets(err)
            && let Some((line, column)) = unclosed_bracket_before(source, pos.line, pos.column)
        {
            let open = Pos::new(file.clone(), line, column);
            out.push(Diagnostic::error(
                syntax_code,
                &open,
                wording::UNCLOSED_BRACKET,
            ));
            return;
        }
        let line = source.lines().nth(pos.line.saturating_sub(1) as usize);
        let message = wording::describe(err, line.unwrap_or_default());
        out.push(Diagnostic::error(syntax_code, &pos, message));
    }
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
mod tests {
    use super::*;

    fn file() -> Arc<str> {
        Arc::from("acts.yaml")
    }

    fn parse_acts(text: &str) -> YamlFile {
        parse(
            &file(),
            text.as_bytes(),
            "yaml-syntax",
            Recovery::SkipBrokenItems,
        )
    }

    fn codes(parsed: &YamlFile) -> Vec<(&'static str, u32, u32)> {
        parsed
            .diagnostics
            .iter()
            .map(|d| (d.code, d.line, d.column))
            .collect()
    }

    #[test]
    fn budget_admits_100_000_acts_in_one_file() {
        // Five nodes an act: twice serde-saphyr's default node budget.
        let text: String = (0..100_000)
            .map(|i| format!("- Label: A{i}\n  Text: hi\n"))
            .collect();
        let parsed = parse_acts(&text);
        assert!(parsed.diagnostics.is_empty(), "{:?}", parsed.diagnostics);
        let Some(Node {
            kind: Kind::Seq(items),
            ..
        }) = parsed.root
        else {
            panic!("expected a list")
        };
        assert_eq!(items.len(), 100_000);
        assert_eq!(items[99_999].pos.line, 199_999);
        let default_budget = serde_saphyr::from_str::<Spanned<raw::Raw>>(&text);
        assert!(
            default_budget.is_err(),
            "the default budget is too small for real bundles"
        );
    }

    #[test]
    fn refuses_files_over_the_size_limit() {
        let parsed = parse_acts(&" ".repeat(MAX_FILE_BYTES + 1));
        assert_eq!(codes(&parsed), [("file-too-large", 1, 1)]);
        assert!(parsed.root.is_none());
    }

    #[test]
    fn locates_bytes_that_are_not_utf8() {
        let parsed = parse(
            &file(),
            b"- Label: A\n  Text: caf\xe9\n",
            "yaml-syntax",
            Recovery::SkipBrokenItems,
        );
        assert_eq!(codes(&parsed), [("file-encoding", 2, 12)]);
    }

    #[test]
    fn guessed_scalars_keep_the_text_as_written() {
        let parsed = parse_acts("- [yes, 3.5, 0x1F, 010, .inf, ~, 'quoted', \"d: q\", plain]\n");
        let Some(Node {
            kind: Kind::Seq(items),
            ..
        }) = parsed.root
        else {
            panic!("expected a list")
        };
        let Kind::Seq(values) = &items[0].kind else {
            panic!("expected a nested list")
        };
        let shown: Vec<String> = values
            .iter()
            .map(|n| match &n.kind {
                Kind::Guessed(t) => format!("guessed {t}"),
                Kind::Str { value, verbatim_at } => format!("text {value} at {verbatim_at:?}"),
                Kind::Null => "null".to_owned(),
                _ => "other".to_owned(),
            })
            .collect();
        assert_eq!(
            shown,
            [
                "guessed yes",
                "guessed 3.5",
                "guessed 0x1F",
                "guessed 010",
                "guessed .inf",
                "null",
                "text quoted at Some(1)",
                "text d: q at Some(1)",
                "text plain at Some(0)",
            ]
        );
    }

    #[test]
    fn a_tab_in_indentation_is_reported_at_the_tab_and_the_rest_still_parses() {
        let parsed = parse_acts("- Label: A\n  Text:\n  \t- x\n- Label: B\n");
        assert_eq!(codes(&parsed), [("yaml-tab", 3, 3)]);
        assert_eq!(parsed.skipped_lines, [(1, 4)]);
        let Some(Node {
            kind: Kind::Seq(items),
            ..
        }) = parsed.root
        else {
            panic!("expected a list")
        };
        assert_eq!(items.len(), 1);
    }

    #[test]
    fn a_tab_yaml_accepts_is_only_a_warning() {
        let parsed = parse_acts("- Label: A\n  Text: |\n    line\n    \tindented text\n");
        assert_eq!(parsed.diagnostics.len(), 1);
        assert_eq!(
            parsed.diagnostics[0].severity,
            crate::content::Severity::Warning
        );
    }

    #[test]
    fn every_broken_item_is_reported_and_skipped() {
        let text = "- Label: A\n  Text: \"open\n- Label: B\n  Text: fine\n\
                    - Label: C\n  Text: [a, b\n- Label: D\n";
        let parsed = parse_acts(text);
        assert_eq!(
            codes(&parsed),
            [("yaml-syntax", 2, 9), ("yaml-syntax", 6, 9)]
        );
        assert_eq!(parsed.skipped_lines, [(1, 3), (5, 7)]);
        let Some(Node {
            kind: Kind::Seq(items),
            ..
        }) = parsed.root
        else {
            panic!("expected a list")
        };
        assert_eq!(items.len(), 2);
        assert_eq!(items[1].pos.line, 7);
    }

    #[test]
    fn settings_are_not_partially_read() {
        let parsed = parse(
            &file(),
            b"home: [x\nspeech: {}\n",
            "config-syntax",
            Recovery::None,
        );
        assert!(parsed.root.is_none());
        assert_eq!(parsed.diagnostics.len(), 1);
        assert_eq!(parsed.diagnostics[0].code, "config-syntax");
    }
}
