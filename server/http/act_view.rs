//! `GET /api/acts`: every act as the operator console reads it: its texts in each of the
//! bundle's languages as the robot would say them (the server's fallback applied, and said),
//! the variant it speaks in each context, its commands and its keywords. The console looks
//! these up instead of repeating the server's rules in JavaScript.

use std::collections::BTreeMap;

use axum::Json;
use axum::extract::State;
use axum::response::{IntoResponse, Response};
use serde::Serialize;
use serde_json::json;

use crate::content::{Act, Bundle, Language, Pos, Variant};
use crate::dispatch::{texts_in, variant_for};
use crate::state::AppState;

#[derive(Serialize)]
struct ActView<'a> {
    label: &'a str,
    at: &'a Pos,
    /// The acts file, relative to the bundle.
    file: &'a str,
    /// The console group: the act's `Group`, else its file name without extension.
    group: &'a str,
    /// The console key (`Alt+` this), if the act has one.
    key: Option<String>,
    variants: Vec<VariantView<'a>>,
    /// For each of the bundle's contexts, the variant the act speaks in it (null: nothing), so
    /// that the console looks the server's choice up instead of repeating its rule.
    speaks: BTreeMap<&'a str, Option<&'a str>>,
    commands: Vec<CommandView<'a>>,
    /// The act's `Keywords` (searched, never spoken).
    keywords: &'a [String],
}

#[derive(Serialize)]
struct VariantView<'a> {
    name: &'a str,
    at: &'a Pos,
    /// The texts in the default language.
    alternatives: Vec<TextView<'a>>,
    /// For each of the bundle's languages, what the robot says for this variant when the
    /// visitor's language is that one: a translation, or the default language's texts
    /// (`language` then says which language they are in).
    languages: BTreeMap<&'a str, LanguageView<'a>>,
}

#[derive(Serialize)]
struct LanguageView<'a> {
    /// The language the texts are in: the one asked for, or the default one in its stead.
    language: Language,
    texts: Vec<&'a str>,
}

#[derive(Serialize)]
struct TextView<'a> {
    text: &'a str,
    at: &'a Pos,
}

#[derive(Serialize)]
struct CommandView<'a> {
    verb: &'a str,
    arg: Option<&'a str>,
    at: &'a Pos,
}

fn variant_view<'a>(bundle: &'a Bundle, variant: &'a Variant) -> VariantView<'a> {
    let languages = bundle.config.languages.all().iter();
    VariantView {
        name: &variant.name,
        at: &variant.pos,
        alternatives: (variant.alternatives.iter())
            .map(|a| TextView {
                text: &a.value,
                at: &a.pos,
            })
            .collect(),
        languages: languages
            .map(|language| {
                let said = texts_in(bundle, variant, language);
                let view = LanguageView {
                    language: said.language,
                    texts: said.alternatives.iter().map(|a| a.value.as_str()).collect(),
                };
                (language.as_str(), view)
            })
            .collect(),
    }
}

fn act_view<'a>(bundle: &'a Bundle, act: &'a Act) -> ActView<'a> {
    ActView {
        label: &act.label,
        at: &act.pos,
        file: &act.pos.file,
        group: act.group_name(),
        key: act.key.map(String::from),
        variants: (act.variants.iter())
            .map(|v| variant_view(bundle, v))
            .collect(),
        speaks: (bundle.contexts.iter())
            .map(|c| (c.as_str(), variant_for(act, c).map(|v| v.name.as_str())))
            .collect(),
        commands: (act.commands.iter())
            .map(|c| CommandView {
                verb: c.value.verb.as_str(),
                arg: c.value.arg.as_deref(),
                at: &c.pos,
            })
            .collect(),
        keywords: &act.keywords,
    }
}

/// `GET /api/acts`: the bundle's contexts and languages (the default first), and every act
/// with its variants (texts per language), commands, keywords and positions.
pub async fn list_acts(State(state): State<AppState>) -> Response {
    let bundle = state.dispatcher.bundle();
    let acts: Vec<ActView<'_>> = (bundle.acts.iter())
        .map(|act| act_view(&bundle, act))
        .collect();
    let languages = bundle.config.languages.all();
    Json(json!({ "contexts": bundle.contexts, "languages": languages, "acts": acts }))
        .into_response()
}
