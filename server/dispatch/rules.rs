//! The dispatcher's small rules, each a function of the bundle or the state a turn holds:
//! which variant an act speaks in a context, whether a context exists, a source's priority,
//! whether an act is speaking, a "did you mean", and a command as reported to its caller.

use crate::adapters::Command;
use crate::content::config::Channel;
use crate::content::{Act, Bundle, DEFAULT_VARIANT, Variant, closest};
use crate::dispatch::state::State;
use crate::dispatch::{ResolvedCommand, TriggerError};
use crate::events::Source;

/// `context` if `bundle` has it, else `unknown-context` with a suggestion.
pub(super) fn known_context(bundle: &Bundle, context: &str) -> Result<String, TriggerError> {
    if bundle.contexts.iter().any(|c| c == context) {
        return Ok(context.to_owned());
    }
    let suggestion = suggest(context, bundle.contexts.iter().map(String::as_str));
    Err(TriggerError::UnknownContext {
        context: context.to_owned(),
        suggestion,
    })
}

/// The priority of `source` in `bundle`'s settings.
pub(super) fn priority(bundle: &Bundle, source: Source) -> u8 {
    let priorities = bundle.config.priorities;
    match source {
        Source::Kiosk => priorities.kiosk,
        // A reaction acts on its own, as a dialog manager does.
        Source::Dm | Source::Robot => priorities.dm,
        Source::Http => priorities.http,
        Source::Operator | Source::Projector | Source::Adapter | Source::Server => {
            priorities.operator
        }
    }
}

/// Whether speech of act `label` is running or waiting.
pub(super) fn speaking_act(state: &State, label: &str) -> bool {
    (state.lanes.get(&Channel::Speech)).is_some_and(|lane| lane.holds(|c| &*c.act.label == label))
}

/// The variant `act` speaks in `context`: the context's own, else `Text`; `None` when the act
/// says nothing there. The one place this rule lives: the trigger applies it, and
/// `GET /api/acts` sends its result per context so the console only looks it up.
pub fn variant_for<'a>(act: &'a Act, context: &str) -> Option<&'a Variant> {
    act.variant(context)
        .or_else(|| act.variant(DEFAULT_VARIANT))
}

/// Labels and contexts longer than this get no suggestion: comparing them costs too much for
/// what a client could send by the thousand.
const MAX_SUGGESTED_LEN: usize = 128;

/// The closest candidate to `word`, for a "did you mean".
pub(super) fn suggest<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<String> {
    (word.len() <= MAX_SUGGESTED_LEN)
        .then(|| closest(word, candidates).map(str::to_owned))
        .flatten()
}

pub(super) fn resolved(command: &Command) -> ResolvedCommand {
    ResolvedCommand {
        id: command.id,
        verb: command.verb.to_string(),
        arg: command.arg.as_deref().map(str::to_owned),
    }
}
