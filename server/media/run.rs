//! Running the converters: ffmpeg with its progress read as it goes, and libheif's
//! `heif-convert` first for HEIC photos (Debian's ffmpeg reads HEIC stills only from version
//! 7.1 on). Each child is killed when its conversion is dropped (a newer save of the file, or
//! shutdown).

use std::path::{Path, PathBuf};
use std::process::Stdio;

use tokio::io::{AsyncBufReadExt, AsyncReadExt, BufReader};
use tokio::process::Command;

use super::recipe::last_words;

/// The converters found on this computer.
#[derive(Clone, Debug, Default)]
pub struct Tools {
    /// `ffmpeg`.
    pub ffmpeg: Option<PathBuf>,
    /// `ffprobe` (in the same Debian package).
    pub ffprobe: Option<PathBuf>,
    /// `heif-convert` (Debian's `libheif-examples`), for HEIC photos.
    pub heif_convert: Option<PathBuf>,
}

impl Tools {
    /// Looks the converters up on `PATH`.
    pub fn find() -> Tools {
        Tools {
            ffmpeg: on_path("ffmpeg"),
            ffprobe: on_path("ffprobe"),
            heif_convert: on_path("heif-convert"),
        }
    }

    /// `heif-info`, beside `heif-convert` in the same package: it reads a HEIC photo's
    /// header and fails when the file is not one.
    pub fn heif_info(&self) -> PathBuf {
        (self.heif_convert.as_deref())
            .and_then(Path::parent)
            .map_or_else(|| PathBuf::from("heif-info"), |dir| dir.join("heif-info"))
    }

    /// Why files of `format` cannot be converted here, in words with the fix; `None` when
    /// they can.
    pub fn missing_for(&self, format: &str) -> Option<String> {
        if self.ffmpeg.is_none() || self.ffprobe.is_none() {
            return Some(
                "ffmpeg is not installed on this computer, so Docent cannot convert it \
                 (install it: `sudo apt install ffmpeg`, then restart Docent)"
                    .to_owned(),
            );
        }
        if format == "HEIC" && self.heif_convert.is_none() {
            return Some(
                "HEIC photos are converted with libheif's heif-convert, which is not installed \
                 on this computer (install it: `sudo apt install libheif-examples`, then \
                 restart Docent)"
                    .to_owned(),
            );
        }
        None
    }
}

/// The program `name` in a folder of `PATH`, if there is one.
fn on_path(name: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|dir| dir.join(name))
        .find(|candidate| candidate.is_file())
}

/// Runs ffmpeg with `args` (which must ask for `-progress pipe:1`), telling `progress` the
/// fraction done when `duration` (seconds) is known. `Err` holds ffmpeg's last words.
pub(super) async fn ffmpeg(
    ffmpeg: &Path,
    args: &[String],
    duration: Option<f64>,
    mut progress: impl FnMut(f64),
) -> Result<(), String> {
    let mut child = Command::new(ffmpeg)
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .kill_on_drop(true)
        .spawn()
        .map_err(|e| format!("ffmpeg could not be started: {e}"))?;
    let (Some(stdout), Some(mut stderr)) = (child.stdout.take(), child.stderr.take()) else {
        return Err("ffmpeg's output could not be read".to_owned());
    };
    let read_progress = async {
        let mut lines = BufReader::new(stdout).lines();
        while let Ok(Some(line)) = lines.next_line().await {
            // `out_time_us` is the position written so far, in microseconds.
            let done = line
                .strip_prefix("out_time_us=")
                .and_then(|v| v.parse::<f64>().ok());
            if let (Some(done), Some(total)) = (done, duration.filter(|d| *d > 0.0)) {
                progress((done / 1e6 / total).clamp(0.0, 1.0));
            }
        }
    };
    let mut said = Vec::new();
    let read_said = stderr.read_to_end(&mut said);
    let ((), _) = tokio::join!(read_progress, read_said);
    let status = child
        .wait()
        .await
        .map_err(|e| format!("ffmpeg did not finish: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(last_words(&String::from_utf8_lossy(&said)))
    }
}

/// Decodes the HEIC photo `input` into the PNG `output` with heif-convert.
pub(super) async fn heif_to_png(tool: &Path, input: &Path, output: &Path) -> Result<(), String> {
    let done = Command::new(tool)
        .arg(input)
        .arg(output)
        .stdin(Stdio::null())
        .kill_on_drop(true)
        .output()
        .await
        .map_err(|e| format!("heif-convert could not be started: {e}"))?;
    if done.status.success() && output.is_file() {
        Ok(())
    } else {
        let said = String::from_utf8_lossy(&done.stderr).into_owned()
            + &String::from_utf8_lossy(&done.stdout);
        Err(format!(
            "heif-convert cannot read it: {}",
            last_words(&said)
        ))
    }
}
