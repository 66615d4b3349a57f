//! Diagnostics drawn for people, as `docent check` prints them: what is wrong, the line of the
//! file with a caret under the place, and how to fix it. The drawing is annotate-snippets' (the
//! renderer rustc and cargo use); this module only picks the line, the span under the caret
//! and splits a message into what happened and the hint.

use std::collections::HashMap;
use std::path::Path;

use annotate_snippets::{AnnotationKind, Group, Level, Renderer, Snippet};

use crate::diagnostic::{Diagnostic, Severity};

/// Whether to colour the output (for a terminal) or not (for files and pipes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Colour {
    /// ANSI colours.
    Styled,
    /// Plain text.
    Plain,
}

/// Every diagnostic of a bundle at `root`, each with its source line, caret and hint.
pub fn render_diagnostics(root: &Path, diagnostics: &[Diagnostic], colour: Colour) -> String {
    let renderer = match colour {
        Colour::Styled => Renderer::styled(),
        Colour::Plain => Renderer::plain(),
    };
    let mut sources: HashMap<&str, Option<String>> = HashMap::new();
    let mut out = String::new();
    for d in diagnostics {
        let source = sources
            .entry(d.file.as_str())
            .or_insert_with(|| std::fs::read_to_string(root.join(&d.file)).ok());
        // A binary file that happens to be UTF-8 (a Mac's `._name`) has no line to show.
        let line = source
            .as_deref()
            .filter(|s| !s.contains('\0'))
            .and_then(|s| s.lines().nth(d.line.saturating_sub(1) as usize));
        out.push_str(&render_one(&renderer, d, line));
        out.push_str("\n\n");
    }
    out
}

fn render_one(renderer: &Renderer, d: &Diagnostic, line: Option<&str>) -> String {
    let level = match d.severity {
        Severity::Error => Level::ERROR,
        Severity::Warning => Level::WARNING,
        Severity::Note => Level::NOTE,
    };
    let (what, hint) = split_message(&d.message);
    let place = format!("{}:{}:{}", d.file, d.line, d.column);
    let title = level.primary_title(what).id(d.code.as_str());
    let mut group = match line {
        Some(line) => {
            let line = line.trim_end_matches('\r');
            let span = caret_span(line, d.column);
            title.element(
                Snippet::source(line)
                    .line_start(d.line as usize)
                    .path(d.file.as_str())
                    .annotation(AnnotationKind::Primary.span(span)),
            )
        }
        // A file that does not exist (yet), or is not text: the place alone.
        None => title.element(Level::NOTE.message(format!("at {place}"))),
    };
    if let Some(hint) = hint {
        group = group.element(Level::HELP.message(hint));
    }
    let report: [Group<'_>; 1] = [group];
    renderer.render(&report).to_string()
}

/// The bytes of `line` under the caret: the word starting at the 1-based character `column`
/// (at least one character; the line's end for a column past it).
fn caret_span(line: &str, column: u32) -> std::ops::Range<usize> {
    let start = line
        .char_indices()
        .nth(column.saturating_sub(1) as usize)
        .map_or(line.len(), |(i, _)| i);
    let rest = &line[start..];
    // A word ends at a space, or at the quote or bracket closing an attribute or a list.
    let word = rest
        .find(|c: char| c.is_whitespace() || matches!(c, '"' | '\'' | '<' | '>' | ',' | ']'))
        .unwrap_or(rest.len())
        .max(rest.chars().next().map_or(0, char::len_utf8));
    start..start + word
}

/// The first sentence (what happened) and the rest (what to do), split at a sentence end
/// outside `code` and "quotes"; the whole message when it is one sentence.
fn split_message(message: &str) -> (&str, Option<&str>) {
    let mut in_code = false;
    let mut in_quote = false;
    let mut previous = ' ';
    for (i, c) in message.char_indices() {
        match c {
            '`' => in_code = !in_code,
            '"' if !in_code => in_quote = !in_quote,
            // "e.g." and "i.e." end no sentence: the example belongs to what it illustrates.
            ' ' if !in_code
                && !in_quote
                && matches!(previous, '.' | '?' | '!')
                && !message[..i].ends_with("e.g.")
                && !message[..i].ends_with("i.e.") =>
            {
                let rest = message[i..].trim_start();
                if !rest.is_empty() {
                    return (&message[..i], Some(rest));
                }
            }
            _ => {}
        }
        previous = c;
    }
    (message, None)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Pos;

    #[test]
    fn messages_split_after_the_first_sentence_outside_code_and_quotes() {
        assert_eq!(
            split_message("`a. b` is odd. Fix it. Now."),
            ("`a. b` is odd.", Some("Fix it. Now.")),
        );
        assert_eq!(
            split_message("`date` is a day, e.g. `date: 2025-12-24`. Found: `x`."),
            (
                "`date` is a day, e.g. `date: 2025-12-24`.",
                Some("Found: `x`.")
            )
        );
        assert_eq!(
            split_message("It says \"Hi. There\" here. Quote it."),
            ("It says \"Hi. There\" here.", Some("Quote it."))
        );
        assert_eq!(split_message("One sentence."), ("One sentence.", None));
    }

    #[test]
    fn the_caret_sits_under_the_word_at_the_column() {
        assert_eq!(caret_span("    - SAY2 Hello", 7), 6..10);
        assert_eq!(caret_span("é x", 3), 3..4);
        assert_eq!(caret_span("ab", 9), 2..2);
        assert_eq!(
            caret_span(r#"<b data-act="WHERE_FORM">Ask</b>"#, 14),
            13..23
        );
    }

    #[test]
    fn a_diagnostic_is_drawn_with_its_line_caret_and_hint() {
        let pos = Pos::new("acts.yaml", 4, 7);
        let d = Diagnostic::error(
            crate::DiagnosticCode::UnknownVerb,
            &pos,
            "`SAY2` is not a command Docent knows. Did you mean `SAY`?",
        );
        let text = render_one(&Renderer::plain(), &d, Some("    - SAY2 Hello"));
        assert!(
            text.contains("error[unknown-verb]: `SAY2` is not a command Docent knows."),
            "{text}"
        );
        assert!(text.contains("acts.yaml:4:7"), "{text}");
        assert!(text.contains("4 |     - SAY2 Hello"), "{text}");
        assert!(text.contains("^^^^"), "{text}");
        assert!(text.contains("help: Did you mean `SAY`?"), "{text}");
        let missing = render_one(&Renderer::plain(), &d, None);
        assert!(missing.contains("at acts.yaml:4:7"), "{missing}");
    }
}
