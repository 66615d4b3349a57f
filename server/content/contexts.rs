//! Contexts: the variant names (`TextGroup`, `TextChild`, ...) a bundle uses, and the checks
//! that catch a misspelt one. A misspelt variant is not an error to YAML: the act simply has
//! a variant no visitor is ever in, and a child hears the adult `Text`. With `contexts:` in
//! docent.yaml an undeclared name is an error; without it, a name one typing slip away from
//! another earns a "did you mean", and one that is not `Text` and a capitalised word a
//! warning. A well-formed name only one act uses is a context like any other.

use std::collections::{BTreeMap, BTreeSet};

use crate::DiagnosticCode;
use crate::config::SiteConfig;
use crate::diagnostic::Diagnostic;
use crate::model::{Act, DEFAULT_VARIANT, Pos, Variant};
use crate::suggest::{closest, did_you_mean};

/// `Text`, then the declared contexts, or else every variant name found, sorted.
pub(crate) fn contexts(config: &SiteConfig, acts: &[Act]) -> Vec<String> {
    let rest: Vec<String> = if config.contexts.is_empty() {
        let found: BTreeSet<&str> = acts
            .iter()
            .flat_map(|a| a.variants.iter().map(|v| v.name.as_str()))
            .collect();
        found.into_iter().map(str::to_owned).collect()
    } else {
        config.contexts.clone()
    };
    std::iter::once(DEFAULT_VARIANT.to_owned())
        .chain(rest.into_iter().filter(|c| c != DEFAULT_VARIANT))
        .collect()
}

/// With `contexts:` declared, each variant of one act must be among them.
pub(crate) fn check_declared(config: &SiteConfig, variants: &[Variant], out: &mut Vec<Diagnostic>) {
    if config.contexts.is_empty() {
        return;
    }
    for variant in variants
        .iter()
        .filter(|v| v.name != DEFAULT_VARIANT && !config.contexts.contains(&v.name))
    {
        let hint = did_you_mean(&variant.name, config.contexts.iter().map(String::as_str));
        let message = format!(
            "`{}` is not one of the contexts declared in docent.yaml ({}).{hint} Rename the \
             key, or add it under `contexts:`.",
            variant.name,
            config.contexts.join(", ")
        );
        out.push(Diagnostic::error(
            DiagnosticCode::UnknownContext,
            &variant.pos,
            message,
        ));
    }
}

/// Without `contexts:`, every variant name is a context, and a context one act alone uses is
/// legitimate (the paper's own Fig. 4 has `TextGroup` and `TextFormally` once each). What is
/// most likely a typing error: a name one slip away from a name at least as many acts use
/// (`TextChlid` beside `TextChild`), or a name that does not read as `Text` and a word with a
/// capital (`Textchild`, `Text_child`), which every context is written as.
pub(crate) fn check_undeclared(config: &SiteConfig, acts: &[Act], out: &mut Vec<Diagnostic>) {
    if !config.contexts.is_empty() {
        return;
    }
    let mut uses: BTreeMap<&str, Vec<&Pos>> = BTreeMap::new();
    for variant in acts.iter().flat_map(|a| &a.variants) {
        if variant.name != DEFAULT_VARIANT {
            uses.entry(&variant.name).or_default().push(&variant.pos);
        }
    }
    for (name, places) in &uses {
        let suffix = name.strip_prefix(DEFAULT_VARIANT).unwrap_or(name);
        let likelier = uses
            .iter()
            .filter(|(other, others)| other != &name && others.len() >= places.len())
            .map(|(other, _)| other.strip_prefix(DEFAULT_VARIANT).unwrap_or(other));
        let message = match closest(suffix, likelier) {
            Some(meant) => {
                let meant = format!("{DEFAULT_VARIANT}{meant}");
                let others = uses.get(meant.as_str()).map_or(0, Vec::len);
                format!(
                    "`{name}` is one slip away from `{meant}`, which {others} other act(s) use. \
                     Did you mean `{meant}`? A visitor in the context `{meant}` hears this \
                     act's `Text` instead. List the contexts in docent.yaml \
                     (`contexts: [{meant}, ...]`) and Docent catches such slips as errors."
                )
            }
            None if !well_formed(suffix) => format!(
                "`{name}` does not read as a context name: contexts are `Text` followed by a \
                 word with a capital letter, such as `TextGroup` or `TextChild`. If it is a \
                 typing error, correct it. If it is wanted, list the contexts in docent.yaml \
                 (`contexts: [{name}, ...]`) to confirm it."
            ),
            None => continue,
        };
        for pos in places {
            out.push(Diagnostic::warning(
                DiagnosticCode::ContextTypo,
                pos,
                message.clone(),
            ));
        }
    }
}

/// Whether a context name's part after `Text` reads as a word with a capital (`Group`,
/// `Formally`, `Älter`, `Child2`): how every context in the paper and the guide is written.
fn well_formed(suffix: &str) -> bool {
    suffix.chars().next().is_some_and(char::is_uppercase)
        && suffix.chars().all(char::is_alphanumeric)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn act(variants: &[&str]) -> Act {
        let pos = Pos::new("acts.yaml", 1, 1);
        let variants = variants
            .iter()
            .map(|name| Variant {
                name: (*name).to_owned(),
                pos: pos.clone(),
                alternatives: Vec::new(),
                translations: std::collections::BTreeMap::new(),
            })
            .collect();
        Act {
            label: "A".to_owned(),
            pos,
            variants,
            commands: Vec::new(),
            group: None,
            key: None,
            keywords: Vec::new(),
        }
    }

    fn warnings(acts: &[Act]) -> Vec<String> {
        let mut out = Vec::new();
        check_undeclared(&SiteConfig::default(), acts, &mut out);
        out.iter().map(|d| d.message.clone()).collect()
    }

    #[test]
    fn a_variant_one_slip_from_a_commoner_one_gets_a_did_you_mean() {
        let acts = [
            act(&["Text", "TextChild"]),
            act(&["Text", "TextChild"]),
            act(&["Text", "TextChlid"]),
        ];
        let found = warnings(&acts);
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(
            found[0].contains("Did you mean `TextChild`?"),
            "{}",
            found[0]
        );
        // The paper's Fig. 4: each context used by one act, and no slip between them.
        assert_eq!(
            warnings(&[act(&["Text", "TextGroup", "TextFormally"]), act(&["Text"])]),
            Vec::<String>::new()
        );
        let sloppy = warnings(&[act(&["Text", "Textchild"]), act(&["Text", "Text_Group"])]);
        assert_eq!(sloppy.len(), 2, "{sloppy:?}");
        assert!(
            sloppy[1].contains("`Textchild` does not read as a context name"),
            "{sloppy:?}"
        );
        assert!(
            warnings(&[
                act(&["TextGroup"]),
                act(&["TextGroup", "TextChild"]),
                act(&["TextChild"])
            ])
            .is_empty()
        );
    }

    #[test]
    fn contexts_are_text_then_declared_or_found_names() {
        let acts = [
            act(&["TextGroup", "Text"]),
            act(&["TextChild", "TextGroup"]),
        ];
        assert_eq!(
            contexts(&SiteConfig::default(), &acts),
            ["Text", "TextChild", "TextGroup"]
        );
        let declared = SiteConfig {
            contexts: vec!["TextGroup".into(), "TextFormally".into()],
            ..SiteConfig::default()
        };
        assert_eq!(
            contexts(&declared, &acts),
            ["Text", "TextGroup", "TextFormally"]
        );
        assert_eq!(contexts(&SiteConfig::default(), &[]), ["Text"]);
    }
}
