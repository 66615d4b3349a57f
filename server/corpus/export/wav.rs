//! The WAV copy of each recording's sound, written beside the EAF for ELAN's players (which
//! cannot be relied on to play WebM): `NAME.audio-1.wav` for `media/audio-1.webm`,
//! `NAME.video-1.wav` for the microphone in `media/video-1.webm`. 16-bit PCM at 48 kHz,
//! mono or stereo as recorded, padded with silence from the session's start to the
//! recording's `start_us`, so that sample 0 is session time 0 like every export's time 0 and
//! the EAF needs no `TIME_ORIGIN`.
//!
//! Only the bytes the `.chunks` index acknowledges are read (`chunks.rs`); a torn
//! tail, an undecodable packet or a file that cannot be read at all becomes an
//! [`ExportWarning`] naming the file, and the export goes on.

use std::fs::File;
use std::io::{self, BufWriter, Seek, SeekFrom, Write};
use std::path::{Component, Path, PathBuf};

use percent_encoding::{AsciiSet, CONTROLS, utf8_percent_encode};

use super::eaf::MediaLink;
use super::webm_audio::{OpusTrack, SAMPLE_RATE};
use super::{ExportError, ExportWarning};
use crate::chunks::index_path;
use crate::manifest::MediaFile;

/// One WAV copy written.
pub struct WavCopy {
    /// The WAV file.
    pub wav: PathBuf,
    /// The recording it was made from, in the session's folder.
    pub webm: PathBuf,
}

/// Writes the WAV copy of every recording in `media` (the manifest's list) of the session in
/// `dir` into `out_dir`; what could not be copied is said in `warnings`.
pub fn write_copies(
    dir: &Path,
    name: &str,
    media: &[MediaFile],
    out_dir: &Path,
    warnings: &mut Vec<ExportWarning>,
) -> Result<Vec<WavCopy>, ExportError> {
    let mut copies = Vec::new();
    for entry in media {
        let webm = dir.join(&entry.file);
        let is_file = std::fs::symlink_metadata(&webm).is_ok_and(|m| m.is_file());
        if !inside(Path::new(&entry.file)) || !is_file {
            let file = entry.file.clone();
            warnings.push(ExportWarning::MediaNotInSession { file });
            continue;
        }
        let stem = Path::new(&entry.file)
            .file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
        let wav = out_dir.join(format!("{name}.{stem}.wav"));
        let problem = |problem: String| ExportWarning::MediaNotCopied {
            file: entry.file.clone(),
            problem,
        };
        let (bytes, unacknowledged) = match acknowledged(&webm) {
            Ok(read) => read,
            Err(e) => {
                warnings.push(problem(format!("it cannot be read: {e}")));
                continue;
            }
        };
        let track = match OpusTrack::open(&bytes) {
            Ok(track) => track,
            Err(why) => {
                warnings.push(problem(why));
                continue;
            }
        };
        let padding =
            u64::try_from(u128::from(entry.start_us) * u128::from(SAMPLE_RATE) / 1_000_000)
                .unwrap_or(u64::MAX);
        let mut left_out = write_wav(out_dir, &wav, track, padding)?;
        if unacknowledged > 0 {
            let beyond = format!(
                "{unacknowledged} bytes beyond its last acknowledged chunk (never acknowledged \
                 to the kiosk: a crash cut the upload) were left out"
            );
            left_out = Some(left_out.map_or(beyond.clone(), |why| format!("{beyond}; {why}")));
        }
        if let Some(problem) = left_out {
            let file = entry.file.clone();
            warnings.push(ExportWarning::MediaPartlyCopied { file, problem });
        }
        copies.push(WavCopy { wav, webm });
    }
    Ok(copies)
}

/// The recording's bytes that its `.chunks` index acknowledges (all of them when it has no
/// index: a file written whole), and how many more the file holds.
fn acknowledged(webm: &Path) -> io::Result<(Vec<u8>, usize)> {
    let mut bytes = std::fs::read(webm)?;
    let index = match std::fs::read_to_string(index_path(webm)) {
        Ok(text) => text,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok((bytes, 0)),
        Err(e) => return Err(e),
    };
    // The last whole line `SEQ END` is the truth; a torn last line was never acknowledged.
    let whole = index.rfind('\n').map_or("", |at| &index[..at]);
    let acked = (whole.lines().next_back())
        .and_then(|line| line.split(' ').nth(1))
        .and_then(|end| end.parse::<usize>().ok())
        .unwrap_or(0);
    let beyond = bytes.len().saturating_sub(acked);
    bytes.truncate(acked);
    Ok((bytes, beyond))
}

/// Whether `file` names a place inside the folder it is relative to.
fn inside(file: &Path) -> bool {
    (file.components()).all(|c| matches!(c, Component::Normal(_) | Component::CurDir))
}

/// Writes `track` to `wav` whole (beside it first, then renamed), after `padding` frames of
/// silence; returns what was left out of the sound.
fn write_wav(
    out_dir: &Path,
    wav: &Path,
    track: OpusTrack<'_>,
    padding: u64,
) -> Result<Option<String>, ExportError> {
    let write_error = |path: &Path| {
        let path = path.to_owned();
        move |source| ExportError::Write { path, source }
    };
    std::fs::create_dir_all(out_dir).map_err(write_error(out_dir))?;
    let mut partial = wav.as_os_str().to_owned();
    partial.push(".partial");
    let partial = PathBuf::from(partial);
    let written = (|| -> io::Result<Option<String>> {
        let channels = track.channels();
        let mut out = BufWriter::with_capacity(1 << 20, File::create(&partial)?);
        out.write_all(&header(channels, 0))?;
        let silence = vec![0u8; 1 << 16];
        let mut left = padding * u64::from(channels) * 2;
        while left > 0 {
            let n = left.min(silence.len() as u64) as usize;
            out.write_all(&silence[..n])?;
            left -= n as u64;
        }
        let mut bytes = Vec::new();
        let decoded = track.decode(|samples| {
            bytes.clear();
            bytes.extend(samples.iter().flat_map(|s| s.to_le_bytes()));
            out.write_all(&bytes)
        })?;
        let data = (padding + decoded.frames) * u64::from(channels) * 2;
        let data = u32::try_from(data).map_err(|_| {
            io::Error::other("the sound is longer than a WAV file can hold (4 GiB)")
        })?;
        let mut file = out.into_inner().map_err(io::IntoInnerError::into_error)?;
        file.seek(SeekFrom::Start(0))?;
        file.write_all(&header(channels, data))?;
        file.sync_data()?;
        std::fs::rename(&partial, wav)?;
        Ok(decoded.left_out)
    })();
    if written.is_err() {
        let _ = std::fs::remove_file(&partial);
    }
    written.map_err(write_error(wav))
}

/// The 44-byte header of a 16-bit PCM WAV at 48 kHz with `data` bytes of samples.
fn header(channels: u16, data: u32) -> [u8; 44] {
    let block = channels * 2;
    let mut h = [0u8; 44];
    h[0..4].copy_from_slice(b"RIFF");
    h[4..8].copy_from_slice(&data.saturating_add(36).to_le_bytes());
    h[8..12].copy_from_slice(b"WAVE");
    h[12..16].copy_from_slice(b"fmt ");
    h[16..20].copy_from_slice(&16u32.to_le_bytes());
    h[20..22].copy_from_slice(&1u16.to_le_bytes());
    h[22..24].copy_from_slice(&channels.to_le_bytes());
    h[24..28].copy_from_slice(&SAMPLE_RATE.to_le_bytes());
    h[28..32].copy_from_slice(&(SAMPLE_RATE * u32::from(block)).to_le_bytes());
    h[32..34].copy_from_slice(&block.to_le_bytes());
    h[34..36].copy_from_slice(&16u16.to_le_bytes());
    h[36..40].copy_from_slice(b"data");
    h[40..44].copy_from_slice(&data.to_le_bytes());
    h
}

/// The EAF's links to `copies`, written into `out_dir`.
pub fn links(copies: &[WavCopy], out_dir: &Path) -> Result<Vec<MediaLink>, ExportError> {
    if copies.is_empty() {
        // Nothing written: the folder may not be made yet.
        return Ok(Vec::new());
    }
    let absolute = |path: &Path| {
        std::fs::canonicalize(path).map_err(|source| ExportError::Write {
            path: path.to_owned(),
            source,
        })
    };
    let folder = absolute(out_dir)?;
    let mut links = Vec::new();
    for copy in copies {
        let wav = absolute(&copy.wav)?;
        let webm = absolute(&copy.webm)?;
        let name = wav.file_name().unwrap_or_default().to_string_lossy();
        links.push(MediaLink {
            url: file_url(&wav),
            relative: format!("./{name}"),
            extracted_from: relative(&folder, &webm),
        });
    }
    Ok(links)
}

/// Characters a `file://` URL's path cannot hold as they are.
const NOT_IN_PATH: &AsciiSet = &CONTROLS
    .add(b' ')
    .add(b'"')
    .add(b'#')
    .add(b'%')
    .add(b'<')
    .add(b'>')
    .add(b'?')
    .add(b'`')
    .add(b'{')
    .add(b'}');

/// `file:///…` of an absolute path.
fn file_url(path: &Path) -> String {
    let text = path.to_string_lossy();
    format!("file://{}", utf8_percent_encode(&text, NOT_IN_PATH))
}

/// `to` relative to the folder `from` (both absolute): `../media/audio-1.webm`.
fn relative(from: &Path, to: &Path) -> String {
    let from: Vec<_> = from.components().collect();
    let to: Vec<_> = to.components().collect();
    let common = from.iter().zip(&to).take_while(|(a, b)| a == b).count();
    let mut path = PathBuf::new();
    for _ in common..from.len() {
        path.push("..");
    }
    path.extend(&to[common..]);
    path.to_string_lossy().into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_recording_is_named_relative_to_the_eafs_folder_and_the_wav_by_its_url() {
        let from = Path::new("/corpus/sessions/S/exports");
        assert_eq!(
            relative(from, Path::new("/corpus/sessions/S/media/audio-1.webm")),
            "../media/audio-1.webm"
        );
        assert_eq!(
            relative(Path::new("/out"), Path::new("/corpus/S/media/a.webm")),
            "../corpus/S/media/a.webm"
        );
        assert_eq!(
            file_url(Path::new("/museum visits/#1/S.audio-1.wav")),
            "file:///museum%20visits/%231/S.audio-1.wav"
        );
    }

    #[test]
    fn the_header_is_a_16_bit_pcm_wav_at_48_khz() {
        let h = header(2, 1000);
        assert_eq!(&h[..4], b"RIFF");
        assert_eq!(u32::from_le_bytes(h[4..8].try_into().unwrap()), 1036);
        assert_eq!(u16::from_le_bytes([h[22], h[23]]), 2);
        assert_eq!(u32::from_le_bytes(h[24..28].try_into().unwrap()), 48_000);
        assert_eq!(u32::from_le_bytes(h[28..32].try_into().unwrap()), 192_000);
        assert_eq!(u16::from_le_bytes([h[32], h[33]]), 4);
        assert_eq!(u32::from_le_bytes(h[40..44].try_into().unwrap()), 1000);
    }
}
