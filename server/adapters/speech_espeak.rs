//! The `espeak` speech adapter: one `espeak-ng` process per utterance, one utterance at a time,
//! killed when speech is cancelled.
//!
//! espeak-ng exits 0 even when it could not play (no sound card) or write (bad `-w` path); the
//! only sign is its stderr (`../shared/notes/devices.md`). So a `SAY` is done only when the
//! process exited 0 *and* said nothing alarming on stderr; with WAV output, also only when the
//! file holds audio. Text goes in on stdin so it is never mistaken for an option.
//!
//! A process that dies (killed, crashed) fails the `SAY` with the signal named; one that
//! hangs is stopped after [`hang_limit`], a generous bound on how long the text can take to
//! say, so that no real utterance is ever cut as hung. Either way the process is reaped
//! before the failure is told, and the next `SAY` starts a fresh one.

use std::collections::BTreeMap;
use std::os::unix::process::ExitStatusExt;
use std::path::PathBuf;
use std::process::{ExitStatus, Stdio};
use std::time::Duration;

use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::process::{Child, Command as Process};

use crate::adapters::worker::{Task, Worker};
use crate::adapters::{Command, Outcome};
use crate::content::{Language, speaking_time};
use crate::lifecycle::Lifecycle;

/// espeak-ng's WAV format: 16-bit mono at 22,050 Hz after a 44-byte header.
const WAV_HEADER: u64 = 44;
const WAV_BYTES_PER_SECOND: f64 = 22_050.0 * 2.0;

/// What a hung espeak-ng is allowed on top of its text's stretched speaking time: starting
/// the process and opening the sound device take time that does not grow with the text.
pub const HANG_GRACE: Duration = Duration::from_secs(5);

/// How much longer than estimated espeak-ng may take. Measured with espeak-ng 1.51 at 80 to
/// 450 words a minute, real speech took up to 2.06 times `speaking_time` for acronyms and
/// pauses (`IBM, DEC, NASA, ...`; `Yes. No. Maybe.`), once digits are counted as below.
const HANG_FACTOR: u32 = 3;

/// How long one espeak-ng process may run before it counts as hung and is killed: three
/// times the text's speaking time at `rate_wpm` (`speaking_time`, the rule of `speaking_ms`,
/// with each digit counted as two more words, as espeak-ng reads numbers out: `8800` is
/// "eight thousand eight hundred", which `speaking_time` counts as one word), and
/// [`HANG_GRACE`].
pub fn hang_limit(text: &str, rate_wpm: u32) -> Duration {
    let digits = text.chars().filter(char::is_ascii_digit).count();
    let read_out = 2.0 * digits as f64 * 60.0 / f64::from(rate_wpm.max(1));
    let spoken = speaking_time(text, rate_wpm) + Duration::from_secs_f64(read_out);
    spoken * HANG_FACTOR + HANG_GRACE
}

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
        let limit = hang_limit(text, self.rate_wpm);
        let Ok(finished) = tokio::time::timeout(limit, finish(&mut child, text)).await else {
            // Killed and reaped here, not left to `kill_on_drop`: no zombie, and the next
            // `SAY` never finds this one still holding the sound device.
            let killed = child.kill().await;
            let note = killed.err().map_or(String::new(), |e| format!(" ({e})"));
            return Err(format!(
                "espeak-ng hung: it did not finish within {:.1} s (three times the text's \
                 speaking time and {} s) and was stopped{note}",
                limit.as_secs_f64(),
                HANG_GRACE.as_secs()
            ));
        };
        let (status, stderr) = finished?;
        if !status.success() {
            return Err(failure(status, &stderr));
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

/// Hands `text` to the running espeak-ng and waits for it to exit: its status and stderr.
async fn finish(child: &mut Child, text: &str) -> Result<(ExitStatus, String), String> {
    // Dropped after writing: the end of input tells espeak-ng the text is complete. A write
    // that fails (the process died first) is told after its exit status, which says more.
    let written = match child.stdin.take() {
        Some(mut stdin) => stdin.write_all(text.as_bytes()).await,
        None => Ok(()),
    };
    let mut stderr = child.stderr.take();
    let mut said = Vec::new();
    let read = async {
        match stderr.as_mut() {
            Some(pipe) => pipe.read_to_end(&mut said).await.map(drop),
            None => Ok(()),
        }
    };
    let (status, read) = tokio::join!(child.wait(), read);
    let status = status.map_err(|e| format!("espeak-ng: {e}"))?;
    // A pipe that cannot be read loses the message, not the outcome.
    if let Err(e) = read {
        tracing::debug!("espeak-ng's stderr could not be read: {e}");
    }
    let said = String::from_utf8_lossy(&said).into_owned();
    match written {
        Err(e) if status.success() => Err(format!("espeak-ng did not take the text: {e}")),
        _ => Ok((status, said)),
    }
}

/// Why espeak-ng ended badly, in words: the signal that ended it, or its exit code and first
/// line of complaint.
fn failure(status: ExitStatus, stderr: &str) -> String {
    match status.signal() {
        Some(signal) => format!(
            "espeak-ng was killed by signal {signal}{} before it finished speaking",
            signal_name(signal).map_or(String::new(), |n| format!(" ({n})"))
        ),
        None => format!("espeak-ng failed ({status}): {}", first_line(stderr)),
    }
}

/// The usual name of the signals that end a process from outside or by a crash.
fn signal_name(signal: i32) -> Option<&'static str> {
    Some(match signal {
        1 => "SIGHUP",
        2 => "SIGINT",
        6 => "SIGABRT",
        7 => "SIGBUS",
        9 => "SIGKILL",
        11 => "SIGSEGV",
        13 => "SIGPIPE",
        15 => "SIGTERM",
        _ => return None,
    })
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

    #[test]
    fn a_process_ended_by_a_signal_is_told_by_the_signal_s_name() {
        let killed = failure(ExitStatus::from_raw(9), "");
        assert_eq!(
            killed,
            "espeak-ng was killed by signal 9 (SIGKILL) before it finished speaking"
        );
        let exited = failure(ExitStatus::from_raw(1 << 8), "bad voice\n");
        assert_eq!(exited, "espeak-ng failed (exit status: 1): bad voice");
    }

    #[test]
    fn the_hang_limit_grows_with_the_text() {
        let short = hang_limit("Hello.", 160);
        let long = hang_limit(&"word ".repeat(160), 160);
        assert!(short > HANG_GRACE && short < HANG_GRACE + Duration::from_secs(2));
        // 160 words at 160 a minute: a minute to say, three allowed.
        assert!(long > Duration::from_secs(180) + HANG_GRACE);
        // One word, read out as six: "eight thousand eight hundred".
        assert!(hang_limit("8800", 160) > hang_limit("eight", 160) + Duration::from_secs(5));
    }
}
