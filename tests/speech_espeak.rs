//! Speech through a real `espeak-ng` process. Without a sound card (CI), speech is verified
//! through its WAV output: one utterance at a time, in order, each with real audio whose length
//! follows its text. espeak-ng must be installed (the test script installs it).

use crate::common;

use common::{TempBundle, TestServer};
use serde_json::{Value, json};

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
