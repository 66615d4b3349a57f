//! A kiosk as the soak drives it: a websocket client from its own loopback address
//! (127.0.0.2, 127.0.0.3, ...), as each touchscreen of a site is its own device, so that
//! every kiosk has the allowance of one (5 taps at once, then 4 a second; `docs/PROTOCOL.md`,
//! Kiosks). It taps an offered act every `tap_every` while visitors are there, records when
//! asked (`record` → `clock` → `recording-started`, chunks uploaded over HTTP, `record-stop` →
//! last chunk → `recording-stopped`), and drops its connection when a storm takes it: half
//! the time with a close frame, half the time without a word, as Wi-Fi does.

use std::collections::HashMap;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::sync::Arc;
use std::sync::atomic::Ordering;

use futures_util::{SinkExt, StreamExt};
use serde_json::{Value, json};
use tokio::net::{TcpSocket, TcpStream};
use tokio::sync::mpsc;
use tokio::time::{Instant, MissedTickBehavior, interval_at, sleep_until, timeout};
use tokio_tungstenite::WebSocketStream;
use tokio_tungstenite::tungstenite::Message;

use crate::ledger::Role;
use crate::recorder::{self, Recording};
use crate::run::{Ctx, DRAIN};
use crate::site;

type Ws = WebSocketStream<TcpStream>;

/// How a connection ended.
enum Ending {
    /// A storm took it, or the server ended it: connect again.
    Again,
    /// The load is over.
    Done,
}

/// Runs kiosk `k` until the load ends.
pub async fn kiosk(k: usize, ctx: Arc<Ctx>) {
    let ip = Ipv4Addr::new(127, 0, (k / 200) as u8, (k % 200 + 2) as u8);
    let http = reqwest::Client::builder()
        .local_address(IpAddr::V4(ip))
        .build()
        .expect("an HTTP client");
    let mut kiosk = Kiosk {
        k,
        prefix: format!("k{k}-"),
        taps: 0,
        ctx: Arc::clone(&ctx),
        http,
        recordings: HashMap::new(),
        asked: HashMap::new(),
    };
    // Kiosks tap in turn, spread over one tap period.
    let phase = ctx
        .plan
        .tap_every
        .mul_f64(k as f64 / ctx.plan.kiosks as f64);
    let mut taps = interval_at(Instant::now() + phase, ctx.plan.tap_every);
    taps.set_missed_tick_behavior(MissedTickBehavior::Delay);
    let mut storms = ctx.storms.subscribe();
    let (stopped_tx, mut stopped) = mpsc::unbounded_channel();
    while !ctx.done.is_cancelled() {
        let ws = match connect(&ctx.addr, ip, k).await {
            Ok(ws) => ws,
            Err(e) => {
                ctx.ledger
                    .unexpected(format!("kiosk {k} could not connect: {e}"));
                return;
            }
        };
        ctx.ledger.connected();
        ctx.connected.fetch_add(1, Ordering::SeqCst);
        let ending = kiosk
            .connection(ws, &mut taps, &mut storms, &stopped_tx, &mut stopped)
            .await;
        ctx.connected.fetch_sub(1, Ordering::SeqCst);
        ctx.ledger.dropped(&kiosk.prefix);
        // A recording ends with its kiosk's connection (`kiosk-left`).
        for (_, recording) in kiosk.recordings.drain() {
            recording.upload.abort();
        }
        kiosk.asked.clear();
        if matches!(ending, Ending::Done) {
            return;
        }
    }
}

struct Kiosk {
    k: usize,
    prefix: String,
    taps: u64,
    ctx: Arc<Ctx>,
    http: reqwest::Client,
    /// Recordings under way, by id.
    recordings: HashMap<u64, Recording>,
    /// `record` frames waiting for the clock's answer, by id.
    asked: HashMap<u64, Value>,
}

impl Kiosk {
    async fn connection(
        &mut self,
        mut ws: Ws,
        taps: &mut tokio::time::Interval,
        storms: &mut tokio::sync::broadcast::Receiver<Arc<Vec<bool>>>,
        stopped_tx: &mpsc::UnboundedSender<u64>,
        stopped: &mut mpsc::UnboundedReceiver<u64>,
    ) -> Ending {
        let ctx = Arc::clone(&self.ctx);
        loop {
            tokio::select! {
                () = ctx.done.cancelled() => return self.drain(ws).await,
                storm = storms.recv() => {
                    let Ok(storm) = storm else { continue };
                    if storm[self.k] {
                        if (self.taps + self.k as u64).is_multiple_of(2) {
                            let _ = ws.close(None).await;
                        }
                        return Ending::Again;
                    }
                }
                _ = taps.tick() => {
                    if *ctx.visiting.borrow() && self.tap(&mut ws).await.is_err() {
                        return Ending::Again;
                    }
                }
                Some(recording) = stopped.recv() => {
                    let frame = json!({"type": "recording-stopped", "recording": recording});
                    if ws.send(Message::text(frame.to_string())).await.is_err() {
                        return Ending::Again;
                    }
                }
                msg = ws.next() => match msg {
                    Some(Ok(Message::Text(text))) => {
                        let frame: Value = serde_json::from_str(&text).unwrap_or_default();
                        if self.frame(&mut ws, &frame, stopped_tx).await.is_err() {
                            return Ending::Again;
                        }
                    }
                    Some(Ok(_)) => {}
                    Some(Err(e)) => {
                        ctx.ledger.unexpected(format!("kiosk {}: the connection failed: {e}", self.k));
                        return Ending::Again;
                    }
                    None => {
                        ctx.ledger.unexpected(format!("kiosk {}: the server closed the connection", self.k));
                        return Ending::Again;
                    }
                },
            }
        }
    }

    async fn tap(&mut self, ws: &mut Ws) -> Result<(), tokio_tungstenite::tungstenite::Error> {
        self.taps += 1;
        let reference = format!("{}{}", self.prefix, self.taps);
        let act = site::label((self.k * 7 + self.taps as usize * 3) % site::ACTS);
        self.ctx.ledger.sent(&reference, Role::Kiosk);
        let frame = json!({"type": "trigger", "label": act, "ref": reference, "via": "touch",
            "element": format!("button[data-act={act}]")});
        ws.send(Message::text(frame.to_string())).await
    }

    async fn frame(
        &mut self,
        ws: &mut Ws,
        frame: &Value,
        stopped_tx: &mpsc::UnboundedSender<u64>,
    ) -> Result<(), tokio_tungstenite::tungstenite::Error> {
        let ledger = &self.ctx.ledger;
        let reference = frame["ref"].as_str().unwrap_or_default();
        match frame["type"].as_str().unwrap_or_default() {
            "triggered" => ledger.answered(reference),
            "error" if reference.starts_with(&self.prefix) => {
                ledger.refused(reference, frame["code"].as_str().unwrap_or_default());
            }
            "error" => ledger.unexpected(format!("kiosk {}: {frame}", self.k)),
            "record" => {
                let id = frame["recording"].as_u64().unwrap_or_default();
                self.asked.insert(id, frame.clone());
                let clock = json!({"type": "clock", "t0": id as f64});
                ws.send(Message::text(clock.to_string())).await?;
            }
            "clock" => {
                let id = frame["t0"].as_f64().unwrap_or_default() as u64;
                let Some(record) = self.asked.remove(&id) else {
                    return Ok(());
                };
                let started = json!({"type": "recording-started", "recording": id,
                    "mime": record["mime"], "mono_us": frame["server_us"], "clock_error_us": 500});
                ws.send(Message::text(started.to_string())).await?;
                let upload = recorder::start(
                    Arc::clone(&self.ctx),
                    self.http.clone(),
                    &record,
                    stopped_tx.clone(),
                );
                self.recordings.insert(id, upload);
            }
            "record-stop" => {
                let id = frame["recording"].as_u64().unwrap_or_default();
                if let Some(recording) = self.recordings.remove(&id) {
                    recording.stop();
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// The load is over: no more taps; the answers still owed are read (within [`DRAIN`]),
    /// then the kiosk says goodbye.
    async fn drain(&mut self, mut ws: Ws) -> Ending {
        let deadline = Instant::now() + DRAIN;
        let (never_tx, _) = mpsc::unbounded_channel();
        while self.owed() > 0 {
            let msg = tokio::select! {
                () = sleep_until(deadline) => break,
                msg = ws.next() => msg,
            };
            let Some(Ok(Message::Text(text))) = msg else {
                break;
            };
            let frame: Value = serde_json::from_str(&text).unwrap_or_default();
            if matches!(frame["type"].as_str(), Some("triggered" | "error")) {
                let _ = self.frame(&mut ws, &frame, &never_tx).await;
            }
        }
        if self.owed() > 0 {
            let k = self.k;
            let owed = self.owed();
            self.ctx.ledger.unexpected(format!(
                "kiosk {k}: {owed} triggers unanswered {DRAIN:?} after the load ended"
            ));
        }
        let _ = ws.close(None).await;
        Ending::Done
    }

    fn owed(&self) -> usize {
        let waiting = self.ctx.ledger.waiting();
        waiting
            .iter()
            .filter(|r| r.starts_with(&self.prefix))
            .count()
    }
}

/// Opens a websocket from `ip` and says hello as kiosk `k`; waits for `welcome`.
async fn connect(addr: &str, ip: Ipv4Addr, k: usize) -> Result<Ws, String> {
    let server: SocketAddr = addr.parse().map_err(|e| format!("{addr}: {e}"))?;
    let socket = TcpSocket::new_v4().map_err(|e| e.to_string())?;
    socket
        .bind(SocketAddr::new(IpAddr::V4(ip), 0))
        .map_err(|e| format!("binding {ip}: {e}"))?;
    let stream = socket.connect(server).await.map_err(|e| e.to_string())?;
    stream.set_nodelay(true).map_err(|e| e.to_string())?;
    let url = format!("ws://{addr}/ws");
    let (mut ws, _) = tokio_tungstenite::client_async(url, stream)
        .await
        .map_err(|e| e.to_string())?;
    let hello = json!({"type": "hello", "role": "kiosk", "name": format!("kiosk-{k}")});
    ws.send(Message::text(hello.to_string()))
        .await
        .map_err(|e| e.to_string())?;
    let welcome = async {
        while let Some(Ok(msg)) = ws.next().await {
            if let Message::Text(text) = msg {
                let frame: Value = serde_json::from_str(&text).unwrap_or_default();
                return frame;
            }
        }
        Value::Null
    };
    let frame = timeout(DRAIN, welcome)
        .await
        .map_err(|_| format!("no welcome within {DRAIN:?}"))?;
    if frame["type"] != "welcome" {
        return Err(format!("answered {frame} instead of welcome"));
    }
    Ok(ws)
}
