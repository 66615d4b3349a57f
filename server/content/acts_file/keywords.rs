//! `Keywords:`: words an operator may search an act by that the act neither says nor shows
//! (`film` for an act that projects `card-punch.webm`). The console only searches them; the
//! robot never says them, so they are not checked as speech and have no translations: write
//! the words of every language in the one list.

use crate::DiagnosticCode;
use crate::diagnostic::Diagnostic;

use super::yaml::{Kind, Node};

const USAGE: &str = "Write the words the operator may search this act by, as a list \
                     (`Keywords: [film, video, Film]`) or one text (`Keywords: film video`).";

/// The keywords, trimmed, in written order (one text is one keyword); usable ones are kept
/// when others are reported (`bad-value`, at the entry).
pub(super) fn read_keywords(value: &Node, out: &mut Vec<Diagnostic>) -> Vec<String> {
    match &value.kind {
        Kind::Seq(items) => items
            .iter()
            .filter_map(|item| one_keyword(item, out))
            .collect(),
        _ => one_keyword(value, out).into_iter().collect(),
    }
}

/// One entry: a non-empty text, else `None` after reporting it.
fn one_keyword(node: &Node, out: &mut Vec<Diagnostic>) -> Option<String> {
    let problem = match &node.kind {
        Kind::Str { value, .. } | Kind::Guessed(value) if !value.trim().is_empty() => {
            return Some(value.trim().to_owned());
        }
        Kind::Str { .. } | Kind::Null => "empty".to_owned(),
        _ => node.describe().to_owned(),
    };
    let message =
        format!("A keyword must be a word or a few words, but this one is {problem}. {USAGE}");
    out.push(Diagnostic::error(
        DiagnosticCode::BadValue,
        &node.pos,
        message,
    ));
    None
}
