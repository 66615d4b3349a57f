//! The visitor's language: one robot-wide state like the context (a robot speaks to one
//! visitor group at a time). Set by a kiosk's language button, an operator or a dialog
//! manager; back to the bundle's default when a visitor session ends or a reloaded bundle
//! lacks it. Every change is a `language.changed` event and a `language` frame to the kiosks,
//! which then show their page in the new language.

use crate::content::{Bundle, Language, Located, Variant};
use crate::dispatch::state::State;
use crate::dispatch::{Dispatcher, TriggerError};
use crate::events::{EventKind, Source};
use crate::sync::lock;

/// The texts of a variant chosen for the visitor's language.
pub(crate) struct InLanguage<'b> {
    /// The alternatives to choose from.
    pub alternatives: &'b [Located<String>],
    /// The language they are in (the default one when the variant has no translation).
    pub language: Language,
    /// The chooser's key: its memory of the last alternative is kept per language.
    pub chooser_key: String,
}

/// `variant`'s texts in `language`, falling back to the bundle's default language.
pub(crate) fn texts_in<'b>(
    bundle: &Bundle,
    variant: &'b Variant,
    language: &Language,
) -> InLanguage<'b> {
    match variant.in_language(language) {
        (alternatives, Some(language)) => InLanguage {
            alternatives,
            language: language.clone(),
            chooser_key: format!("{}@{language}", variant.name),
        },
        (alternatives, None) => InLanguage {
            alternatives,
            language: bundle.config.languages.default_language().clone(),
            chooser_key: variant.name.clone(),
        },
    }
}

/// The bundle's language spelt `wanted` (any case), or `unknown-language` listing them.
fn bundle_language(bundle: &Bundle, wanted: &str) -> Result<Language, TriggerError> {
    let languages = &bundle.config.languages;
    (languages.find(wanted).cloned()).ok_or_else(|| TriggerError::UnknownLanguage {
        language: wanted.to_owned(),
        available: languages.listed(),
    })
}

impl Dispatcher {
    /// The visitor's language now.
    pub fn language(&self) -> Language {
        lock(&self.state).language.clone()
    }

    /// Changes the visitor's language to the bundle's language spelt `wanted`; a kiosk
    /// (`Source::Kiosk`) only to one a button on `page` offers. `answer`, the client that
    /// asked, is answered among the notices, after every screen was told.
    pub fn set_language(
        &self,
        wanted: &str,
        source: Source,
        page: Option<&str>,
        answer: Option<super::Answer>,
    ) -> Result<Language, TriggerError> {
        // Checked and changed in one turn, against the bundle live then (as the context).
        let mut turn = self.turn();
        let bundle = &turn.bundle;
        let language = bundle_language(bundle, wanted)?;
        if source == Source::Kiosk
            && !page.is_some_and(|page| bundle.page_offers_language(page, &language))
        {
            return Err(TriggerError::LanguageNotOffered {
                language: language.to_string(),
            });
        }
        self.publish_language(&mut turn.state, language.clone(), source, answer);
        Ok(language)
    }

    /// Takes the language a reconnecting kiosk shows its pages in (its `hello`), when nothing
    /// changed the language since this server started: a server restarted mid-visit goes on
    /// in the visitor's language instead of the default. Once anything changed it (a button,
    /// an operator, a session's end), the server's language stands and the kiosk follows it.
    /// Returns the language in force.
    pub fn adopt_kiosk_language(&self, wanted: &str) -> Result<Language, TriggerError> {
        let mut turn = self.turn();
        let language = bundle_language(&turn.bundle, wanted)?;
        if turn.state.language_changed || turn.state.language == language {
            return Ok(turn.state.language.clone());
        }
        self.publish_language(&mut turn.state, language.clone(), Source::Kiosk, None);
        Ok(language)
    }

    /// Makes `language` the visitor's, logs the change and tells the kiosks, in one turn: the
    /// log's last change is the language in force.
    pub(super) fn publish_language(
        &self,
        state: &mut State,
        language: Language,
        source: Source,
        answer: Option<super::Answer>,
    ) {
        state.language_changed = true;
        let event = self.hub.publish(EventKind::LanguageChanged {
            source,
            language: language.clone(),
        });
        self.notify(super::Notice::Language {
            language: language.clone(),
            seq: event.seq,
            answer,
        });
        state.language = language;
    }

    /// Back to the default language after `bundle` went live, if it lacks the current one.
    pub(super) fn keep_language(&self, state: &mut State, bundle: &Bundle) {
        if bundle.config.languages.all().contains(&state.language) {
            return;
        }
        let default = bundle.config.languages.default_language().clone();
        self.publish_language(state, default, Source::Server, None);
    }

    /// Back to the bundle's default language, when a visitor session ended: the next
    /// visitors start in it. Called by the session's end itself (`operator::Visits`), in the
    /// same step, so no end is missed and none is taken for another.
    pub fn back_to_default(&self) {
        let mut turn = self.turn();
        let default = turn.bundle.config.languages.default_language().clone();
        if turn.state.language != default {
            self.publish_language(&mut turn.state, default, Source::Server, None);
        }
    }
}
