//! The load: subscribers (adapters or kiosks) that time every command frame they read, and
//! senders (operators) that send triggers.
//!
//! Open loop: each sender keeps a fixed schedule of `rate` triggers/s, several senders spread
//! evenly over one period, and latency runs from the time a trigger was *due*, so a server that
//! stalls the client is charged for the wait (no coordinated omission). tokio's timer has 1 ms
//! resolution, so each sender has its own thread and ends its wait with a thread sleep and a
//! spin of at most 100 µs (only up to 2,000 triggers a second in all: beyond, the spinning would
//! take a core from the server). Closed loop: each sender sends its next trigger once the previous one
//! reached every subscriber (or after `drain`, when its missing frames count as lost).
//! All subscribers share the calling thread, as in /work/shared/bench's wsload.

use std::future::Future;
use std::sync::{Arc, mpsc};
use std::thread;
use std::time::{Duration, Instant};

use futures_util::{SinkExt, StreamExt};
use tokio::sync::oneshot;
use tokio::time::{sleep, sleep_until, timeout, timeout_at};
use tokio_tungstenite::tungstenite::Message;

use crate::Error;
use crate::client::{self, Role, Ws};
use crate::procfs::{self, Usage};
use crate::tally::{Summary, Tally};

/// What to run.
#[derive(Clone, Debug)]
pub struct Plan {
    pub url: String,
    pub label: String,
    /// Role of the subscribers: [`Role::SayAdapter`] (answers `done`) or [`Role::Kiosk`].
    pub subscriber: Role,
    pub subscribers: usize,
    pub senders: usize,
    /// Time each sender's own `triggered` answers instead of the subscribers' commands (the
    /// subscribers are then load only).
    pub answers: bool,
    /// Triggers/s per sender; `None` runs closed loop.
    pub rate: Option<f64>,
    pub warmup: Duration,
    pub duration: Duration,
    /// How long to wait for outstanding commands after the last trigger (closed loop: per trigger).
    pub drain: Duration,
    pub server_pid: Option<u32>,
}

/// What a run measured.
pub struct Measured {
    pub summary: Summary,
    pub usage: Usage,
    /// Seconds from the start of the measured window to the last measured delivery (or the
    /// window's length, if longer): what throughput is counted over.
    pub delivery_window_s: f64,
}

/// The shared time line of one run.
#[derive(Clone, Copy)]
struct Clock {
    start: Instant,
    measure_from: Instant,
    end: Instant,
}

struct Job {
    url: String,
    label: String,
    rate: Option<f64>,
    senders: usize,
    drain: Duration,
    answers: bool,
    tally: Tally,
}

/// Runs `plan` on the current (single-threaded) runtime, which the subscribers share.
pub async fn run(plan: &Plan) -> Result<Measured, Error> {
    if plan.subscribers == 0 || plan.senders == 0 {
        return Err("subscribers and senders must be at least 1".into());
    }
    if plan
        .rate
        .is_some_and(|r| r.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater))
    {
        return Err("the rate must be positive".into());
    }
    let job = Arc::new(Job {
        url: plan.url.clone(),
        label: plan.label.clone(),
        rate: plan.rate,
        senders: plan.senders,
        drain: plan.drain,
        answers: plan.answers,
        tally: Tally::new(if plan.answers {
            1
        } else {
            plan.subscribers as u64
        }),
    });
    let mut subscribers = Vec::with_capacity(plan.subscribers);
    for _ in 0..plan.subscribers {
        let ws = client::connect(&plan.url, plan.subscriber).await?;
        let answer = plan.subscriber == Role::SayAdapter;
        subscribers.push(tokio::spawn(subscribe(
            ws,
            job.clone(),
            answer,
            !plan.answers,
        )));
    }

    // Each sender reports once connected and once finished; all start on one clock.
    let (events_tx, mut events) = tokio::sync::mpsc::unbounded_channel();
    let mut starts = Vec::with_capacity(plan.senders);
    let mut threads = Vec::with_capacity(plan.senders);
    for k in 0..plan.senders {
        let (start_tx, start_rx) = mpsc::channel();
        starts.push(start_tx);
        let (job, events_tx) = (job.clone(), events_tx.clone());
        let thread = thread::Builder::new()
            .name(format!("sender-{k}"))
            .spawn(move || sender_thread(&job, k, &start_rx, &events_tx))
            .map_err(|e| format!("starting a sender thread: {e}"))?;
        threads.push(thread);
    }
    drop(events_tx);
    for _ in 0..plan.senders {
        events.recv().await.ok_or("a sender thread died")??;
    }
    let start = Instant::now();
    let measure_from = start + plan.warmup;
    let clock = Clock {
        start,
        measure_from,
        end: measure_from + plan.duration,
    };
    for start_tx in starts {
        start_tx.send(clock)?;
    }
    let usage = tokio::spawn(procfs::watch(plan.server_pid, measure_from, clock.end));
    for _ in 0..plan.senders {
        events.recv().await.ok_or("a sender thread died")??;
    }
    let give_up = Instant::now() + plan.drain;
    while job.tally.outstanding() > 0 && Instant::now() < give_up {
        sleep(Duration::from_millis(10)).await;
    }
    let usage = usage.await?;
    for s in &subscribers {
        s.abort();
    }
    for t in threads {
        let _ = t.join();
    }
    let summary = job.tally.summary();
    let delivered_by = summary.last_delivery.map_or(0.0, |t| {
        t.saturating_duration_since(measure_from).as_secs_f64()
    });
    Ok(Measured {
        summary,
        usage,
        delivery_window_s: plan.duration.as_secs_f64().max(delivered_by),
    })
}

/// A subscriber: times every command frame (when `timed`); an adapter also answers each with
/// `done`.
async fn subscribe(mut ws: Ws, job: Arc<Job>, answer: bool, timed: bool) {
    while let Some(msg) = ws.next().await {
        let text = match msg {
            Ok(Message::Text(text)) => text,
            Ok(Message::Close(_)) => break,
            Ok(_) => continue,
            Err(e) => return eprintln!("docent-bench: subscriber: {e}"),
        };
        let at = Instant::now();
        let Some(frame) = client::parse(&text) else {
            continue;
        };
        match frame.kind.as_str() {
            "command" => {
                if let Some(number) = frame.reference.as_deref().and_then(client::ref_number)
                    && timed
                {
                    job.tally.deliver(number, at);
                }
                if answer
                    && let Some(id) = frame.id
                    && let Err(e) = ws.send(client::done(id)).await
                {
                    return eprintln!("docent-bench: adapter could not answer: {e}");
                }
            }
            "error" => job
                .tally
                .error(frame.message.as_deref().unwrap_or_default()),
            _ => {}
        }
    }
    eprintln!("docent-bench: the server closed a subscriber's connection");
}

fn sender_thread(
    job: &Job,
    k: usize,
    start: &mpsc::Receiver<Clock>,
    events: &tokio::sync::mpsc::UnboundedSender<Result<(), Error>>,
) {
    let rt = match tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
    {
        Ok(rt) => rt,
        Err(e) => return drop(events.send(Err(format!("sender runtime: {e}").into()))),
    };
    let mut ws = match rt.block_on(client::connect(&job.url, Role::Operator)) {
        Ok(ws) => ws,
        Err(e) => return drop(events.send(Err(e))),
    };
    let _ = events.send(Ok(()));
    let Ok(clock) = start.recv() else { return };
    let finished = rt.block_on(async {
        let send = async {
            match job.rate {
                Some(rate) => open_loop(&mut ws, job, clock, k, rate).await,
                None => closed_loop(&mut ws, job, clock).await,
            }
        };
        // Bounded whatever the server does: a server that stops reading ends the run.
        timeout_at((clock.end + job.drain).into(), send)
            .await
            .unwrap_or_else(|_| {
                eprintln!("docent-bench: sender {k}: the server stopped taking triggers");
                Ok(())
            })
    });
    let _ = rt.block_on(ws.close(None));
    let _ = events.send(finished);
}

/// tokio's timer only brings a sender close to a due time; a thread sleep and a short spin on
/// the sender's own thread do the rest.
const COARSE: Duration = Duration::from_millis(2);
const SPIN: Duration = Duration::from_micros(100);

/// Above this many triggers a second in all, senders do not spin: 10,000 spins of 100 µs a
/// second would take a whole core from the server on a 2-core machine, and a sender that
/// wakes a little late is charged for it anyway (latency runs from the due time).
const MOST_SPUN_PER_SECOND: f64 = 2_000.0;

fn wait_precisely(due: Instant, spin: bool) {
    let spin = if spin { SPIN } else { Duration::ZERO };
    if let Some(rest) = due.checked_duration_since(Instant::now())
        && rest > spin
    {
        thread::sleep(rest - spin);
    }
    while Instant::now() < due {
        std::hint::spin_loop();
    }
}

async fn open_loop(ws: &mut Ws, job: &Job, clock: Clock, k: usize, rate: f64) -> Result<(), Error> {
    // Senders are spread evenly over one period instead of all firing together.
    let offset = k as f64 / job.senders as f64;
    let spin = job.senders as f64 * rate <= MOST_SPUN_PER_SECOND;
    let schedule = (0u64..)
        .map(|i| clock.start + Duration::from_secs_f64((i as f64 + offset) / rate))
        .take_while(|due| *due < clock.end);
    for due in schedule {
        let coarse = due.checked_sub(COARSE).unwrap_or(due);
        read_until(ws, job, sleep_until(coarse.into())).await?;
        wait_precisely(due, spin);
        let number = job.tally.register(due, due >= clock.measure_from, None);
        ws.send(client::trigger(&job.label, number)).await?;
    }
    if job.answers {
        // The last answers are read too (the caller bounds the wait by the drain).
        let all_answered = async {
            while job.tally.outstanding() > 0 {
                sleep(Duration::from_millis(5)).await;
            }
        };
        read_until(ws, job, all_answered).await?;
    }
    Ok(())
}

async fn closed_loop(ws: &mut Ws, job: &Job, clock: Clock) -> Result<(), Error> {
    loop {
        let now = Instant::now();
        if now >= clock.end {
            return Ok(());
        }
        let (all_arrived, arrived) = oneshot::channel();
        let measured = now >= clock.measure_from;
        let number = job.tally.register(now, measured, Some(all_arrived));
        ws.send(client::trigger(&job.label, number)).await?;
        // After `drain` the trigger's missing frames count as lost and the sender moves on.
        let _ = read_until(ws, job, timeout(job.drain, arrived)).await?;
    }
}

/// Waits for `until` while reading the sender's own connection (its `triggered` answers,
/// timed when the job times answers), counting `error` frames.
async fn read_until<F: Future>(ws: &mut Ws, job: &Job, until: F) -> Result<F::Output, Error> {
    tokio::pin!(until);
    loop {
        tokio::select! {
            biased;
            out = &mut until => return Ok(out),
            msg = ws.next() => match msg {
                Some(Ok(Message::Text(text))) => {
                    // Frames start with their type (serde writes the tag first); only errors
                    // are read further.
                    if text.starts_with(r#"{"type":"error""#) {
                        let frame = client::parse(&text);
                        job.tally.error(frame.and_then(|f| f.message).as_deref().unwrap_or(&text));
                    } else if job.answers && text.starts_with(r#"{"type":"triggered""#) {
                        let at = Instant::now();
                        let frame = client::parse(&text);
                        let number = frame.and_then(|f| f.reference).as_deref().and_then(client::ref_number);
                        if let Some(number) = number {
                            job.tally.deliver(number, at);
                        }
                    }
                }
                Some(Ok(Message::Close(_))) | None => {
                    return Err("the server closed a sender's connection".into());
                }
                Some(Ok(_)) => {}
                Some(Err(e)) => return Err(format!("sender: {e}").into()),
            },
        }
    }
}
