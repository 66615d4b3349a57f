//! Acts with `WAIT`: the commands before a `WAIT` are sent at once; `WAIT` alone waits until all
//! of the act's earlier commands are done, `WAIT 2s` pauses; then the rest follows. A stop ends
//! the sequence and reports its unsent commands as cancelled.

use std::sync::Arc;

use futures_util::future::join_all;
use tokio::sync::oneshot;
use tokio_util::sync::CancellationToken;

use crate::adapters::{Command, Outcome, Reply};
use crate::content::{Verb, parse_duration};
use crate::dispatch::Dispatcher;
use crate::events::EventKind;

/// Runs `commands` in order, honouring `WAIT`, until done, `stop` is cancelled, or a `WAIT`
/// finds that an earlier command did not succeed (the rest of the act would then act on a
/// false premise, e.g. show an exhibit's page although the robot never drove there).
pub async fn run_sequence(
    dispatcher: Arc<Dispatcher>,
    commands: Vec<Command>,
    stop: CancellationToken,
) {
    let mut outstanding: Vec<(String, oneshot::Receiver<Outcome>)> = Vec::new();
    let mut rest = commands.into_iter();
    let mut abandoned = None;
    for command in rest.by_ref() {
        if command.verb != Verb::Wait {
            let (tx, rx) = oneshot::channel();
            outstanding.push((command.verb.to_string(), rx));
            dispatcher.send(command, Some(tx));
            continue;
        }
        let hub = dispatcher.hub().clone();
        hub.publish(EventKind::CommandSent {
            command: command.id,
            act: Arc::clone(&command.act),
            verb: command.verb.to_string(),
            arg: command.arg.as_deref().map(str::to_owned),
            adapter: "dispatcher",
        });
        let pause = command.arg.as_deref().and_then(parse_duration);
        let reply = Reply::new(hub, command, None);
        reply.started();
        // A pause leaves earlier commands outstanding for a later plain WAIT to wait for.
        let earlier = match pause {
            Some(_) => Vec::new(),
            None => std::mem::take(&mut outstanding),
        };
        let waited = async {
            match pause {
                Some(pause) => {
                    tokio::time::sleep(pause).await;
                    Ok(())
                }
                None => first_failure(earlier).await,
            }
        };
        // A stop cancels the earlier commands too: it must win over "they all ended".
        let outcome = tokio::select! {
            biased;
            () = stop.cancelled() => Err("stopped".to_owned()),
            result = waited => result,
        };
        match outcome {
            Ok(()) => reply.finish(Outcome::Done),
            Err(reason) if stop.is_cancelled() => {
                reply.finish(Outcome::Cancelled(reason));
                abandoned = Some("stopped before it was sent".to_owned());
                break;
            }
            Err(reason) => {
                reply.finish(Outcome::Failed(reason.clone()));
                abandoned = Some(format!("not sent: {reason}"));
                break;
            }
        }
    }
    let reason = abandoned.unwrap_or_default();
    for command in rest {
        let hub = dispatcher.hub().clone();
        Reply::new(hub, command, None).finish(Outcome::Cancelled(reason.clone()));
    }
}

/// Waits for every earlier command; the first that failed, in words.
async fn first_failure(earlier: Vec<(String, oneshot::Receiver<Outcome>)>) -> Result<(), String> {
    let (verbs, outcomes): (Vec<String>, Vec<_>) = earlier.into_iter().unzip();
    let outcomes = join_all(outcomes).await;
    for (verb, outcome) in verbs.iter().zip(outcomes) {
        match outcome {
            // Speech cut short by an interrupting trigger still ended; a stop is seen
            // through the stop token.
            Ok(Outcome::Done | Outcome::Cancelled(_)) => {}
            Ok(Outcome::Failed(why)) => {
                return Err(format!(
                    "an earlier {verb} of this act did not succeed ({why})"
                ));
            }
            Err(_) => return Err(format!("an earlier {verb} of this act was lost")),
        }
    }
    Ok(())
}
