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

/// Runs `commands` in order, honouring `WAIT`, until done or `stop` is cancelled.
pub async fn run_sequence(
    dispatcher: Arc<Dispatcher>,
    commands: Vec<Command>,
    stop: CancellationToken,
) {
    let mut outstanding: Vec<oneshot::Receiver<Outcome>> = Vec::new();
    let mut rest = commands.into_iter();
    for command in rest.by_ref() {
        if command.verb != Verb::Wait {
            let (tx, rx) = oneshot::channel();
            outstanding.push(rx);
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
                Some(pause) => tokio::time::sleep(pause).await,
                None => drop(join_all(earlier).await),
            }
        };
        tokio::select! {
            () = waited => reply.finish(Outcome::Done),
            () = stop.cancelled() => {
                reply.finish(Outcome::Cancelled("stopped".into()));
                break;
            }
        }
    }
    for command in rest {
        let hub = dispatcher.hub().clone();
        Reply::new(hub, command, None)
            .finish(Outcome::Cancelled("stopped before it was sent".into()));
    }
}
