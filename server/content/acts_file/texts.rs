//! Texts that YAML changed behind the author's back. A text can read fine in the editor and
//! still reach the robot changed: ` #` starts a comment and cuts the sentence, a line indented
//! one space too far is joined to the text above, a word processor's `–` bullet or “curly”
//! quotes are not YAML's `-` and `"`. These checks compare what was written (the source bytes
//! of the text) with what YAML made of it, and quote what the robot will really say.

use crate::DiagnosticCode;
use crate::diagnostic::Diagnostic;
use crate::model::Pos;

use super::yaml::Node;

/// Word-processor bullets and dashes that look like YAML's `-` but are text to YAML.
const FAKE_BULLETS: [char; 5] = ['–', '—', '−', '•', '‒'];
/// Opening and closing typographic quotes.
const CURLY_OPEN: [char; 6] = ['“', '„', '‘', '‚', '«', '»'];
const CURLY_CLOSE: [char; 5] = ['”', '“', '’', '‘', '»'];
/// Texts longer than this are quoted by their start and end.
const QUOTE_CHARS: usize = 160;

/// The file being read.
pub(crate) struct Source<'a> {
    /// The whole text of the file.
    pub text: &'a str,
}

/// How a text was written.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Style {
    /// Without quotes: YAML's comment and folding rules apply.
    Plain,
    /// In `"` or `'` quotes.
    Quoted,
    /// A `|` or `>` block.
    Block,
}

/// Checks one text (an alternative) against how it was written.
pub(crate) fn check_written(
    source: &Source<'_>,
    node: &Node,
    value: &str,
    out: &mut Vec<Diagnostic>,
) {
    if let Some(span) = &node.span
        && let Some(written) = source.text.get(span.clone())
    {
        let style = match written.chars().next() {
            Some('"' | '\'') => Style::Quoted,
            Some('|' | '>') => Style::Block,
            _ if after_block_indicator(&source.text[..span.start]) => Style::Block,
            _ => Style::Plain,
        };
        if style == Style::Plain {
            cut_by_comment(source, node, span.end, value, out);
            // `-Hello` over a following `- ` line: the glued dash is the one slip to fix.
            if !dash_without_space(node, written, value, out) {
                joined_lines(source, node, written, value, out);
            }
        }
    }
    fake_bullet(node, value, out);
    curly_quotes(node, value, out);
}

/// `-Hello`: a dash glued to the text is text to YAML, not a list item. Whether it was told.
fn dash_without_space(node: &Node, written: &str, value: &str, out: &mut Vec<Diagnostic>) -> bool {
    let Some(rest) = value.strip_prefix('-') else {
        return false;
    };
    if !rest.starts_with(char::is_alphabetic) {
        return false; // `-20 degrees`, `--`: not a slip
    }
    // The fix is for this line only: lines below joined to it are texts of their own.
    let first_line = written.lines().next().unwrap_or(written).trim_end();
    let fixed = first_line.strip_prefix('-').unwrap_or(first_line);
    let message = format!(
        "This text starts with a dash right before a word, so YAML reads it as text, not as a \
         list item, and the robot says: {}. Put a space after the dash: `- {fixed}`.",
        quote(value)
    );
    out.push(Diagnostic::error(
        DiagnosticCode::DashWithoutSpace,
        &node.pos,
        message,
    ));
    true
}

/// Whether text starting right after `before` is the body of a `|` or `>` block (the parser
/// places a block's text at its first line, after the indicator and its options).
fn after_block_indicator(before: &str) -> bool {
    let last_line = before.trim_end().rsplit('\n').next().unwrap_or_default();
    let header = last_line.split(" #").next().unwrap_or_default().trim_end();
    let header = header.trim_end_matches(|c: char| c == '+' || c == '-' || c.is_ascii_digit());
    header.ends_with(['|', '>'])
}

/// ` #` after a plain text starts a comment: the text ends before it.
fn cut_by_comment(
    source: &Source<'_>,
    node: &Node,
    end: usize,
    value: &str,
    out: &mut Vec<Diagnostic>,
) {
    let rest = source.text[end..].split('\n').next().unwrap_or_default();
    let Some(hash) = rest.find('#') else { return };
    if !rest[..hash].chars().all(char::is_whitespace) || hash == 0 {
        return;
    }
    let comment = rest[hash + 1..].trim_end_matches('\r');
    let pos = pos_at(source, node, end + hash);
    let quoted = quote(value);
    // `Room #4`: a number or word right after `#` is text, not a comment.
    let glued = comment.starts_with(|c: char| c.is_alphanumeric());
    let ends_sentence = value
        .trim_end()
        .ends_with(['.', '!', '?', '…', ')', '"', '”']);
    let message = format!(
        "YAML reads ` #` as the start of a comment, so the text ends before it and the robot \
         says only: {quoted}. If `#{comment}` belongs to the text, put the whole text in quotes: \
         `- \"{value} #{comment}\"`. If it is a note for people, put it on a line of its own."
    );
    out.push(if glued || !ends_sentence {
        Diagnostic::error(DiagnosticCode::TextCutByComment, &pos, message)
    } else {
        Diagnostic::warning(DiagnosticCode::TextCutByComment, &pos, message)
    });
}

/// A plain text over several lines is joined into one: a list item indented too far, a
/// missing dash, or a line that simply goes on.
fn joined_lines(
    source: &Source<'_>,
    node: &Node,
    written: &str,
    value: &str,
    out: &mut Vec<Diagnostic>,
) {
    let Some(first_break) = written.find('\n') else {
        return;
    };
    let start = node.span.as_ref().map_or(0, |s| s.start);
    let mut offset = first_break + 1;
    for line in written[first_break + 1..].split('\n') {
        let content = line.trim_start_matches([' ', '\t']);
        let at = start + offset + (line.len() - content.len());
        offset += line.len() + 1;
        let bullet = content
            .chars()
            .next()
            .filter(|&c| c == '-' || FAKE_BULLETS.contains(&c));
        if let Some(bullet) = bullet
            && content[bullet.len_utf8()..].starts_with([' ', '\u{a0}'])
        {
            if bullet == '-' && missing_dash(source, node, written, value, out) {
                return;
            }
            let why = if bullet == '-' {
                "is indented differently from the `- ` line above it".to_owned()
            } else {
                format!("`{bullet}` is a word processor's dash, which YAML takes as text")
            };
            let message = format!(
                "This line starts with `{bullet} ` but {why}, so YAML joins it to the text before \
                 it and the robot says: {}. Start it with `- ` in exactly the same column as the \
                 other `- ` lines (spaces only).",
                quote(value)
            );
            out.push(Diagnostic::error(
                DiagnosticCode::JoinedLines,
                &pos_at(source, node, at),
                message,
            ));
            return;
        }
    }
    // Reported where the author acts: the first line that goes on (a missing `- ` goes there).
    let second = &written[first_break + 1..];
    let indent = second.len() - second.trim_start_matches([' ', '\t']).len();
    let at = pos_at(source, node, start + first_break + 1 + indent);
    let message = format!(
        "This line goes on with the text of line {}, and YAML joins the lines into one text: {}. \
         If it is a separate alternative, start it with `- ` in the same column as the others. \
         If it is one text, write it on one line, or put it in quotes.",
        node.pos.line,
        quote(value)
    );
    out.push(Diagnostic::warning(
        DiagnosticCode::JoinedLines,
        &at,
        message,
    ));
}

/// A text joined to the `- ` lines below it because it has no `- ` itself: the first
/// alternative written without its dash (`Text:`, then `Welcome!`, then `- Hello!`), or
/// written after `Text:` on the key's own line. Told at the text, where the dash is missing.
/// Whether it was told.
fn missing_dash(
    source: &Source<'_>,
    node: &Node,
    written: &str,
    value: &str,
    out: &mut Vec<Diagnostic>,
) -> bool {
    let start = node.span.as_ref().map_or(0, |s| s.start);
    let line_start = source.text[..start].rfind('\n').map_or(0, |i| i + 1);
    let before = source.text[line_start..start].trim();
    let first_line = written.lines().next().unwrap_or(written).trim_end();
    let message = if before.is_empty() {
        format!(
            "This line has no `- ` in front, but the lines below it start with `- `, so YAML \
             joins them all into one text and the robot says: {}. Put a dash and a space in \
             front of it, in the same column as the `- ` below: `- {first_line}`.",
            quote(value)
        )
    } else if before.ends_with(':') {
        format!(
            "This text is written on the same line as `{before}`, but the lines below it start \
             with `- `, so YAML joins them all into one text and the robot says: {}. Move it \
             to a line of its own under `{before}`, as `- {first_line}` in the same column as \
             the `- ` lines.",
            quote(value)
        )
    } else {
        return false; // A list item itself: the line below is what moved.
    };
    out.push(Diagnostic::error(
        DiagnosticCode::JoinedLines,
        &node.pos,
        message,
    ));
    true
}

/// `Label: WELCOME` with `- ` lines right under it (the `Text:` line forgotten): YAML makes
/// them part of the label. Told at the first `- ` line, where `Text:` belongs; the label
/// meant (its first line) is returned, so the pages naming it are not blamed too.
pub(crate) fn label_swallowed_texts(
    source: &Source<'_>,
    node: &Node,
    out: &mut Vec<Diagnostic>,
) -> Option<String> {
    let written = source.text.get(node.span.clone()?)?;
    let (first, rest) = written.split_once('\n')?;
    let mut offset = first.len() + 1;
    for line in rest.split('\n') {
        let content = line.trim_start_matches(' ');
        if content.starts_with("- ") {
            let start = node.span.as_ref().map_or(0, |s| s.start);
            let at = pos_at(source, node, start + offset + line.len() - content.len());
            let label = first.trim();
            let message = format!(
                "This line starts with `- ` right under `Label: {label}`, with no `Text:` line \
                 between, so YAML makes it part of the label. Add a line `Text:` above it, in \
                 the same column as `Label`."
            );
            out.push(Diagnostic::error(DiagnosticCode::JoinedLines, &at, message));
            return Some(label.to_owned());
        }
        offset += line.len() + 1;
    }
    None
}

/// `– Hello`: Word's en dash bullet is text to YAML.
fn fake_bullet(node: &Node, value: &str, out: &mut Vec<Diagnostic>) {
    let Some(bullet) = value.chars().next().filter(|c| FAKE_BULLETS.contains(c)) else {
        return;
    };
    if !value[bullet.len_utf8()..].starts_with(char::is_whitespace) {
        return;
    }
    let message = format!(
        "This text starts with `{bullet}`, a dash or bullet from a word processor. YAML lists \
         need the plain minus sign `-` (the key next to 0), so this is read as text and the \
         robot says: {}. Replace `{bullet}` with `-` on each line, in the same column as the \
         other `- ` lines.",
        quote(value)
    );
    out.push(Diagnostic::error(
        DiagnosticCode::WordProcessorDash,
        &node.pos,
        message,
    ));
}

/// “Hello”: typographic quotes are not YAML quotes; they stay in the text.
fn curly_quotes(node: &Node, value: &str, out: &mut Vec<Diagnostic>) {
    let trimmed = value.trim();
    let opens = trimmed.starts_with(CURLY_OPEN);
    let closes = trimmed.ends_with(CURLY_CLOSE);
    if !(opens && closes) || trimmed.chars().count() < 2 {
        return;
    }
    let message = format!(
        "This text is in curly quotes, typed by a word processor. YAML takes only straight \
         quotes (\" or ') as quotes, so the curly ones become part of what the robot says: {}. \
         Replace them with straight quotes, or remove them.",
        quote(value)
    );
    out.push(Diagnostic::warning(
        DiagnosticCode::CurlyQuotes,
        &node.pos,
        message,
    ));
}

/// The position of byte `at` of the file, counted from the node's own start.
fn pos_at(source: &Source<'_>, node: &Node, at: usize) -> Pos {
    let start = node.span.as_ref().map_or(0, |s| s.start).min(at);
    let Some(between) = source.text.get(start..at) else {
        return node.pos.clone();
    };
    let lines = between.matches('\n').count();
    let mut pos = node.pos.clone();
    let after_break = between.rsplit('\n').next().unwrap_or_default();
    let chars = u32::try_from(after_break.chars().count()).unwrap_or(0);
    if lines == 0 {
        pos.column = pos.column.saturating_add(chars);
    } else {
        pos.line = pos.line.saturating_add(u32::try_from(lines).unwrap_or(0));
        pos.column = chars + 1;
    }
    pos
}

/// The text as the robot would say it, in quotes; long texts by their start and end.
pub(crate) fn quote(value: &str) -> String {
    let chars: Vec<char> = value.chars().collect();
    if chars.len() <= QUOTE_CHARS {
        return format!("\"{value}\"");
    }
    let head: String = chars[..90].iter().collect();
    let tail: String = chars[chars.len() - 50..].iter().collect();
    format!("\"{head} … {tail}\"")
}
