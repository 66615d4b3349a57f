//! What a file becomes and the ffmpeg command that makes it. A film whose codecs Chromium
//! already plays, in a container it does not (H.264 in QuickTime or MPEG-TS, VP9 in
//! Matroska), is only re-packed, which takes a second; anything else is converted to WebM
//! (VP9 and Opus, which every Chromium plays) at ffmpeg's real-time speed setting. Pictures
//! become WebP, scaled to fit the largest screen.

use std::path::Path;
use std::process::Stdio;

use serde::Deserialize;
use tokio::process::Command;

use crate::content::{ConvertInto, SCALED_SIDE};

/// How a file is converted; its name is part of the cached file's name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Recipe {
    /// H.264 (with AAC or MP3 sound) re-packed into MP4.
    RepackMp4,
    /// VP8, VP9 or AV1 (with Opus or Vorbis sound) re-packed into WebM.
    RepackWebm,
    /// Converted to WebM with VP9 and Opus.
    Vp9,
    /// Sound converted to WebM with Opus.
    Opus,
    /// A picture converted to WebP, scaled to fit [`SCALED_SIDE`].
    Webp,
}

impl Recipe {
    /// The recipe's part of the cached file's name.
    pub(super) fn name(self) -> &'static str {
        match self {
            Recipe::RepackMp4 => "-mp4",
            Recipe::RepackWebm => "-webm",
            Recipe::Vp9 => "-vp9",
            Recipe::Opus => "-opus",
            Recipe::Webp => "-webp",
        }
    }

    /// The result's file ending (also ffmpeg's output format).
    pub(super) fn ext(self) -> &'static str {
        match self {
            Recipe::RepackMp4 => "mp4",
            Recipe::RepackWebm | Recipe::Vp9 | Recipe::Opus => "webm",
            Recipe::Webp => "webp",
        }
    }

    /// ffmpeg's arguments from `input` to `output`, with progress on standard output.
    pub fn ffmpeg_args(self, input: &Path, output: &Path) -> Vec<String> {
        let mut args: Vec<String> = ["-nostdin", "-hide_banner", "-loglevel", "error", "-y"]
            .map(String::from)
            .to_vec();
        args.push("-i".into());
        args.push(input.display().to_string());
        let fit = format!(
            "scale=w='min({SCALED_SIDE},iw)':h='min({SCALED_SIDE},ih)':\
             force_original_aspect_ratio=decrease"
        );
        let rest: &[&str] = match self {
            Recipe::RepackMp4 => &[
                "-map",
                "0:v:0",
                "-map",
                "0:a:0?",
                "-c",
                "copy",
                "-movflags",
                "+faststart",
            ],
            Recipe::RepackWebm => &["-map", "0:v:0", "-map", "0:a:0?", "-c", "copy"],
            Recipe::Vp9 => &[
                "-map",
                "0:v:0",
                "-map",
                "0:a:0?",
                "-c:v",
                "libvpx-vp9",
                "-deadline",
                "realtime",
                "-cpu-used",
                "8",
                "-row-mt",
                "1",
                "-b:v",
                "0",
                "-crf",
                "32",
                "-pix_fmt",
                "yuv420p",
                "-c:a",
                "libopus",
                "-b:a",
                "128k",
                "-ac",
                "2",
            ],
            Recipe::Opus => &["-vn", "-c:a", "libopus", "-b:a", "128k"],
            Recipe::Webp => &["-frames:v", "1", "-c:v", "libwebp", "-quality", "90"],
        };
        if self == Recipe::Webp || self == Recipe::Vp9 {
            args.push("-vf".into());
            args.push(fit);
        }
        args.extend(rest.iter().map(|s| (*s).to_owned()));
        args.extend(["-progress", "pipe:1", "-nostats", "-f", self.ext()].map(String::from));
        args.push(output.display().to_string());
        args
    }
}

/// What ffprobe says a file holds.
#[derive(Debug, Default, PartialEq)]
pub(super) struct Probe {
    /// The first video stream's codec (`h264`, `mpeg1video`), if any.
    pub video: Option<String>,
    /// The first sound stream's codec (`aac`, `mp2`), if any.
    pub audio: Option<String>,
    /// Seconds, when known: the progress is measured against it.
    pub duration: Option<f64>,
}

#[derive(Deserialize)]
struct ProbeJson {
    #[serde(default)]
    streams: Vec<StreamJson>,
    format: Option<FormatJson>,
}

#[derive(Deserialize)]
struct StreamJson {
    codec_type: Option<String>,
    codec_name: Option<String>,
}

#[derive(Deserialize)]
struct FormatJson {
    duration: Option<String>,
}

/// Asks ffprobe what `path` holds; `Err` with ffprobe's own words when it cannot read it.
pub(super) async fn probe(ffprobe: &Path, path: &Path) -> Result<Probe, String> {
    let output = Command::new(ffprobe)
        .args(["-v", "error", "-show_entries"])
        .arg("stream=codec_type,codec_name:format=duration")
        .args(["-of", "json"])
        .arg(path)
        .stdin(Stdio::null())
        .kill_on_drop(true)
        .output()
        .await
        .map_err(|e| format!("ffprobe could not be started: {e}"))?;
    let said = String::from_utf8_lossy(&output.stderr).trim().to_owned();
    if !output.status.success() {
        return Err(last_words(&said));
    }
    let json: ProbeJson = serde_json::from_slice(&output.stdout)
        .map_err(|e| format!("ffprobe's answer could not be read: {e}"))?;
    let first = |kind: &str| {
        (json.streams.iter())
            .find(|s| s.codec_type.as_deref() == Some(kind))
            .and_then(|s| s.codec_name.clone())
    };
    let probe = Probe {
        video: first("video"),
        audio: first("audio"),
        duration: (json.format.and_then(|f| f.duration)).and_then(|d| d.parse().ok()),
    };
    if probe.video.is_none() && probe.audio.is_none() {
        return Err(if said.is_empty() {
            "ffmpeg finds no picture, film or sound in it".to_owned()
        } else {
            last_words(&said)
        });
    }
    Ok(probe)
}

/// The recipe for a file that becomes `into`, given what it holds.
pub(super) fn choose(into: ConvertInto, probe: &Probe) -> Recipe {
    match into {
        ConvertInto::Picture => Recipe::Webp,
        ConvertInto::Sound => Recipe::Opus,
        ConvertInto::Video => {
            let audio = probe.audio.as_deref();
            match probe.video.as_deref() {
                Some("h264") if matches!(audio, None | Some("aac" | "mp3")) => Recipe::RepackMp4,
                Some("vp8" | "vp9" | "av1") if matches!(audio, None | Some("opus" | "vorbis")) => {
                    Recipe::RepackWebm
                }
                // A "video" file with sound only (a `.wma`, an `.mka`).
                None => Recipe::Opus,
                _ => Recipe::Vp9,
            }
        }
    }
}

/// The last lines of what a tool said, for a message (its first lines are often
/// configuration noise).
pub(super) fn last_words(said: &str) -> String {
    let lines: Vec<&str> = (said.lines())
        .map(|line| without_context(line.trim()))
        .filter(|l| !l.is_empty())
        .collect();
    let start = lines.len().saturating_sub(2);
    let words = lines[start..].join("; ");
    if words.is_empty() {
        "it stopped without saying why".to_owned()
    } else {
        words
    }
}

/// A line of ffmpeg's without what only a programmer reads: the `[mov,mp4 @ 0x55d2]` of
/// the part that spoke, and the file's path before `: `.
fn without_context(line: &str) -> &str {
    let line = match line
        .strip_prefix('[')
        .and_then(|rest| rest.split_once("] "))
    {
        Some((part, rest)) if part.contains(" @ 0x") => rest,
        _ => line,
    };
    match line.split_once(": ") {
        Some((path, rest)) if path.starts_with('/') => rest,
        _ => line,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn probe(video: Option<&str>, audio: Option<&str>) -> Probe {
        Probe {
            video: video.map(str::to_owned),
            audio: audio.map(str::to_owned),
            duration: None,
        }
    }

    #[test]
    fn playable_codecs_are_repacked_and_the_rest_converted() {
        let film = |v, a| choose(ConvertInto::Video, &probe(v, a));
        assert_eq!(film(Some("h264"), Some("aac")), Recipe::RepackMp4);
        assert_eq!(film(Some("h264"), None), Recipe::RepackMp4);
        assert_eq!(film(Some("h264"), Some("pcm_s16le")), Recipe::Vp9);
        assert_eq!(film(Some("vp9"), Some("opus")), Recipe::RepackWebm);
        assert_eq!(film(Some("mpeg1video"), Some("mp2")), Recipe::Vp9);
        assert_eq!(film(Some("hevc"), Some("aac")), Recipe::Vp9);
        assert_eq!(film(None, Some("wmav2")), Recipe::Opus);
        assert_eq!(
            choose(ConvertInto::Picture, &probe(Some("tiff"), None)),
            Recipe::Webp
        );
    }

    #[test]
    fn the_command_writes_the_recipes_format_with_progress() {
        let args =
            Recipe::Vp9.ffmpeg_args(Path::new("/b/media/v.mpg"), Path::new("/c/k.webm.partial"));
        let line = args.join(" ");
        assert!(line.starts_with("-nostdin -hide_banner -loglevel error -y -i /b/media/v.mpg"));
        assert!(line.contains("-c:v libvpx-vp9"), "{line}");
        assert!(line.ends_with("-progress pipe:1 -nostats -f webm /c/k.webm.partial"));
        let args = Recipe::Webp.ffmpeg_args(Path::new("a.tif"), Path::new("k.webp.partial"));
        assert!(args.join(" ").contains("min(3840,iw)"));
    }

    #[test]
    fn a_tools_last_lines_are_kept() {
        assert_eq!(last_words("a\n\nb\nc\nd\n"), "c; d");
        assert_eq!(
            last_words(
                "[mov,mp4,m4a @ 0x556ab39ba600] moov atom not found\n\
                 /tmp/b/media/bad.mov: Invalid data found when processing input\n"
            ),
            "moov atom not found; Invalid data found when processing input"
        );
        assert_eq!(last_words(" "), "it stopped without saying why");
    }
}
