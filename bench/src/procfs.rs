//! CPU time and resident memory of the server and of this client, read from /proc (Linux).
//! Every reader returns `None` when /proc has no answer (another OS, or the process is gone),
//! so a report simply leaves those figures out.

use std::fs;
use std::time::{Duration, Instant};

use tokio::time::{sleep, sleep_until};

/// How often the server's VmRSS is sampled.
pub const RSS_SAMPLE_EVERY: Duration = Duration::from_millis(100);

/// What the server and this client used over a measured window.
#[derive(Clone, Copy, Debug, Default)]
pub struct Usage {
    /// Server CPU time over wall time, in % of one core (200 % = both cores of 2).
    pub server_cpu_pct: Option<f64>,
    /// Server CPU seconds (user + system) spent in the window.
    pub server_cpu_s: Option<f64>,
    /// Largest server VmRSS seen, sampled every [`RSS_SAMPLE_EVERY`].
    pub server_rss_peak_kb: Option<u64>,
    /// This client's CPU, in % of one core.
    pub client_cpu_pct: Option<f64>,
    /// CPU time the hypervisor gave to other guests in the window (all cores), in ms.
    pub steal_ms: Option<f64>,
}

fn proc_dir(pid: Option<u32>) -> String {
    match pid {
        Some(pid) => format!("/proc/{pid}"),
        None => "/proc/self".to_owned(),
    }
}

/// User + system CPU seconds of all threads of `pid` (this process when `None`).
pub fn cpu_seconds(pid: Option<u32>) -> Option<f64> {
    let stat = fs::read_to_string(format!("{}/stat", proc_dir(pid))).ok()?;
    // Fields after the parenthesised name start at field 3; utime and stime are 14 and 15.
    let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
    let ticks = fields.get(11)?.parse::<u64>().ok()? + fields.get(12)?.parse::<u64>().ok()?;
    Some(ticks as f64 / 100.0) // USER_HZ is 100 on Linux
}

/// VmRSS of `pid` in kB.
pub fn rss_kb(pid: u32) -> Option<u64> {
    let status = fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find_map(|l| l.strip_prefix("VmRSS:"))?;
    line.trim().trim_end_matches("kB").trim().parse().ok()
}

/// Steal time of the whole machine in seconds: the 8th value of the `cpu` line of /proc/stat.
fn steal_seconds() -> Option<f64> {
    let stat = fs::read_to_string("/proc/stat").ok()?;
    let ticks = stat.lines().next()?.split_whitespace().nth(8)?;
    Some(ticks.parse::<u64>().ok()? as f64 / 100.0)
}

/// The largest VmRSS of `pid` over `window`, sampled every [`RSS_SAMPLE_EVERY`].
pub async fn rss_peak(pid: u32, window: Duration) -> Option<u64> {
    let end = Instant::now() + window;
    let mut peak = rss_kb(pid);
    while Instant::now() < end {
        sleep(RSS_SAMPLE_EVERY).await;
        peak = peak.max(rss_kb(pid));
    }
    peak
}

/// Watches the server (when its pid is known) and this client from `from` to `to`.
pub async fn watch(server: Option<u32>, from: Instant, to: Instant) -> Usage {
    sleep_until(from.into()).await;
    let server_cpu0 = server.and_then(|pid| cpu_seconds(Some(pid)));
    let (client_cpu0, steal0, t0) = (cpu_seconds(None), steal_seconds(), Instant::now());
    let mut rss_peak = None;
    while Instant::now() < to {
        rss_peak = rss_peak.max(server.and_then(rss_kb));
        sleep(RSS_SAMPLE_EVERY).await;
    }
    let window = t0.elapsed().as_secs_f64();
    let server_cpu_s = server
        .and_then(|pid| cpu_seconds(Some(pid)))
        .zip(server_cpu0)
        .map(|(after, before)| after - before);
    let client_cpu_s = cpu_seconds(None)
        .zip(client_cpu0)
        .map(|(after, before)| after - before);
    Usage {
        server_cpu_pct: server_cpu_s.map(|s| s / window * 100.0),
        server_cpu_s,
        server_rss_peak_kb: rss_peak,
        client_cpu_pct: client_cpu_s.map(|s| s / window * 100.0),
        steal_ms: steal_seconds()
            .zip(steal0)
            .map(|(after, before)| (after - before) * 1000.0),
    }
}
