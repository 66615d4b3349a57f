//! The WAV copies of a session's recordings and the EAF's links to them: a recording Chromium's
//! MediaRecorder made (`tests/fixtures/recordings/`, a live WebM of unknown sizes) and a tone
//! `ffmpeg` encodes here, each placed at its `start_us` on the session clock, read back with
//! Python's `wave`, Praat (parselmouth) and pympi-ling; compared with ffmpeg's own decoding; and
//! recordings torn (bytes beyond the index, a cut inside a block), damaged or missing, which
//! export with a warning naming the file.

use std::path::{Path, PathBuf};
use std::process::Command;

use docent::corpus::export::{ExportFormat, ExportWarning, export_session};
use docent::corpus::manifest::{MANIFEST_FORMAT, MediaFile, SessionManifest, SessionMark};
use serde_json::json;

use crate::common::repo;
use crate::corpus_export::read_back;

const NAME: &str = "2026-11-24T12-30-29Z";

/// A session of 4 s, with its log, and `media` in its manifest (the files put in place by the
/// caller).
fn session(media: Vec<MediaFile>) -> (tempfile::TempDir, PathBuf) {
    let corpus = tempfile::tempdir().unwrap();
    let dir = corpus.path().join("sessions").join(NAME);
    std::fs::create_dir_all(dir.join("media")).unwrap();
    let log = concat!(
        r#"{"v":4,"seq":6,"time":"2026-11-24T12:30:29.191Z","mono_us":2429575,"session_us":0,"type":"session.started","session":1,"source":"operator","client":4,"consent":"recorded","page":"index.html","projector":null}"#,
        "\n",
        r#"{"v":4,"seq":80,"time":"2026-11-24T12:30:33.191Z","mono_us":6429575,"session_us":4000000,"type":"session.ended","session":1,"source":"operator","reason":"marked"}"#,
        "\n",
    );
    std::fs::write(dir.join("events.jsonl"), log).unwrap();
    let manifest = SessionManifest {
        format: MANIFEST_FORMAT,
        session: NAME.to_owned(),
        number: 1,
        docent: "0.1.0".to_owned(),
        bundle: None,
        bundle_hash: None,
        started: SessionMark {
            seq: 6,
            time: "2026-11-24T12:30:29.191Z".to_owned(),
            mono_us: 2429575,
            source: "operator".to_owned(),
            reason: None,
        },
        ended: None,
        group: None,
        context: None,
        consent: "recorded".to_owned(),
        media,
    };
    manifest.write_to(&dir).unwrap();
    (corpus, dir)
}

fn media(file: &str, start_us: u64, recording: u64) -> MediaFile {
    MediaFile {
        file: file.to_owned(),
        track: "audio".to_owned(),
        mime: "audio/webm;codecs=opus".to_owned(),
        start_us,
        clock_error_us: 500,
        recording,
    }
}

/// The Chromium-made recording (3 acknowledged chunks) copied to `to`, with its index.
fn chromium_recording(to: &Path) {
    let fixture = repo().join("tests/fixtures/recordings/chromium-audio.webm");
    std::fs::copy(&fixture, to).unwrap();
    let index = |p: &Path| PathBuf::from(format!("{}.chunks", p.display()));
    std::fs::copy(index(&fixture), index(to)).unwrap();
}

/// `seconds` of a sine at `hz`, as ffmpeg's libopus writes it into WebM (known sizes, a
/// pre-skip of 312).
fn ffmpeg_tone(to: &Path, hz: u32, seconds: u32) {
    let status = Command::new("ffmpeg")
        .args(["-v", "error", "-y", "-f", "lavfi", "-i"])
        .arg(format!(
            "sine=frequency={hz}:duration={seconds}:sample_rate=48000"
        ))
        .args(["-c:a", "libopus", "-f", "webm"])
        .arg(to)
        .status()
        .expect("ffmpeg runs (scripts/install-test-deps.sh installs it)");
    assert!(status.success());
}

/// The WAV's samples of channel 0, its channel count and its rate.
fn wav(path: &Path) -> (Vec<i16>, u16, u32) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..4], b"RIFF");
    assert_eq!(&bytes[8..16], b"WAVEfmt ");
    let channels = u16::from_le_bytes([bytes[22], bytes[23]]);
    let rate = u32::from_le_bytes(bytes[24..28].try_into().unwrap());
    assert_eq!(&bytes[36..40], b"data");
    let data = u32::from_le_bytes(bytes[40..44].try_into().unwrap()) as usize;
    assert_eq!(
        data,
        bytes.len() - 44,
        "the data chunk's size is the file's rest"
    );
    let samples = (bytes[44..].chunks_exact(2 * usize::from(channels)))
        .map(|frame| i16::from_le_bytes([frame[0], frame[1]]))
        .collect();
    (samples, channels, rate)
}

/// What ffmpeg decodes from `webm`: mono samples at 48 kHz.
fn ffmpeg_decoded(webm: &Path) -> Vec<i16> {
    let output = Command::new("ffmpeg")
        .args(["-v", "quiet", "-i"])
        .arg(webm)
        .args(["-f", "s16le", "-ac", "1", "-ar", "48000", "-"])
        .output()
        .expect("ffmpeg runs");
    (output.stdout.chunks_exact(2))
        .map(|b| i16::from_le_bytes([b[0], b[1]]))
        .collect()
}

/// Exports EAF, TextGrid and CSV (what `read_back` reads) into `out`; the EAF's files and
/// warnings.
fn export(dir: &Path, out: &Path) -> (Vec<PathBuf>, Vec<ExportWarning>) {
    let eaf = export_session(dir, ExportFormat::Eaf, out).unwrap();
    for format in [ExportFormat::TextGrid, ExportFormat::Csv] {
        export_session(dir, format, out).unwrap();
    }
    // The session names no bundle: its vocabulary is the session's, said in every export.
    let warnings = (eaf.warnings.into_iter())
        .filter(|w| !matches!(w, ExportWarning::VocabularyFromSessionOnly(_)))
        .collect();
    (eaf.files, warnings)
}

#[test]
fn recordings_are_copied_to_wav_on_the_session_clock_and_linked_from_the_eaf() {
    let (_corpus, dir) = session(vec![
        media("media/audio-1.webm", 109_042, 1),
        media("media/audio-2.webm", 1_500_000, 2),
    ]);
    chromium_recording(&dir.join("media/audio-1.webm"));
    ffmpeg_tone(&dir.join("media/audio-2.webm"), 440, 2);
    let out = dir.join("exports");
    let (files, warnings) = export(&dir, &out);
    assert_eq!(warnings, []);
    let chromium = out.join(format!("{NAME}.audio-1.wav"));
    let tone = out.join(format!("{NAME}.audio-2.wav"));
    assert_eq!(
        files,
        [
            out.join(format!("{NAME}.eaf")),
            chromium.clone(),
            tone.clone()
        ]
    );

    // Chromium's recording: silence up to 109.042 ms (5233 frames), then what ffmpeg decodes
    // from the same file, sample for sample (within 1 of 32768).
    let (samples, channels, rate) = wav(&chromium);
    assert_eq!((channels, rate), (1, 48_000));
    let padding = 109_042 * 48 / 1000;
    assert!(samples[..padding].iter().all(|&s| s == 0));
    let reference = ffmpeg_decoded(&dir.join("media/audio-1.webm"));
    assert_eq!(
        samples.len() - padding,
        reference.len(),
        "3 s as ffmpeg decodes it"
    );
    let most = (samples[padding..].iter().zip(&reference))
        .map(|(a, b)| (i32::from(*a) - i32::from(*b)).abs())
        .max();
    assert!(
        most <= Some(1),
        "differs from ffmpeg's decoding by {most:?}"
    );

    // ffmpeg's tone: 2 s of 440 Hz after 1.5 s of silence (its pre-skip dropped).
    let (samples, channels, _) = wav(&tone);
    assert_eq!(channels, 1);
    let padding = 72_000;
    let frame = 960;
    assert!(
        samples.len().abs_diff(padding + 96_000) <= frame,
        "{}",
        samples.len()
    );
    assert!(samples[..padding].iter().all(|&s| s == 0));
    let tone_part = &samples[padding + frame..padding + 96_000 - frame];
    let crossings = (tone_part.windows(2))
        .filter(|w| (w[0] < 0) != (w[1] < 0))
        .count();
    let hz = crossings as f64 / 2.0 / (tone_part.len() as f64 / 48_000.0);
    assert!((hz - 440.0).abs() < 2.0, "{hz} Hz");
    assert!(
        tone_part.iter().any(|&s| s.unsigned_abs() > 3000),
        "audible"
    );

    let read = read_back(&out, NAME);
    assert_eq!(read["problems"], json!([]));
    let linked = |n: u32, frames: usize| {
        json!({"relative": format!("./{NAME}.audio-{n}.wav"), "mime": "audio/x-wav",
               "extracted_from": format!("../media/audio-{n}.webm"), "time_origin": null,
               "rate": 48000, "channels": 1, "width": 2, "frames": frames})
    };
    let tone_frames = samples.len();
    let chromium_frames = wav(&chromium).0.len();
    assert_eq!(
        read["eaf_media"],
        json!([linked(1, chromium_frames), linked(2, tone_frames)])
    );
}

#[test]
fn a_torn_recording_is_copied_up_to_what_is_whole_and_the_rest_is_named() {
    let (_corpus, dir) = session(vec![media("media/audio-1.webm", 0, 1)]);
    let webm = dir.join("media/audio-1.webm");
    chromium_recording(&webm);
    // A crash after the second chunk was acknowledged: the third's bytes are on disk, never
    // indexed; the second ends inside a cluster (of unknown size), after a whole block.
    std::fs::write(
        PathBuf::from(format!("{}.chunks", webm.display())),
        "0 8354\n1 24865\n2 4",
    )
    .unwrap();
    let out = dir.join("exports");
    let (files, warnings) = export(&dir, &out);
    assert_eq!(files.len(), 2, "the EAF and the WAV copy");
    let [ExportWarning::MediaPartlyCopied { file, problem }] = &warnings[..] else {
        panic!("{warnings:?}");
    };
    assert_eq!(file, "media/audio-1.webm");
    assert!(
        problem.starts_with(
            "16497 bytes beyond its last acknowledged chunk (never acknowledged to the kiosk: \
             a crash cut the upload) were left out"
        ),
        "{problem}"
    );
    // What the first two chunks hold, as ffmpeg decodes the same bytes.
    let whole = dir.join("whole.webm");
    std::fs::write(&whole, &std::fs::read(&webm).unwrap()[..24865]).unwrap();
    let reference = ffmpeg_decoded(&whole);
    let (samples, _, _) = wav(&files[1]);
    assert!(
        samples.len().abs_diff(reference.len()) <= 960,
        "{} frames, ffmpeg {}",
        samples.len(),
        reference.len()
    );
    assert!(samples.len() < 3 * 48_000 - 960);
    assert_eq!(read_back(&out, NAME)["problems"], json!([]));
}

#[test]
fn a_recording_that_is_no_webm_or_missing_is_named_and_the_export_goes_on() {
    let (_corpus, dir) = session(vec![
        media("media/audio-1.webm", 0, 1),
        media("media/audio-2.webm", 0, 2),
        media("media/gone.webm", 0, 3),
        media("../outside.webm", 0, 4),
    ]);
    std::fs::write(dir.join("media/audio-1.webm"), b"").unwrap();
    std::fs::write(dir.join("media/audio-2.webm"), b"not a webm at all").unwrap();
    std::fs::write(dir.join("../outside.webm"), b"").unwrap();
    let out = dir.join("exports");
    let (files, warnings) = export(&dir, &out);
    assert_eq!(files, [out.join(format!("{NAME}.eaf"))]);
    let told: Vec<String> = warnings.iter().map(ToString::to_string).collect();
    assert_eq!(
        told,
        [
            "no WAV copy of the recording \"media/audio-1.webm\" was written, and the EAF does \
             not link it: it is empty: no chunk of the recording was ever acknowledged",
            "no WAV copy of the recording \"media/audio-2.webm\" was written, and the EAF does \
             not link it: it is not a WebM file that can be read (unexpected element found. \
             Expected: Ebml Found: Unknown)",
            "session.json lists the media file \"media/gone.webm\", which is not a file in the \
             session's folder (deleted, moved, or a path outside it): the MCAP's \
             `docent.media` names it all the same, but a player will not find it there, and \
             the EAF has no WAV copy of it",
            "session.json lists the media file \"../outside.webm\", which is not a file in the \
             session's folder (deleted, moved, or a path outside it): the MCAP's \
             `docent.media` names it all the same, but a player will not find it there, and \
             the EAF has no WAV copy of it",
        ]
    );
    let read = read_back(&out, NAME);
    assert_eq!(read["problems"], json!([]));
    assert_eq!(read["eaf_media"], json!([]));
}

#[test]
fn a_recording_cut_in_the_middle_of_a_packet_is_copied_up_to_the_last_whole_one() {
    let (_corpus, dir) = session(vec![media("media/audio-1.webm", 0, 1)]);
    let webm = dir.join("media/audio-1.webm");
    chromium_recording(&webm);
    // An index whose last end falls inside a SimpleBlock (as a damaged disk or a hand-cut
    // file can leave it).
    let index = PathBuf::from(format!("{}.chunks", webm.display()));
    std::fs::write(index, "0 8354\n1 20000\n").unwrap();
    let out = dir.join("exports");
    let (files, warnings) = export(&dir, &out);
    let told: Vec<String> = warnings.iter().map(ToString::to_string).collect();
    assert_eq!(
        told,
        [
            "the WAV copy of the recording \"media/audio-1.webm\" stops early: 21362 bytes beyond \
          its last acknowledged chunk (never acknowledged to the kiosk: a crash cut the upload) \
          were left out; its end could not be read after 1.620 s (element declared size of \
          962 bytes but only 949 bytes are available) and was left out"
        ]
    );
    let whole = dir.join("whole.webm");
    std::fs::write(&whole, &std::fs::read(&webm).unwrap()[..20000]).unwrap();
    let (samples, _, _) = wav(&files[1]);
    assert_eq!(
        samples.len(),
        ffmpeg_decoded(&whole).len(),
        "1.62 s, as ffmpeg reads it"
    );
}

#[test]
fn a_session_whose_visitors_withdrew_or_declined_exports_no_recording_and_says_so() {
    for consent in ["withdrawn", "declined"] {
        // A manifest that still lists the recording and a file still in the folder: what a
        // server that missed the withdrawal left (issue 24).
        let (_corpus, dir) = session(vec![media("media/audio-1.webm", 109_042, 1)]);
        chromium_recording(&dir.join("media/audio-1.webm"));
        let mut manifest = SessionManifest::read_from(&dir).unwrap();
        manifest.consent = consent.to_owned();
        manifest.write_to(&dir).unwrap();
        let out = dir.join("exports");
        let (files, warnings) = export(&dir, &out);
        assert_eq!(
            files,
            [out.join(format!("{NAME}.eaf"))],
            "{consent}: no WAV"
        );
        assert_eq!(
            warnings,
            [ExportWarning::MediaWithheld {
                consent: consent.to_owned(),
                files: 2,
            }],
            "{consent}"
        );
        let said = warnings[0].to_string();
        assert!(
            said.contains("no recording of this session is exported"),
            "{said}"
        );
        let eaf = std::fs::read_to_string(&files[0]).unwrap();
        assert!(
            !eaf.contains("MEDIA_DESCRIPTOR"),
            "{consent}: nothing linked"
        );
        let wavs = std::fs::read_dir(&out)
            .unwrap()
            .filter(|f| {
                f.as_ref()
                    .unwrap()
                    .path()
                    .extension()
                    .is_some_and(|e| e == "wav")
            })
            .count();
        assert_eq!(wavs, 0, "{consent}");
        let mcap = export_session(&dir, ExportFormat::Mcap, &out).unwrap();
        let bytes = std::fs::read(&mcap.files[0]).unwrap();
        let named = bytes
            .windows(b"audio-1.webm".len())
            .any(|w| w == b"audio-1.webm");
        assert!(!named, "{consent}: the MCAP names no recording");
    }
}
