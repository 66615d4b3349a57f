//! One soak from start to end: the server started, the load (kiosks, staff, visits, storms,
//! reloads) run for the plan's length while the server is sampled every second, the load
//! ended and its answers read, the server stopped with SIGTERM and its corpus read back.

use std::path::PathBuf;
use std::process::ExitStatus;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use serde_json::Value;
use tokio::sync::{broadcast, watch};
use tokio::time::{Instant, MissedTickBehavior, interval, interval_at, sleep, sleep_until};
use tokio_util::sync::CancellationToken;

use crate::ledger::{Book, Ledger, Role};
use crate::plan::Plan;
use crate::server::{self, Docent};
use crate::site::Site;
use crate::{kiosk, staff};

/// How long answers still owed may take once the load has ended, and a handshake.
pub const DRAIN: Duration = Duration::from_secs(10);

/// What the load's tasks share.
pub struct Ctx {
    pub plan: Plan,
    /// `127.0.0.1:PORT`.
    pub addr: String,
    pub ledger: Ledger,
    /// Cancelled when the load ends.
    pub done: CancellationToken,
    /// Whether visitors are at the kiosks now (they tap) or not (the session goes idle).
    pub visiting: watch::Receiver<bool>,
    /// Each storm: which kiosks drop their connection.
    pub storms: broadcast::Sender<Arc<Vec<bool>>>,
    /// Kiosks connected now.
    pub connected: AtomicUsize,
}

/// The server, sampled once a second.
#[derive(Clone, Copy, Debug)]
pub struct Sample {
    /// Seconds into the run.
    pub at: f64,
    pub rss_kb: u64,
    pub fds: usize,
    pub kiosks: usize,
    /// Triggers acknowledged so far.
    pub acked: usize,
}

/// Everything a soak leaves to be judged.
pub struct Run {
    pub samples: Vec<Sample>,
    pub book: Book,
    /// Every line of the corpus, in `seq` order.
    pub corpus: Vec<Value>,
    /// The corpus folder (kept until the run is dropped).
    pub corpus_dir: tempfile::TempDir,
    /// `docent`'s exit after SIGTERM; `None` when it did not exit within [`DRAIN`].
    pub exit: Option<ExitStatus>,
    /// Its standard error, for a failure's message.
    pub server_log: String,
    pub reloads: usize,
    pub storms: usize,
    pub wall: Duration,
}

/// Runs `plan` against a fresh server.
pub async fn soak(plan: &Plan) -> Run {
    let started = std::time::Instant::now();
    let site = Site::new();
    let corpus_dir = tempfile::tempdir().expect("a corpus folder");
    let log = corpus_dir.path().with_extension("log");
    let (binary, bundle, corpus, server_log) = (
        plan.docent.clone(),
        site.bundle(),
        corpus_dir.path().to_path_buf(),
        log.clone(),
    );
    // Reading its first lines blocks: not on a worker of the runtime the clients share.
    let docent =
        tokio::task::spawn_blocking(move || Docent::start(&binary, &bundle, &corpus, &server_log))
            .await
            .expect("starting docent");
    let (visits, visiting) = watch::channel(false);
    let start = Instant::now();
    let ctx = Arc::new(Ctx {
        plan: plan.clone(),
        addr: docent.addr.clone(),
        ledger: Ledger::new(start.into_std()),
        done: CancellationToken::new(),
        visiting,
        storms: broadcast::channel(16).0,
        connected: AtomicUsize::new(0),
    });
    let mut clients = Vec::new();
    for k in 0..plan.kiosks {
        clients.push(tokio::spawn(kiosk::kiosk(k, Arc::clone(&ctx))));
    }
    for role in [Role::Operator, Role::Dm] {
        clients.push(tokio::spawn(staff::staff(role, Arc::clone(&ctx))));
    }
    let sampler = tokio::spawn(sample(Arc::clone(&ctx), docent.pid(), start));
    let storms = tokio::spawn(storm(Arc::clone(&ctx)));
    let reloads = tokio::spawn(reload(Arc::clone(&ctx), site));
    let schedule = tokio::spawn(visit(Arc::clone(&ctx), visits));
    // The load's own time line: it runs for the plan's length.
    sleep_until(start + plan.length).await;
    ctx.done.cancel();
    for client in clients {
        client.await.expect("a client task");
    }
    let samples = sampler.await.expect("the sampler");
    let storms = storms.await.expect("the storms");
    let site = reloads.await.expect("the reloads");
    schedule.await.expect("the visits");
    let exit = tokio::task::spawn_blocking(move || docent.stop(DRAIN))
        .await
        .expect("stopping docent");
    let server_log = std::fs::read_to_string(&log).unwrap_or_default();
    let _ = std::fs::remove_file(&log);
    let corpus = read_corpus(corpus_dir.path().to_path_buf());
    Run {
        samples,
        book: ctx.ledger.take(),
        corpus,
        corpus_dir,
        exit,
        server_log,
        reloads: site.reloads(),
        storms,
        wall: started.elapsed(),
    }
}

/// Every line of every event log (day logs and sessions), parsed, in `seq` order.
fn read_corpus(corpus: PathBuf) -> Vec<Value> {
    let logs = docent::corpus::layout::event_logs(&corpus).expect("the corpus folder");
    let mut lines: Vec<Value> = logs
        .iter()
        .flat_map(|log| {
            let text = std::fs::read_to_string(log).expect("a corpus log");
            text.lines()
                .map(|l| serde_json::from_str(l).expect("a corpus line is JSON"))
                .collect::<Vec<Value>>()
        })
        .collect();
    lines.sort_by_key(|e| e["seq"].as_u64());
    lines
}

async fn sample(ctx: Arc<Ctx>, pid: u32, start: Instant) -> Vec<Sample> {
    let mut samples = Vec::new();
    let mut ticks = interval(Duration::from_secs(1));
    ticks.set_missed_tick_behavior(MissedTickBehavior::Delay);
    while !ctx.done.is_cancelled() {
        tokio::select! {
            () = ctx.done.cancelled() => break,
            _ = ticks.tick() => {}
        }
        let (Some(rss_kb), Some(fds)) = (server::rss_kb(pid), server::open_fds(pid)) else {
            ctx.ledger
                .unexpected("the server's /proc entry is gone".into());
            break;
        };
        samples.push(Sample {
            at: start.elapsed().as_secs_f64(),
            rss_kb,
            fds,
            kiosks: ctx.connected.load(Ordering::SeqCst),
            acked: ctx.ledger.acked(),
        });
    }
    samples
}

/// Visits and pauses in turn; a pause is longer than `session_idle`, so each visit is a
/// session of its own.
async fn visit(ctx: Arc<Ctx>, visits: watch::Sender<bool>) {
    loop {
        visits.send_replace(true);
        tokio::select! {
            () = ctx.done.cancelled() => return,
            () = sleep(ctx.plan.visit) => {}
        }
        visits.send_replace(false);
        tokio::select! {
            () = ctx.done.cancelled() => return,
            () = sleep(ctx.plan.pause) => {}
        }
    }
}

/// Every `storm_every`, between `storm_size.0` and `storm_size.1` kiosks, picked at random
/// (a fixed seed: every run meets the same storms), drop their connection at once.
async fn storm(ctx: Arc<Ctx>) -> usize {
    let mut random = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = move || {
        random ^= random << 13;
        random ^= random >> 7;
        random ^= random << 17;
        random
    };
    let every = ctx.plan.storm_every;
    let mut ticks = interval_at(Instant::now() + every, every);
    let mut storms = 0;
    let (least, most) = ctx.plan.storm_size;
    let kiosks = ctx.plan.kiosks;
    loop {
        tokio::select! {
            () = ctx.done.cancelled() => return storms,
            _ = ticks.tick() => {}
        }
        let size = (least + next() as usize % (most - least + 1)).min(kiosks);
        let mut dropped = vec![false; kiosks];
        while dropped.iter().filter(|d| **d).count() < size {
            dropped[next() as usize % kiosks] = true;
        }
        let _ = ctx.storms.send(Arc::new(dropped));
        storms += 1;
    }
}

/// Saves the acts anew every `reload_every`.
async fn reload(ctx: Arc<Ctx>, mut site: Site) -> Site {
    let every = ctx.plan.reload_every;
    let mut ticks = interval_at(Instant::now() + every, every);
    loop {
        tokio::select! {
            () = ctx.done.cancelled() => return site,
            _ = ticks.tick() => site.save(),
        }
    }
}
