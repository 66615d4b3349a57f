//! What a session's visitors agreed to. Here, below the corpus and the runtime, because
//! `docent.yaml` names a site's default (`corpus: consent`), the corpus writes it in every
//! session's manifest and the operator's `mark` frames set it.

use serde::{Deserialize, Serialize};

/// What a session's visitors agreed to: whether its audio and video may be kept.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Consent {
    /// They agreed (or the site records by default, with notice).
    Recorded,
    /// They did not agree: nothing of them is recorded.
    Declined,
    /// They took it back: what was recorded is removed, and nothing more is recorded.
    Withdrawn,
}

impl Consent {
    /// The name written in the corpus and in `mark` frames.
    pub fn as_str(self) -> &'static str {
        match self {
            Consent::Recorded => "recorded",
            Consent::Declined => "declined",
            Consent::Withdrawn => "withdrawn",
        }
    }

    /// The state named `word`, if any.
    pub fn from_word(word: &str) -> Option<Consent> {
        [Consent::Recorded, Consent::Declined, Consent::Withdrawn]
            .into_iter()
            .find(|c| c.as_str() == word)
    }
}
