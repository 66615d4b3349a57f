//! Acts nothing can reach. An act is reached by a page (`data-act`, a page script's
//! `docent.trigger`), by the kiosk's idle act, or by the operator, who finds every act in the
//! console: under its `Group`, or under its file's name without one.
//!
//! So an act no page offers is, by itself, the operator's button: the paper's own Fig. 4 has
//! two (WELCOME and OK). Only a bundle that sorts its operator's acts into `Group`s (or gives
//! them `Key`s) says which acts are for the operator; there, an act with no page, no idle
//! timer and no `Group` or `Key` was most often forgotten, or its label misspelt where it is
//! used (the misspelt place is an `unknown-act` of its own).

use std::collections::HashSet;

use crate::DiagnosticCode;
use crate::diagnostic::Diagnostic;
use crate::model::Act;

/// In a bundle whose operator acts have a `Group` or `Key`, warns about each act that no page,
/// idle timer, console group or key reaches. `referenced` holds every label something in the
/// bundle triggers.
pub(crate) fn check_unused<'a>(
    acts: &[Act],
    referenced: impl IntoIterator<Item = &'a str>,
    out: &mut Vec<Diagnostic>,
) {
    let for_operator = |act: &Act| act.group.is_some() || act.key.is_some();
    if !acts.iter().any(for_operator) {
        return;
    }
    let referenced: HashSet<&str> = referenced.into_iter().collect();
    for act in acts {
        if for_operator(act) || referenced.contains(act.label.as_str()) {
            continue;
        }
        let message = format!(
            "Nothing triggers `{0}`: no page offers it (`data-act`), it is not the kiosk's idle \
             act, and unlike this bundle's other acts for the operator it has no `Group` or \
             `Key`. The console lists it only under its file's name. If visitors should reach \
             it, offer it on a page (`data-act=\"{0}\"`); if it is for the operator, give it a \
             `Group:`; if it is left over, remove it.",
            act.label
        );
        out.push(Diagnostic::warning(
            DiagnosticCode::UnusedAct,
            &act.pos,
            message,
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Pos;

    fn act(label: &str, group: Option<&str>) -> Act {
        Act {
            label: label.to_owned(),
            pos: Pos::new("acts.yaml", 1, 10),
            variants: Vec::new(),
            commands: Vec::new(),
            group: group.map(str::to_owned),
            key: None,
            keywords: Vec::new(),
        }
    }

    fn unused(acts: &[Act], referenced: &[&str]) -> Vec<String> {
        let mut out = Vec::new();
        check_unused(acts, referenced.iter().copied(), &mut out);
        out.iter().map(|d| d.message.clone()).collect()
    }

    #[test]
    fn without_groups_every_act_no_page_offers_is_the_operators() {
        let fig4 = [
            act("WELCOME", None),
            act("OK", None),
            act("WHERE_FROM", None),
        ];
        assert!(unused(&fig4, &["WHERE_FROM"]).is_empty());
    }

    #[test]
    fn with_groups_an_act_without_one_and_without_a_page_is_warned_about() {
        let acts = [
            act("HELLO", Some("Small talk")),
            act("OFFERED", None),
            act("FORGOTTEN", None),
        ];
        let found = unused(&acts, &["OFFERED"]);
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(found[0].contains("`FORGOTTEN`"), "{found:?}");
    }
}
