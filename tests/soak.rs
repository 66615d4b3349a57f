//! The soak: two hours of a museum's day compressed twelvefold, against the real `docent`
//! binary with real clients: 50 kiosks tapping (each from its own loopback address), an
//! operator and a dialog manager triggering, storms that drop 20 to 50 kiosks at once every
//! 2.5 s, the acts saved anew every 5 s (live reload), sessions a visit's taps start and 5 s
//! without one end, and the kiosks' recordings uploaded chunk by chunk. Then SIGTERM, and the
//! rules of `soak/verdict.rs`: memory and descriptors flat, every acknowledged trigger in the
//! corpus once, no session left open, p99 latency stable.
//!
//! One implementation, two lengths: the test command runs it for one minute against the
//! debug binary; `bench/soak.sh` for ten minutes against the release binary
//! (`DOCENT_SOAK_SECONDS`, `DOCENT_SOAK_BIN`), keeping its samples and plot
//! (`DOCENT_SOAK_OUT`). A binary of its own: it owns the machine's cores while it measures.

#[path = "common/mod.rs"]
mod common;
#[path = "soak/kiosk.rs"]
mod kiosk;
#[path = "soak/ledger.rs"]
mod ledger;
#[path = "soak/plan.rs"]
mod plan;
#[path = "soak/planted.rs"]
mod planted;
#[path = "soak/recorder.rs"]
mod recorder;
#[path = "soak/report.rs"]
mod report;
#[path = "soak/run.rs"]
mod run;
#[path = "soak/server.rs"]
mod server;
#[path = "soak/site.rs"]
mod site;
#[path = "soak/staff.rs"]
mod staff;
#[path = "soak/verdict.rs"]
mod verdict;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_compressed_day_of_taps_storms_reloads_and_recordings_leaks_nothing_and_loses_nothing() {
    let plan = plan::Plan::from_env();
    let run = run::soak(&plan).await;
    let verdict = verdict::judge(&plan, &run);
    eprintln!("{}", report::summary(&run, &verdict));
    if let Some(dir) = &plan.out {
        report::write(dir, &plan, &run, &verdict);
    }
    assert!(
        verdict.failures.is_empty(),
        "the soak failed:\n{}",
        verdict.failures.join("\n")
    );
}
