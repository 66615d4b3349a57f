//! What to tell an author about a file nothing converts: the `ffmpeg` command (or the
//! program to export from) that makes it something Chromium shows.

use super::ShownBy;
use super::sniff::{self, Format, Kind};

/// How to convert `shown` (named from the bundle root) into something `by` shows, as a
/// command to run in the bundle folder.
pub(super) fn convert_advice(shown: &str, format: &Format, by: ShownBy) -> String {
    let picture = format.kind == Kind::Image;
    if format.name == sniff::MIDI.name {
        return " ffmpeg cannot turn MIDI notes into sound: export the music as MP3 or WAV \
                 from your music program, then convert it to WebM."
            .to_owned();
    }
    let (ext, options) = match (picture, format.name) {
        (true, "HEIC" | "JPEG 2000" | "JPEG XL") => ("jpg", " -q:v 2"),
        (true, _) => ("png", ""),
        (false, _) if format.kind == Kind::Audio && by == ShownBy::PagePlayer => {
            ("mp3", " -vn -c:a libmp3lame -q:a 2")
        }
        (false, _) if format.kind == Kind::Audio => ("webm", " -vn -c:a libopus"),
        (false, _) => ("webm", " -c:v libvpx-vp9 -b:v 0 -crf 32 -c:a libopus"),
    };
    let output = converted_name(shown, ext);
    let mut advice = format!(
        " Convert it with ffmpeg (https://ffmpeg.org), in a terminal opened in the bundle \
         folder:\n    ffmpeg -i \"{shown}\"{options} \"{output}\"\nthen use `{output}` instead."
    );
    if format.name == sniff::HEIC.name {
        advice.push_str(
            " ffmpeg reads HEIC photos from version 7.1 on; with an older one, open the photo \
             in the phone's or computer's Photos app (or Preview on a Mac) and export it as \
             JPEG.",
        );
    } else if format.name == sniff::PSD.name {
        advice.push_str(" Or export the picture as PNG from your drawing program.");
    }
    advice
}

/// `shown` with its ending replaced by `ext`; `-converted` is added when that would be the
/// same name (a HEIC photo named `.jpg`).
fn converted_name(shown: &str, ext: &str) -> String {
    let stem = match shown.rsplit_once('.') {
        Some((stem, old)) if !old.contains('/') => stem,
        _ => shown,
    };
    let candidate = format!("{stem}.{ext}");
    if candidate == shown {
        format!("{stem}-converted.{ext}")
    } else {
        candidate
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn converted_names_never_overwrite_the_original() {
        assert_eq!(converted_name("media/film.mov", "webm"), "media/film.webm");
        assert_eq!(
            converted_name("pages/img/photo.jpg", "jpg"),
            "pages/img/photo-converted.jpg"
        );
        assert_eq!(
            converted_name("media/a.b/film", "webm"),
            "media/a.b/film.webm"
        );
    }

    #[test]
    fn advice_is_a_command_to_copy() {
        let advice = convert_advice("media/film.mov", &sniff::QUICKTIME, ShownBy::Projector);
        assert!(
            advice.contains(
                "ffmpeg -i \"media/film.mov\" -c:v libvpx-vp9 -b:v 0 -crf 32 -c:a libopus \
                 \"media/film.webm\""
            ),
            "{advice}"
        );
        let advice = convert_advice("pages/a.heic", &sniff::HEIC, ShownBy::PageImage);
        assert!(advice.contains("ffmpeg -i \"pages/a.heic\" -q:v 2 \"pages/a.jpg\""));
        assert!(advice.contains("Preview"));
    }
}
