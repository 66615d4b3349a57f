//! Speech through a real `espeak-ng` process. Without a sound card (CI), speech is verified
//! through its WAV output: one utterance at a time, in order, each with real audio whose length
//! follows its text. espeak-ng must be installed (the test script installs it).

#[path = "speech_espeak/watched.rs"]
mod watched;

use crate::common;

use common::{TempBundle, TestServer};
use serde_json::{Value, json};
use watched::{BLOCKED, WatchedEspeak, unblock};

const ACTS: &str = r#"
- Label: SHORT
  Text: [Hello.]
- Label: LONG
  Text: [Welcome to the museum. Today we will look at computers from the nineteen seventies.]
"#;

fn wav_seconds(path: &std::path::Path) -> f64 {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(&bytes[0..4], b"RIFF");
    assert_eq!(&bytes[8..12], b"WAVE");
    let rate = u32::from_le_bytes(bytes[24..28].try_into().unwrap());
    let bits = u16::from_le_bytes(bytes[34..36].try_into().unwrap());
    assert_eq!(
        (rate, bits),
        (22_050, 16),
        "espeak-ng writes 16-bit 22.05 kHz"
    );
    let samples = (bytes.len() - 44) / 2;
    // Some of it must be sound, not silence.
    let loud = bytes[44..]
        .chunks_exact(2)
        .filter(|s| i16::from_le_bytes([s[0], s[1]]).unsigned_abs() > 1000)
        .count();
    assert!(loud > samples / 20, "the audio is mostly silence");
    samples as f64 / f64::from(rate)
}

fn id(triggered: &Value) -> u64 {
    triggered["commands"][0]["id"].as_u64().unwrap()
}

#[tokio::test]
async fn espeak_speaks_one_utterance_after_another_into_real_audio() {
    assert!(
        docent::adapters::espeak_available(),
        "espeak-ng is not installed: run scripts/test.sh, which installs it"
    );
    let b = TempBundle::new(ACTS).with_file(
        "docent.yaml",
        "speech: {adapter: espeak, voice: en, rate: 220}\n",
    );
    let wavs = tempfile::tempdir().unwrap();
    let server =
        TestServer::start_with(b.path(), |o| o.speech_wav = Some(wavs.path().to_owned())).await;
    let mut op = server.operator().await;
    let long = id(&server.trigger("LONG", json!({})).await);
    let short = id(&server.trigger("SHORT", json!({})).await);
    let events = op
        .events_until(|e| {
            e["command"] == short
                && e["type"].as_str().unwrap().starts_with("command.")
                && e["type"] != "command.sent"
                && e["type"] != "command.started"
        })
        .await;
    let at = |kind: &str, cmd: u64| {
        events
            .iter()
            .position(|e| e["type"] == kind && e["command"] == cmd)
    };
    assert!(at("command.done", short).is_some(), "{events:#?}");
    assert!(at("command.done", long).unwrap() < at("command.started", short).unwrap());
    let long_s = wav_seconds(&wavs.path().join(format!("{long}.wav")));
    let short_s = wav_seconds(&wavs.path().join(format!("{short}.wav")));
    assert!(short_s > 0.2 && short_s < 2.0, "Hello. took {short_s} s");
    assert!(
        long_s > 3.0 * short_s,
        "long {long_s} s vs short {short_s} s"
    );
    // The command took at least as long as its audio: it was "spoken", not just written.
    let mono = |kind: &str, cmd: u64| events[at(kind, cmd).unwrap()]["mono_us"].as_u64().unwrap();
    let spoken = (mono("command.done", long) - mono("command.started", long)) as f64 / 1e6;
    assert!(
        spoken >= long_s,
        "done after {spoken} s for {long_s} s of audio"
    );
    server.stop().await;
}

#[tokio::test]
async fn an_espeak_failure_becomes_command_failed_and_the_next_act_still_runs() {
    assert!(
        docent::adapters::espeak_available(),
        "espeak-ng is not installed: run scripts/test.sh, which installs it"
    );
    let b = TempBundle::new(ACTS).with_file("docent.yaml", "speech: {adapter: espeak}\n");
    let wavs = tempfile::tempdir().unwrap();
    let server =
        TestServer::start_with(b.path(), |o| o.speech_wav = Some(wavs.path().to_owned())).await;
    // espeak-ng cannot write its audio any more; it still exits 0, saying so only on stderr.
    std::fs::remove_dir_all(wavs.path()).unwrap();
    let mut op = server.operator().await;
    let first = id(&server.trigger("SHORT", json!({})).await);
    let failed = op
        .event_where(|e| e["command"] == first && e["type"] == "command.failed")
        .await;
    assert!(
        failed["reason"].as_str().unwrap().contains("Can't write"),
        "{failed}"
    );
    let second = id(&server.trigger("SHORT", json!({})).await);
    op.event_where(|e| e["command"] == second && e["type"] == "command.failed")
        .await;
    let (status, _) = server.get("/healthz").await;
    assert_eq!(status, 200);
    server.stop().await;
}

#[test]
fn an_unknown_voice_is_reported_at_start_up() {
    assert!(
        docent::adapters::espeak_available(),
        "espeak-ng is not installed: run scripts/test.sh, which installs it"
    );
    let voices = docent::adapters::espeak_voices();
    assert!(voices.iter().any(|v| v == "en"), "{voices:?}");
    let b = TempBundle::new(ACTS).with_file(
        "docent.yaml",
        "speech: {adapter: espeak, voice: no-such-voice}\n",
    );
    let bundle = docent::content::load_bundle(b.path()).bundle.unwrap();
    let corpus = tempfile::tempdir().unwrap();
    let options = docent::serve::ServeOptions {
        seed: None,
        corpus_dir: corpus.path().to_owned(),
        corpus_sync: docent::corpus::DEFAULT_SYNC_INTERVAL,
        speech_wav: None,
        access: common::test_access(),
        limits: None,
        media_cache: corpus.path().join("media-cache"),
        media_tools: docent::media::Tools::find(),
    };
    let runtime = tokio::runtime::Runtime::new().unwrap();
    let server =
        runtime.block_on(async { docent::serve::Server::start(bundle, &options).unwrap() });
    assert!(
        server.warnings.iter().any(|w| w.contains("no-such-voice")),
        "{:?}",
        server.warnings
    );
}

fn signal(pid: u32, signal: &str) {
    let sent = std::process::Command::new("kill")
        .args([signal, &pid.to_string()])
        .status();
    assert!(sent.is_ok_and(|s| s.success()), "kill {signal} {pid}");
}

/// True while `pid` exists, even as a zombie nobody reaped.
fn exists(pid: u32) -> bool {
    std::path::Path::new(&format!("/proc/{pid}")).exists()
}

async fn next_outcome(op: &mut common::WsClient, command: u64) -> Value {
    op.event_where(|e| {
        e["command"] == command
            && matches!(
                e["type"].as_str(),
                Some("command.done" | "command.failed" | "command.cancelled")
            )
    })
    .await
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_espeak_killed_mid_utterance_fails_the_say_at_once_and_the_next_one_speaks() {
    assert!(
        docent::adapters::espeak_available(),
        "espeak-ng is not installed: run scripts/test.sh, which installs it"
    );
    let b = TempBundle::new(ACTS).with_file("docent.yaml", "speech: {adapter: espeak}\n");
    let wavs = tempfile::tempdir().unwrap();
    let mut server = WatchedEspeak::start(&b, wavs.path());
    let mut op = server.operator().await;
    let first = server.trigger("LONG").await;
    assert!(first <= BLOCKED, "command {first} has no blocking pipe");
    let pid = server.next_espeak().await;
    let killed_at = std::time::Instant::now();
    signal(pid, "-KILL");
    let failed = next_outcome(&mut op, first).await;
    let told_after = killed_at.elapsed();
    assert_eq!(failed["type"], "command.failed", "{failed}");
    assert_eq!(
        failed["reason"],
        "espeak-ng was killed by signal 9 (SIGKILL) before it finished speaking"
    );
    // Told at once, not when the text would have been said (its hang limit is over 5 s).
    assert!(told_after < docent::adapters::HANG_GRACE, "{told_after:?}");
    assert!(!exists(pid), "espeak-ng {pid} was not reaped");

    unblock(wavs.path());
    let second = server.trigger("SHORT").await;
    let done = next_outcome(&mut op, second).await;
    assert_eq!(done["type"], "command.done", "{done}");
    assert!(wav_seconds(&wavs.path().join(format!("{second}.wav"))) > 0.2);
    server.stop();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_hung_espeak_is_stopped_after_its_hang_limit_and_the_next_say_speaks() {
    assert!(
        docent::adapters::espeak_available(),
        "espeak-ng is not installed: run scripts/test.sh, which installs it"
    );
    let b = TempBundle::new(ACTS).with_file(
        "docent.yaml",
        "speech: {adapter: espeak, voice: en, rate: 220}\n",
    );
    let wavs = tempfile::tempdir().unwrap();
    let mut server = WatchedEspeak::start(&b, wavs.path());
    let mut op = server.operator().await;
    let first = server.trigger("SHORT").await;
    assert!(first <= BLOCKED, "command {first} has no blocking pipe");
    let pid = server.next_espeak().await;
    // Stopped, it neither finishes nor exits: a hang, whatever it was blocked on before.
    signal(pid, "-STOP");
    let events = op
        .events_until(|e| e["command"] == first && e["type"] == "command.failed")
        .await;
    let failed = events.last().unwrap();
    let reason = failed["reason"].as_str().unwrap();
    assert!(
        reason.starts_with("espeak-ng hung: it did not finish within"),
        "{reason}"
    );
    let limit = docent::adapters::hang_limit("Hello.", 220);
    let started = (events.iter())
        .find(|e| e["command"] == first && e["type"] == "command.started")
        .expect("command.started");
    let waited_us = failed["mono_us"].as_u64().unwrap() - started["mono_us"].as_u64().unwrap();
    let waited = std::time::Duration::from_micros(waited_us);
    assert!(
        waited >= limit,
        "failed after {waited:?}, before the limit {limit:?}"
    );
    assert!(
        waited < limit + std::time::Duration::from_secs(5),
        "failed after {waited:?}, long after the limit {limit:?}"
    );
    assert!(
        !exists(pid),
        "the hung espeak-ng {pid} was not killed and reaped"
    );

    unblock(wavs.path());
    let second = server.trigger("SHORT").await;
    let done = next_outcome(&mut op, second).await;
    assert_eq!(done["type"], "command.done", "{done}");
    server.stop();
}

/// Texts espeak-ng takes far longer to say than their words suggest: numbers read out,
/// acronyms spelled, pauses at punctuation, an address and a telephone number.
const SLOW_TEXTS: [&str; 5] = [
    "In 1975 the Altair 8800 cost 439 dollars, or 621 dollars assembled.",
    "1234567 7654321 9876543 1777777",
    "IBM, DEC, HP, NASA, MIT, USB, CPU, RAM, ROM, LED, PDP, VAX, www, etc.",
    "Yes. No. Maybe. Well, perhaps; who knows? Oh! Ah! Hm, right, okay, fine.",
    "See www.example.com/computers/1975 or call +49 30 1234 5678.",
];

#[test]
fn the_hang_limit_never_cuts_real_speech_short() {
    assert!(
        docent::adapters::espeak_available(),
        "espeak-ng is not installed: run scripts/test.sh, which installs it"
    );
    let wavs = tempfile::tempdir().unwrap();
    let wav = wavs.path().join("said.wav");
    for rate in [80, 160, 450] {
        for text in SLOW_TEXTS {
            let mut espeak = std::process::Command::new("espeak-ng")
                .args(["--stdin", "-v", "en", "-s", &rate.to_string(), "-w"])
                .arg(&wav)
                .stdin(std::process::Stdio::piped())
                .spawn()
                .expect("espeak-ng starts");
            let mut stdin = espeak.stdin.take().unwrap();
            std::io::Write::write_all(&mut stdin, text.as_bytes()).unwrap();
            drop(stdin);
            assert!(espeak.wait().unwrap().success());
            let said = std::time::Duration::from_secs_f64(wav_seconds(&wav));
            let limit = docent::adapters::hang_limit(text, rate);
            assert!(
                said < limit - docent::adapters::HANG_GRACE,
                "{text:?} at {rate} wpm took {said:?}, near its hang limit {limit:?}"
            );
        }
    }
}
