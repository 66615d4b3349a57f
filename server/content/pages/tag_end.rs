//! A start tag typed without its `>`: the browser reads on to the next `>`, so the text after
//! it (a button's words) becomes part of the tag and is never shown. Reported where the `>`
//! belongs, under `page-hidden-content` (content the visitor never sees).

use crate::DiagnosticCode;
use crate::diagnostic::Diagnostic;

use super::scan::Value;
use super::text::SourceText;

/// Reports the start tag `tag` (its name, at the place of the missing `>`) that swallowed
/// `swallowed`.
pub(super) fn report(source: &SourceText, tag: &Value, swallowed: &str, out: &mut Vec<Diagnostic>) {
    let name = &tag.text;
    let message = format!(
        "This `<{name}>` tag has no `>` here, so the browser reads what follows up to the next \
         `>` (`{swallowed}`) as part of the tag, and it is never shown. Type `>` right here."
    );
    out.push(Diagnostic::error(
        DiagnosticCode::PageHiddenContent,
        &source.pos(tag.at),
        message,
    ));
}
