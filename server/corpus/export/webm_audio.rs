//! The Opus track of a recording (`media/audio-N.webm`, or the microphone in
//! `media/video-N.webm`) decoded to 16-bit PCM at 48 kHz, for the WAV copy (`wav.rs`).
//! Chromium's MediaRecorder writes a live WebM: a Segment and Clusters of unknown size, with
//! SimpleBlocks; `matroska-demuxer` reads those, and `opus-rs` (pure Rust, libopus's algorithms) decodes
//! the packets. The OpusHead in the track's CodecPrivate gives the channel count and the pre-skip
//! (the encoder's priming samples, dropped before sample 0). Each packet lands at its block's
//! timestamp: a gap in the timestamps (a dropped packet) becomes silence rather than pulling
//! later sound earlier.
//!
//! Only the acknowledged bytes are read (the caller cuts the file to its `.chunks` index). A
//! file whose tail is torn (cut mid-cluster) is decoded up to the last whole packet, and what
//! was left out is said in [`Decoded::left_out`].

use std::io::Cursor;

use matroska_demuxer::{Frame, MatroskaFile, TrackType};
use opus_rs::OpusDecoder;

/// Opus always decodes at 48 kHz.
pub const SAMPLE_RATE: u32 = 48_000;

/// A recording's Opus track, ready to be decoded.
pub struct OpusTrack<'a> {
    webm: MatroskaFile<Cursor<&'a [u8]>>,
    track: u64,
    head: OpusHead,
    /// Nanoseconds per timestamp tick.
    scale: u64,
}

/// What decoding went through with.
pub struct Decoded {
    /// Frames (samples per channel) handed on, after the pre-skip.
    pub frames: u64,
    /// Why the end of the file was left out (a torn tail, an undecodable packet), with where.
    pub left_out: Option<String>,
}

impl<'a> OpusTrack<'a> {
    /// Finds the Opus track of the WebM `bytes`; an error says why it cannot be decoded.
    pub fn open(bytes: &'a [u8]) -> Result<OpusTrack<'a>, String> {
        if bytes.is_empty() {
            return Err("it is empty: no chunk of the recording was ever acknowledged".to_owned());
        }
        let webm = MatroskaFile::open(Cursor::new(bytes))
            .map_err(|e| format!("it is not a WebM file that can be read ({e})"))?;
        let track = (webm.tracks().iter())
            .find(|t| t.track_type() == TrackType::Audio)
            .ok_or("it has no audio track")?;
        if track.codec_id() != "A_OPUS" {
            let codec = track.codec_id();
            return Err(format!("its audio is {codec}, not Opus (A_OPUS)"));
        }
        let number = track.track_number().get();
        let head = OpusHead::read(track.codec_private().unwrap_or_default())?;
        let scale = webm.info().timestamp_scale().get();
        Ok(OpusTrack {
            webm,
            track: number,
            head,
            scale,
        })
    }

    /// 1 (mono) or 2 (stereo).
    pub fn channels(&self) -> u16 {
        u16::from(self.head.channels)
    }

    /// Decodes the track, handing `sink` the interleaved samples in order. Only `sink`'s
    /// errors are errors: what cannot be read or decoded ends the sound, said in `left_out`.
    pub fn decode<E>(
        mut self,
        mut sink: impl FnMut(&[i16]) -> Result<(), E>,
    ) -> Result<Decoded, E> {
        let channels = usize::from(self.head.channels);
        let mut decoder = match OpusDecoder::new(SAMPLE_RATE as i32, channels) {
            Ok(decoder) => decoder,
            Err(e) => {
                let left_out = Some(format!("no Opus decoder for {channels} channels: {e}"));
                return Ok(Decoded {
                    frames: 0,
                    left_out,
                });
            }
        };
        let mut pcm = vec![0f32; MAX_FRAME * channels];
        let mut pcm16: Vec<i16> = Vec::with_capacity(MAX_FRAME * channels);
        // Frames decoded so far, the pre-skip included; and how much of it is still to drop.
        let mut have: u64 = 0;
        let mut skip = u64::from(self.head.pre_skip);
        let mut emit = |samples: &[i16], skip: &mut u64| -> Result<(), E> {
            let frames = (samples.len() / channels) as u64;
            let dropped = (*skip).min(frames);
            *skip -= dropped;
            sink(&samples[dropped as usize * channels..])
        };
        let mut frame = Frame::default();
        let mut left_out = None;
        let mut first_ns = None;
        loop {
            match self.webm.next_frame(&mut frame) {
                Ok(true) => {}
                Ok(false) => break,
                Err(e) => {
                    left_out = Some(format!(
                        "its end could not be read after {} ({e}) and was left out",
                        at(have)
                    ));
                    break;
                }
            }
            if frame.track != self.track {
                continue;
            }
            let ns = frame.timestamp.saturating_mul(self.scale);
            let first = *first_ns.get_or_insert(ns);
            // Where this packet belongs, in frames from the first packet.
            let due = (u128::from(ns.saturating_sub(first)) * u128::from(SAMPLE_RATE)
                / 1_000_000_000) as u64;
            // More than 10 ms missing: a packet was lost; keep the later sound at its time.
            if due > have + u64::from(SAMPLE_RATE / 100) {
                let silence = vec![0i16; (due - have) as usize * channels];
                emit(&silence, &mut skip)?;
                have = due;
            }
            match decoder.decode(&frame.data, MAX_FRAME, &mut pcm) {
                Ok(n) => {
                    pcm16.clear();
                    pcm16.extend(pcm[..n * channels].iter().map(|&x| to_i16(x)));
                    emit(&pcm16, &mut skip)?;
                    have += n as u64;
                }
                Err(e) => {
                    left_out = Some(format!(
                        "a packet at {} could not be decoded ({e}): it and what follows were \
                         left out",
                        at(have)
                    ));
                    break;
                }
            }
        }
        let frames = have.saturating_sub(u64::from(self.head.pre_skip));
        Ok(Decoded { frames, left_out })
    }
}

/// The longest Opus packet: 120 ms at 48 kHz, per channel.
const MAX_FRAME: usize = 5760;

/// A float sample as 16-bit PCM, rounded and clipped as libopus's `opus_decode` does.
fn to_i16(x: f32) -> i16 {
    (x * 32768.0).round().clamp(-32768.0, 32767.0) as i16
}

/// A place in the recording, for people: seconds from its start.
fn at(frames: u64) -> String {
    format!("{:.3} s", frames as f64 / f64::from(SAMPLE_RATE))
}

/// What the Opus identification header (RFC 7845, section 5.1) tells the decoder.
struct OpusHead {
    channels: u8,
    pre_skip: u16,
}

impl OpusHead {
    fn read(bytes: &[u8]) -> Result<OpusHead, String> {
        if bytes.len() < 19 || &bytes[..8] != b"OpusHead" {
            return Err("its Opus track has no OpusHead in its CodecPrivate".to_owned());
        }
        let channels = bytes[9];
        let mapping = bytes[18];
        if !(1..=2).contains(&channels) || mapping != 0 {
            return Err(format!(
                "its Opus track has {channels} channels in mapping family {mapping}: only mono \
                 and stereo (family 0) are decoded"
            ));
        }
        let pre_skip = u16::from_le_bytes([bytes[10], bytes[11]]);
        Ok(OpusHead { channels, pre_skip })
    }
}
