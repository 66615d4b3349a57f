//! The `espeak` speech adapter: one `espeak-ng` process per utterance, one utterance at a time,
//! killed when speech is cancelled.
//!
//! espeak-ng exits 0 even when it could not play (no sound card) or write (bad `-w` path); the
//! only sign is its stderr (`../shared/notes/devices.md`). So a `SAY` is done only when the
//! process exited 0 *and* said nothing alarming on stderr; with WAV output, also only when the
//! file holds audio. Text goes in on stdin so it is never mistaken for an option.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::Stdio;
use std::time::Duration;

use tokio::io::AsyncWriteExt;
use tokio::process::Command as Process;

use crate::adapters::worker::{Task, Worker};
use crate::adapters::{Command, Outcome};
use crate::content::Language;
use crate::lifecycle::Lifecycle;

/// espeak-ng's WAV format: 16-bit mono at 22,050 Hz after a 44-byte header.
const WAV_HEADER: u64 = 44;
const WAV_BYTES_PER_SECOND: f64 = 22_050.0 * 2.0;

/// Where speech goes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SpeechOutput {
    /// The sound device.
    Audio,
    /// One WAV file per utterance in this folder, named `<command id>.wav`; the command is
    /// done once the audio's duration has passed, as if spoken (used without a sound card).
    Wav(PathBuf),
}

/// True when `espeak-ng` can be started.
pub fn espeak_available() -> bool {
    std::process::Command::new("espeak-ng")
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// True when espeak-ng can reach a sound device: it speaks a silent utterance and must not
/// complain on stderr (it exits 0 either way).
pub fn espeak_can_play() -> bool {
    std::process::Command::new("espeak-ng")
        .args(["-a", "0", "."])
        .stdout(Stdio::null())
        .output()
        .is_ok_and(|out| {
            out.status.success() && alarming(&String::from_utf8_lossy(&out.stderr)).is_none()
        })
}

/// The voice names espeak-ng knows (languages such as `en-us` and voice files such as
/// `gmw/en`). espeak-ng silently falls back to its default voice for an unknown name, so the
/// server checks the configured voice against this list at start-up.
pub fn espeak_voices() -> Vec<String> {
    let Ok(out) = std::process::Command::new("espeak-ng")
        .arg("--voices")
        .output()
    else {
        return Vec::new();
    };
    let listing = String::from_utf8_lossy(&out.stdout);
    // Columns: priority, language, age/gender, voice name, file, then "(language priority)"
    // pairs for other languages; espeak-ng accepts any of these names and the file's base name.
    let mut names: Vec<String> = Vec::new();
    for line in listing.lines().skip(1) {
        let columns: Vec<&str> = line.split_whitespace().collect();
        let [_, language, _, voice, file, others @ ..] = &columns[..] else {
            continue;
        };
        let base = file.rsplit('/').next().unwrap_or(file);
        names.extend([language, voice, file, &base].map(|s| (*s).to_owned()));
        names.extend(
            others
                .iter()
                .filter_map(|o| o.strip_prefix('('))
                .map(str::to_owned),
        );
    }
    names.sort();
    names.dedup();
    names
}

/// The `espeak` adapter: speech through espeak-ng with each language's voice (`voice` for a
/// `SAY` in no language the map has), this rate and output.
pub fn espeak_adapter(
    voice: String,
    voices: BTreeMap<Language, String>,
    rate_wpm: u32,
    output: SpeechOutput,
    life: &Lifecycle,
) -> Worker {
    Worker::start(
        "espeak",
        Espeak {
            voice,
            voices,
            rate_wpm,
            output,
        },
        life,
    )
}

struct Espeak {
    voice: String,
    voices: BTreeMap<Language, String>,
    rate_wpm: u32,
    output: SpeechOutput,
}

impl Espeak {
    /// The voice of the language the `SAY` was resolved in.
    fn voice_for(&self, command: &Command) -> &str {
        let language = command.args.say_language();
        (language.and_then(|l| self.voices.get(l))).map_or(&self.voice, String::as_str)
    }

    async fn speak(&self, command: &Command) -> Result<(), String> {
        let text = command.arg.as_deref().unwrap_or_default();
        let mut process = Process::new("espeak-ng");
        process
            .args([
                "--stdin",
                "-v",
                self.voice_for(command),
                "-s",
                &self.rate_wpm.to_string(),
            ])
            .stdin(Stdio::piped())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            // Cancelling the command drops this future, and with it the process.
            .kill_on_drop(true);
        let wav = match &self.output {
            SpeechOutput::Audio => None,
            SpeechOutput::Wav(dir) => {
                let path = dir.join(format!("{}.wav", command.id));
                process.arg("-w").arg(&path);
                Some(path)
            }
        };
        let mut child = process
            .spawn()
            .map_err(|e| format!("could not start espeak-ng: {e}"))?;
        if let Some(mut stdin) = child.stdin.take() {
            stdin
                .write_all(text.as_bytes())
                .await
                .map_err(|e| format!("espeak-ng: {e}"))?;
        }
        let out = child
            .wait_with_output()
            .await
            .map_err(|e| format!("espeak-ng: {e}"))?;
        let stderr = String::from_utf8_lossy(&out.stderr);
        if !out.status.success() {
            return Err(format!(
                "espeak-ng failed ({}): {}",
                out.status,
                first_line(&stderr)
            ));
        }
        if let Some(problem) = alarming(&stderr) {
            return Err(format!("espeak-ng could not speak: {problem}"));
        }
        if let Some(path) = wav {
            let seconds = wav_seconds(&path)?;
            tokio::time::sleep(Duration::from_secs_f64(seconds)).await;
        }
        Ok(())
    }
}

impl Task for Espeak {
    async fn run(&self, command: &Command) -> Outcome {
        match self.speak(command).await {
            Ok(()) => Outcome::Done,
            Err(reason) => Outcome::Failed(reason),
        }
    }
}

fn first_line(text: &str) -> &str {
    text.lines()
        .find(|l| !l.trim().is_empty())
        .unwrap_or("no message")
        .trim()
}

/// The first stderr line that means the speech did not reach its output.
fn alarming(stderr: &str) -> Option<&str> {
    const SIGNS: [&str; 6] = ["ALSA", "cannot", "Can't", "Failed", "error", "Error"];
    stderr
        .lines()
        .map(str::trim)
        .find(|l| SIGNS.iter().any(|s| l.contains(s)))
}

/// The audio duration of an espeak-ng WAV file; an error when it holds no audio.
fn wav_seconds(path: &std::path::Path) -> Result<f64, String> {
    let len = std::fs::metadata(path)
        .map_err(|e| format!("espeak-ng wrote no audio file {}: {e}", path.display()))?
        .len();
    if len <= WAV_HEADER {
        return Err(format!(
            "espeak-ng wrote an empty audio file {}",
            path.display()
        ));
    }
    Ok((len - WAV_HEADER) as f64 / WAV_BYTES_PER_SECOND)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn alsa_complaints_count_as_failure_even_with_exit_zero() {
        let stderr = "ALSA lib confmisc.c:855:(parse_card) cannot find card '0'\n";
        assert!(alarming(stderr).unwrap().contains("cannot find card"));
        assert_eq!(alarming(""), None);
        assert!(alarming("Can't write to: /nope/x.wav").is_some());
    }
}
