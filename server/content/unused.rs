//! Acts nothing can reach. An act is reached by a page (`data-act`, a page script's
//! `docent.trigger`), by the kiosk's idle act, or by the operator, who finds it in the console
//! under its `Group` or fires it with its `Key`. An act with none of these is heard only if a
//! dialog manager asks for it by name: most often it was forgotten, or its label misspelt where
//! it is used.

use std::collections::HashSet;

use crate::DiagnosticCode;
use crate::diagnostic::Diagnostic;
use crate::model::Act;

/// Warns about each act that no page, idle timer or console group or key reaches.
/// `referenced` holds every label something in the bundle triggers.
pub(crate) fn check_unused<'a>(
    acts: &[Act],
    referenced: impl IntoIterator<Item = &'a str>,
    out: &mut Vec<Diagnostic>,
) {
    let referenced: HashSet<&str> = referenced.into_iter().collect();
    for act in acts {
        if act.group.is_some() || act.key.is_some() || referenced.contains(act.label.as_str()) {
            continue;
        }
        let message = format!(
            "Nothing triggers `{}`: no page offers it (`data-act`), it is not the kiosk's idle \
             act, and it has no `Group` or `Key` for the operator console. Visitors will hear \
             it only if a dialog manager asks for it by name. Offer it on a page, give it a \
             `Group:` so the operator finds it, or remove it.",
            act.label
        );
        out.push(Diagnostic::warning(
            DiagnosticCode::UnusedAct,
            &act.pos,
            message,
        ));
    }
}
