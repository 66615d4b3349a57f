//! Getting past a syntax error: each top-level item of an acts file parsed on its own, so one
//! broken act costs only itself, and each parse error reported once, at the place an author
//! can fix (where a bracket was opened; not at all where a tab or odd space explains it).

use std::sync::Arc;

use serde_saphyr::Spanned;

use super::layout::{Item, unclosed_bracket_before};
use super::slips::{act_start_slip, list_start_slip};
use super::{Kind, Node, YamlFile, options, raw, wording};
use crate::diagnostic::{Diagnostic, DiagnosticCode};
use crate::model::Pos;

/// Parses each top-level item on its own, so an error (even an unclosed bracket) stays
/// inside its item and every other act is read.
pub(super) fn parse_items(
    file: &Arc<str>,
    source: &str,
    items: &[Item],
    syntax_code: DiagnosticCode,
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
                let scope = Scope {
                    source,
                    text,
                    first_line: line_offset,
                };
                report_error(
                    file,
                    &scope,
                    &err,
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

/// The text a parse error was found in: the whole file, or one top-level item of it.
pub(super) struct Scope<'a> {
    /// The whole file.
    pub source: &'a str,
    /// The text parsed: the whole file, or the item.
    pub text: &'a str,
    /// The lines of the file before `text`.
    pub first_line: u32,
}

/// Adds the diagnostic for a parse error, unless a layout problem (a tab, a no-break space) on
/// that line (or the next, where the parser tends to notice it) already explains it.
pub(super) fn report_error(
    file: &Arc<str>,
    scope: &Scope<'_>,
    err: &serde_saphyr::Error,
    syntax_code: DiagnosticCode,
    explained: &[(u32, u32)],
    out: &mut Vec<Diagnostic>,
) {
    let source = scope.source;
    let pos = match err.location() {
        Some(location) => {
            let mut pos = raw::pos(file, &location);
            pos.line = pos.line.saturating_add(scope.first_line);
            pos
        }
        None => Pos::start_of(file.clone()),
    };
    // Looking back from the error stays inside the text parsed (one act, when items are).
    let local_line = pos.line.saturating_sub(scope.first_line);
    let explained_by_tab = explained
        .iter()
        .any(|&(line, _)| line.abs_diff(pos.line) <= 1);
    if !explained_by_tab {
        // `-Label: X` or `Label: X` without its dash: the parser notices it a line later.
        if let Some(slip) = act_start_slip(scope.text, local_line, scope.first_line) {
            let (at, message) = wording::act_start(file, &slip);
            out.push(Diagnostic::error(syntax_code, &at, message));
            return;
        }
        // A list of texts that lost its first `- ` or its `Text:` line.
        if let Some(slip) = list_start_slip(scope.text, local_line, scope.first_line) {
            let (at, message) = wording::list_start(file, &slip);
            out.push(Diagnostic::error(syntax_code, &at, message));
            return;
        }
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
        let lines: Vec<&str> = scope.text.lines().take(local_line as usize).collect();
        let (line, before) = lines.split_last().unwrap_or((&"", &[]));
        let above = before.iter().rev().find(|l| !l.trim().is_empty());
        let message = wording::describe(err, line, above.copied().unwrap_or_default());
        out.push(Diagnostic::error(syntax_code, &pos, message));
    }
}
