//! The `idle` scenario: many kiosk connections that say hello and then nothing, and what they
//! cost the server in resident memory.

use std::time::{Duration, Instant};

use futures_util::{StreamExt, stream};
use tokio::time::sleep;

use crate::Error;
use crate::client::{self, Role};
use crate::procfs;

/// Connections opened at once while connecting.
const CONNECT_CONCURRENCY: usize = 16;
/// How long RSS is sampled before and after connecting.
const SAMPLE_WINDOW: Duration = Duration::from_secs(1);

/// What the idle connections cost.
#[derive(Debug)]
pub struct IdleReport {
    pub connections: usize,
    pub connect_s: f64,
    pub rss_before_kb: Option<u64>,
    pub rss_after_kb: Option<u64>,
    /// Server CPU while the connections sat idle, in % of one core.
    pub idle_cpu_pct: Option<f64>,
}

impl IdleReport {
    /// Extra resident memory per connection, in kB.
    pub fn per_connection_kb(&self) -> Option<f64> {
        let (before, after) = (self.rss_before_kb?, self.rss_after_kb?);
        Some((after as f64 - before as f64) / self.connections.max(1) as f64)
    }
}

/// Opens `connections` kiosk connections (each waits for its `welcome`), keeps them open and
/// read (so pings are answered), and samples the server's VmRSS before and after.
pub async fn run(url: &str, connections: usize, pid: Option<u32>) -> Result<IdleReport, Error> {
    let rss_before_kb = match pid {
        Some(pid) => procfs::rss_peak(pid, SAMPLE_WINDOW).await,
        None => None,
    };
    let started = Instant::now();
    let opened: Vec<_> = stream::iter(0..connections)
        .map(|_| client::connect(url, Role::Kiosk))
        .buffer_unordered(CONNECT_CONCURRENCY)
        .collect()
        .await;
    let connect_s = started.elapsed().as_secs_f64();
    let mut readers = Vec::with_capacity(connections);
    for ws in opened {
        let mut ws = ws.map_err(|e| format!("idle connection: {e}"))?;
        readers.push(tokio::spawn(async move {
            while let Some(Ok(_)) = ws.next().await {}
        }));
    }
    sleep(SAMPLE_WINDOW).await;
    let cpu0 = pid.and_then(|p| procfs::cpu_seconds(Some(p)));
    let t0 = Instant::now();
    let rss_after_kb = match pid {
        Some(pid) => procfs::rss_peak(pid, SAMPLE_WINDOW).await,
        None => None,
    };
    let idle_cpu_pct = pid
        .and_then(|p| procfs::cpu_seconds(Some(p)))
        .zip(cpu0)
        .map(|(after, before)| (after - before) / t0.elapsed().as_secs_f64() * 100.0);
    for r in &readers {
        r.abort();
    }
    Ok(IdleReport {
        connections,
        connect_s,
        rss_before_kb,
        rss_after_kb,
        idle_cpu_pct,
    })
}
