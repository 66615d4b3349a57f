//! How far the corpus log is written ([`Logged`], which the corpus crate's writer reports) and why an
//! acknowledgement cannot be given when the log cannot be written ([`LogUnwritable`]).

use std::sync::Arc;

use crate::wire::ErrorCode;

pub use docent_corpus::Logged;

/// Why an acknowledgement cannot be given: the event is not in the log.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the corpus log cannot be written ({0}); see the server log")]
pub struct LogUnwritable(pub Arc<str>);

impl LogUnwritable {
    /// The stable error code sent to clients.
    pub const CODE: ErrorCode = ErrorCode::CorpusUnwritable;

    /// Said instead of an acknowledgement: what was asked for was done, but is not known to be
    /// in the log.
    pub fn after_the_fact(&self) -> String {
        format!(
            "carried out, but not confirmed in the log: {self}. New triggers are refused until \
             the log can be written again."
        )
    }

    /// Said when a trigger is refused before anything was done.
    pub fn refusal(&self) -> String {
        format!("not triggered: {self}. Triggers are accepted again once it can be written.")
    }
}

/// `Ok` when `logged` covers `seq`; otherwise why not.
pub(super) fn check_logged(logged: &Logged, seq: u64) -> Result<(), LogUnwritable> {
    if logged.holds(seq) {
        return Ok(());
    }
    if logged.through >= seq {
        return Err(LogUnwritable(
            "it was dropped while the log could not be written (see corpus.gap)".into(),
        ));
    }
    Err(LogUnwritable(match &logged.failure {
        Some(failure) => Arc::clone(failure),
        None => "the corpus writer has stopped".into(),
    }))
}
