//! The operator's console and the dialog manager, each one websocket with its credential,
//! triggering an act every `staff_every` on a fixed schedule (not waiting for answers, as a
//! person at a console or a planner does not), reading every frame (the console takes the
//! event stream, as the real one does).

use std::sync::Arc;

use futures_util::{SinkExt, StreamExt};
use serde_json::{Value, json};
use tokio::time::{Instant, MissedTickBehavior, interval, sleep_until, timeout};
use tokio_tungstenite::tungstenite::Message;

use crate::ledger::Role;
use crate::run::{Ctx, DRAIN};
use crate::server::{DM_TOKEN, OPERATOR_TOKEN};
use crate::site;

/// Runs the operator or the dialog manager until the load ends and its answers are in.
pub async fn staff(role: Role, ctx: Arc<Ctx>) {
    let (name, token, prefix) = match role {
        Role::Operator => ("operator", OPERATOR_TOKEN, "o-"),
        _ => ("dm", DM_TOKEN, "d-"),
    };
    let url = format!("ws://{}/ws", ctx.addr);
    let (mut ws, _) = tokio_tungstenite::connect_async(url)
        .await
        .expect("the staff connect");
    let hello =
        json!({"type": "hello", "role": name, "name": format!("soak {name}"), "token": token});
    ws.send(Message::text(hello.to_string()))
        .await
        .expect("hello");
    let mut ticks = interval(ctx.plan.staff_every);
    ticks.set_missed_tick_behavior(MissedTickBehavior::Delay);
    let mut sent = 0_usize;
    let mut deadline = None;
    loop {
        let owed = ctx
            .ledger
            .waiting()
            .iter()
            .filter(|r| r.starts_with(prefix))
            .count();
        if deadline.is_some() && owed == 0 {
            break;
        }
        tokio::select! {
            () = ctx.done.cancelled(), if deadline.is_none() => {
                deadline = Some(Instant::now() + DRAIN);
            }
            () = sleep_until(deadline.unwrap_or_else(Instant::now)), if deadline.is_some() => {
                ctx.ledger.unexpected(format!("{name}: {owed} triggers unanswered {DRAIN:?} after the load ended"));
                break;
            }
            _ = ticks.tick(), if deadline.is_none() => {
                sent += 1;
                let reference = format!("{prefix}{sent}");
                ctx.ledger.sent(&reference, role);
                let frame = json!({"type": "trigger", "label": site::label(sent), "ref": reference});
                if let Err(e) = ws.send(Message::text(frame.to_string())).await {
                    ctx.ledger.unexpected(format!("{name}: could not send: {e}"));
                    return;
                }
            }
            msg = ws.next() => match msg {
                Some(Ok(Message::Text(text))) => {
                    let frame: Value = serde_json::from_str(&text).unwrap_or_default();
                    let reference = frame["ref"].as_str().unwrap_or_default();
                    match frame["type"].as_str().unwrap_or_default() {
                        "triggered" => ctx.ledger.answered(reference),
                        "error" => {
                            ctx.ledger.unexpected(format!("{name}: {frame}"));
                            if !reference.is_empty() {
                                ctx.ledger.refused(reference, frame["code"].as_str().unwrap_or_default());
                            }
                        }
                        _ => {}
                    }
                }
                Some(Ok(_)) => {}
                other => {
                    ctx.ledger.unexpected(format!("{name}: the connection ended: {other:?}"));
                    return;
                }
            },
        }
    }
    let _ = timeout(DRAIN, ws.close(None)).await;
}
