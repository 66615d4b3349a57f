//! What callers give the dispatcher and what they get back; the HTTP and websocket layers
//! turn these into their own wire formats.

use crate::events::Source;
use crate::wire::ErrorCode;
pub use docent_protocol::server_frames::{ResolvedCommand, Triggered};

/// A request to trigger an act.
#[derive(Clone, Debug)]
pub struct TriggerRequest {
    /// The act's label.
    pub label: String,
    /// The context variant to use; the current context when absent.
    pub context: Option<String>,
    /// Whether to clear queued and current speech first.
    pub interrupt: bool,
    /// The caller's own reference, echoed in replies, commands and the log.
    pub reference: Option<String>,
    /// Who asks.
    pub source: Source,
    /// The websocket client that asks, if any.
    pub client: Option<u64>,
}

impl TriggerRequest {
    /// A plain trigger of `label` from `source`.
    pub fn new(label: impl Into<String>, source: Source) -> Self {
        TriggerRequest {
            label: label.into(),
            context: None,
            interrupt: false,
            reference: None,
            source,
            client: None,
        }
    }
}

/// Why a trigger or a context change was refused.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum TriggerError {
    /// No act has this label.
    #[error("there is no act labelled {label:?}{}", hint(.suggestion))]
    UnknownAct {
        /// The label asked for.
        label: String,
        /// The closest existing label.
        suggestion: Option<String>,
    },
    /// No variant of this name exists in the bundle.
    #[error("there is no context {context:?}{}", hint(.suggestion))]
    UnknownContext {
        /// The context asked for.
        context: String,
        /// The closest existing context.
        suggestion: Option<String>,
    },
    /// No such language in the bundle (`languages:`).
    #[error("{language:?} is not one of this bundle's languages ({available})")]
    UnknownLanguage {
        /// The language asked for, as sent.
        language: String,
        /// The bundle's languages, listed.
        available: String,
    },
    /// A touchscreen asked for a language its page offers no button for.
    #[error("the page on the touchscreen offers no button for the language {language:?}")]
    LanguageNotOffered {
        /// The language asked for.
        language: String,
    },
    /// A touchscreen asked for an act whose speech is already running or waiting.
    #[error("the act {label:?} is already being said or about to be; it is not repeated")]
    AlreadySpeaking {
        /// The act asked for.
        label: String,
    },
}

fn hint(suggestion: &Option<String>) -> String {
    suggestion
        .as_ref()
        .map(|s| format!("; did you mean {s:?}?"))
        .unwrap_or_default()
}

impl TriggerError {
    /// The stable error code (`unknown-act`, `unknown-context`, `already-speaking`).
    pub fn code(&self) -> ErrorCode {
        match self {
            TriggerError::UnknownAct { .. } => ErrorCode::UnknownAct,
            TriggerError::UnknownContext { .. } => ErrorCode::UnknownContext,
            TriggerError::AlreadySpeaking { .. } => ErrorCode::AlreadySpeaking,
            TriggerError::UnknownLanguage { .. } => ErrorCode::UnknownLanguage,
            TriggerError::LanguageNotOffered { .. } => ErrorCode::NotOffered,
        }
    }

    /// The suggested correction.
    pub fn suggestion(&self) -> Option<&str> {
        match self {
            TriggerError::UnknownAct { suggestion, .. }
            | TriggerError::UnknownContext { suggestion, .. } => suggestion.as_deref(),
            TriggerError::AlreadySpeaking { .. }
            | TriggerError::UnknownLanguage { .. }
            | TriggerError::LanguageNotOffered { .. } => None,
        }
    }
}
