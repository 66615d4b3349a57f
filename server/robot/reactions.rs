//! The site's `reactions:` carried out: a robot event whose reading passes a reaction's
//! condition triggers its act, at most once per cool-down, as source `robot` (a dialog
//! manager's priority: it never overrides an operator). A condition that cannot be decided
//! (a field the event did not carry) is told as `reaction.failed`, once per cool-down, rather
//! than taken as "no": the author's mapping is wrong, and they should hear of it.

use std::collections::HashMap;
use std::sync::Mutex;

use serde_json::Value;
use tokio::time::Instant;

use crate::content::config::Reaction;
use crate::dispatch::{Dispatcher, TriggerRequest};
use crate::events::{EventKind, Hub, ReactionFailed, Source};
use crate::sync::lock;

/// A reaction's identity across live reloads: its place and what it maps, so an edited
/// reaction starts afresh and an untouched one keeps its cool-down.
type ReactionKey = (usize, String, String);

/// When each reaction last fired, and last told of a condition it could not decide.
#[derive(Default)]
pub struct Reactions {
    fired: Mutex<HashMap<ReactionKey, Instant>>,
    told: Mutex<HashMap<ReactionKey, Instant>>,
}

/// What one reaction did with one event (for tests and the caller's log).
#[derive(Clone, Debug, PartialEq)]
pub enum Reacted {
    /// It triggered its act.
    Triggered,
    /// Its condition did not hold.
    NotMet,
    /// It fired less than its cool-down ago.
    CoolingDown,
    /// Its condition could not be decided; told unless told within the cool-down.
    Undecided(String),
    /// The dispatcher refused the act (logged by the dispatcher as `trigger.refused`).
    Refused(String),
}

impl Reactions {
    /// Runs every reaction of `reactions` that listens for `event`, in written order.
    pub fn react(
        &self,
        reactions: &[Reaction],
        (event, data): (&str, &Value),
        dispatcher: &std::sync::Arc<Dispatcher>,
        hub: &Hub,
    ) -> Vec<Reacted> {
        let now = Instant::now();
        let listening = reactions.iter().enumerate();
        let listening = listening.filter(|(_, r)| r.event == event);
        let mut outcomes = Vec::new();
        for (index, reaction) in listening {
            let key = (index, reaction.event.clone(), reaction.act.clone());
            let decided = match &reaction.condition {
                Some(condition) => condition.holds(data),
                None => Ok(true),
            };
            let outcome = match decided {
                Ok(false) => Reacted::NotMet,
                Err(reason) => {
                    if !recent(&self.told, &key, now, reaction) {
                        lock(&self.told).insert(key, now);
                        hub.publish(EventKind::ReactionFailed(ReactionFailed {
                            reaction: index + 1,
                            event: event.to_owned(),
                            act: reaction.act.clone(),
                            reason: format!(
                                "the condition `{}` could not be decided: {reason}; fix `if:` \
                                 in docent.yaml's reactions, or what the robot sends",
                                reaction
                                    .condition
                                    .as_ref()
                                    .map(ToString::to_string)
                                    .unwrap_or_default()
                            ),
                        }));
                    }
                    Reacted::Undecided(reason)
                }
                Ok(true) if recent(&self.fired, &key, now, reaction) => Reacted::CoolingDown,
                Ok(true) => {
                    // The cool-down runs from the attempt: a refused act is not retried at the
                    // sensor's rate.
                    lock(&self.fired).insert(key, now);
                    let mut request = TriggerRequest::new(reaction.act.clone(), Source::Robot);
                    request.reference = Some(format!("reaction {}: {event}", index + 1));
                    match dispatcher.trigger(request) {
                        Ok(_) => Reacted::Triggered,
                        Err(refused) => Reacted::Refused(refused.to_string()),
                    }
                }
            };
            outcomes.push(outcome);
        }
        outcomes
    }
}

fn recent(
    times: &Mutex<HashMap<ReactionKey, Instant>>,
    key: &ReactionKey,
    now: Instant,
    reaction: &Reaction,
) -> bool {
    lock(times)
        .get(key)
        .is_some_and(|at| now.duration_since(*at) < reaction.cooldown)
}

#[cfg(test)]
#[path = "reactions_tests.rs"]
mod tests;
