//! A kiosk's recording, uploaded as its browser would: one chunk every `chunk_every`, strictly
//! in order, each `PUT /api/recordings/{recording}/chunks/{seq}` with the recording's token;
//! told to stop, it uploads its last chunk and reports `recording-stopped` through its kiosk.
//! The bytes are not WebM: Docent stores chunks as they come (as `tests/corpus_recording.rs`
//! shows), and what the soak checks is that every acknowledged byte is kept.

use std::sync::Arc;

use serde_json::Value;
use tokio::sync::{mpsc, oneshot};
use tokio::task::JoinHandle;
use tokio::time::{MissedTickBehavior, interval};

use crate::run::Ctx;

/// A recording under way.
pub struct Recording {
    stop: oneshot::Sender<()>,
    /// The uploading task; aborted when the kiosk's connection ends.
    pub upload: JoinHandle<()>,
}

impl Recording {
    /// `record-stop` arrived: the last chunk goes up, then the kiosk reports it.
    pub fn stop(self) {
        let _ = self.stop.send(());
    }
}

/// Starts uploading the recording a `record` frame asked for; its id goes to `stopped` once
/// its last chunk is stored.
pub fn start(
    ctx: Arc<Ctx>,
    http: reqwest::Client,
    record: &Value,
    stopped: mpsc::UnboundedSender<u64>,
) -> Recording {
    let (stop, told) = oneshot::channel();
    let id = record["recording"].as_u64().unwrap_or_default();
    let upload = format!(
        "http://{}{}",
        ctx.addr,
        record["upload"].as_str().unwrap_or_default()
    );
    let token = record["token"].as_str().unwrap_or_default().to_owned();
    let upload = tokio::spawn(async move {
        let mut told = told;
        let mut ticks = interval(ctx.plan.chunk_every);
        ticks.set_missed_tick_behavior(MissedTickBehavior::Delay);
        let body = vec![0x1a_u8; ctx.plan.chunk_bytes];
        for seq in 0_u64.. {
            let last = tokio::select! {
                _ = ticks.tick() => false,
                _ = &mut told => true,
            };
            let sent = http
                .put(format!("{upload}{seq}"))
                .bearer_auth(&token)
                .body(body.clone())
                .send()
                .await;
            let response = match sent {
                Ok(response) => response,
                Err(e) => {
                    return ctx
                        .ledger
                        .unexpected(format!("recording {id}: chunk {seq} not sent: {e}"));
                }
            };
            match response.status().as_u16() {
                200 => {
                    let answer: Value = response.json().await.unwrap_or_default();
                    let acked = answer["acked"].as_u64().unwrap_or_default();
                    ctx.ledger.chunk(id, acked);
                }
                // Closed by the server (the session ended and its last chunk was late, or the
                // server is stopping): nothing more to upload.
                410 => return,
                status => {
                    let answer = response.text().await.unwrap_or_default();
                    return ctx
                        .ledger
                        .unexpected(format!("recording {id}: chunk {seq}: {status} {answer}"));
                }
            }
            if last {
                let _ = stopped.send(id);
                return;
            }
        }
    });
    Recording { stop, upload }
}
