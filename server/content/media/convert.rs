//! The plan of media conversions: which files of a bundle Chromium cannot show as they are
//! (or are far larger than any screen) and what each becomes. The content check only plans;
//! the runtime's converter (the `docent` crate's `media` module) runs ffmpeg in the
//! background and serves the result under the original name, so `PROJECT Exhibit/video.mpg`
//! works as the author wrote it and the original file is never changed.

use std::path::PathBuf;

use crate::model::Pos;

use super::sniff::{Format, Kind};

/// A picture wider or taller than this is scaled down ...
pub const OVERSIZED_SIDE: u32 = 4096;
/// ... to fit in a square of this side: a 4K screen's width, the largest screen a kiosk or
/// projector has.
pub const SCALED_SIDE: u32 = 3840;

/// What a converted file becomes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ConvertInto {
    /// A picture (WebP), at most [`SCALED_SIDE`] on its longer side.
    Picture,
    /// A film Chromium plays (WebM, or MP4 when only the container was the problem).
    Video,
    /// Sound Chromium plays (WebM with Opus).
    Sound,
}

/// Why a file is converted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConvertWhy {
    /// Chromium cannot show or play its format (named in [`Conversion::format`]).
    Format,
    /// A picture Chromium shows, but so large that decoding it costs a kiosk PC hundreds of
    /// megabytes for nothing: it is scaled down.
    Oversized {
        /// Its width in pixels.
        width: u32,
        /// Its height in pixels.
        height: u32,
    },
}

/// One media file of the bundle to convert before it is shown.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Conversion {
    /// The file as found in the bundle (canonical), the key the runtime serves it by.
    pub path: PathBuf,
    /// Its name from the bundle root (`media/Exhibit/video.mpg`), for messages.
    pub shown: String,
    /// Its format as authors know it (`MPEG-1/2`, `HEIC`).
    pub format: &'static str,
    /// What it becomes.
    pub into: ConvertInto,
    /// Why.
    pub why: ConvertWhy,
    /// Where it is first shown (a `PROJECT` command or a page's attribute).
    pub pos: Pos,
    /// The pages that show it, relative to `pages/` (a kiosk showing one reloads it when the
    /// file is ready).
    pub pages: Vec<String>,
}

impl Conversion {
    /// Adds another use: its page, and its place if it comes first in the bundle's order.
    pub(crate) fn used_again_at(&mut self, pos: &Pos) {
        if *pos < self.pos {
            self.pos = pos.clone();
        }
        self.shown_at(pos);
    }

    /// Adds the page of `pos`, if `pos` is in a page, to [`pages`](Self::pages).
    pub(crate) fn shown_at(&mut self, pos: &Pos) {
        if let Some(page) = pos.file.strip_prefix("pages/")
            && !self.pages.iter().any(|p| p == page)
        {
            self.pages.push(page.to_owned());
        }
    }
}

impl Conversion {
    pub(crate) fn of_format(path: PathBuf, shown: &str, format: &Format, pos: &Pos) -> Self {
        let into = match format.kind {
            Kind::Image => ConvertInto::Picture,
            Kind::Video => ConvertInto::Video,
            Kind::Audio => ConvertInto::Sound,
        };
        let mut conversion = Conversion {
            path,
            shown: shown.to_owned(),
            format: format.name,
            into,
            why: ConvertWhy::Format,
            pos: pos.clone(),
            pages: Vec::new(),
        };
        conversion.shown_at(pos);
        conversion
    }

    /// In words, for `docent check`'s note: what will happen to the file and why.
    pub fn describe(&self) -> String {
        let shown = &self.shown;
        match self.why {
            ConvertWhy::Format => {
                let into = match self.into {
                    ConvertInto::Picture => "a WebP picture",
                    ConvertInto::Video => "a film Chromium plays (WebM, or MP4)",
                    ConvertInto::Sound => "WebM sound",
                };
                let kind = match self.into {
                    ConvertInto::Picture => "picture",
                    ConvertInto::Video => "video",
                    ConvertInto::Sound => "sound file",
                };
                format!(
                    "`{shown}` is {} {} {kind}, which Chromium on the kiosk and projector \
                     cannot show as it is. Docent converts it once with ffmpeg into {into} when the \
                     bundle is served, keeps the result in its media cache and shows that \
                     under the same name; your file is not changed. Nothing to do, unless you \
                     prefer to convert it yourself.",
                    article(self.format),
                    self.format,
                )
            }
            ConvertWhy::Oversized { width, height } => format!(
                "`{shown}` is {width} x {height} pixels, far more than any screen shows \
                 (decoding it takes a kiosk PC {} MB). Docent scales a copy down to fit \
                 {SCALED_SIDE} x {SCALED_SIDE} pixels when the bundle is served and shows \
                 that; your file is not changed. To save the conversion, export the picture \
                 at most {SCALED_SIDE} pixels wide and high.",
                decoded_megabytes(width, height)
            ),
        }
    }
}

/// Whether a picture of `width` x `height` is scaled down.
pub(crate) fn is_oversized(width: u32, height: u32) -> bool {
    width.max(height) > OVERSIZED_SIDE
}

/// Megabytes a browser holds for a decoded picture (4 bytes a pixel), rounded.
fn decoded_megabytes(width: u32, height: u32) -> u64 {
    (u64::from(width) * u64::from(height) * 4).div_ceil(1_000_000)
}

/// "an" before a vowel sound, for format names (`an MPEG-1/2 video`, `a HEIC picture`).
pub(super) fn article(name: &str) -> &'static str {
    let first = name.chars().next().unwrap_or('x').to_ascii_uppercase();
    // Letters read as a letter name starting with a vowel sound: A, E, F, H, I, L, M, N,
    // O, R, S, X (`an MPEG`, `an AVI`), except names read as a word.
    let spelled = name.chars().take(2).all(|c| c.is_ascii_uppercase());
    let vowel = if spelled {
        "AEFHILMNORSX".contains(first)
    } else {
        "AEIOU".contains(first)
    };
    if vowel && !name.starts_with("HEIC") {
        "an"
    } else {
        "a"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn articles_follow_how_the_names_are_read() {
        assert_eq!(article("MPEG-1/2"), "an");
        assert_eq!(article("AVI"), "an");
        assert_eq!(article("HEIC"), "a");
        assert_eq!(article("QuickTime"), "a");
        assert_eq!(article("TIFF"), "a");
        assert_eq!(article("Ogg Theora"), "an");
        assert_eq!(article("Windows Media"), "a");
    }

    #[test]
    fn only_pictures_far_larger_than_a_4k_screen_are_oversized() {
        assert!(!is_oversized(4032, 3024), "a phone photo stays as it is");
        assert!(!is_oversized(3840, 2160));
        assert!(is_oversized(12000, 9000));
        assert!(is_oversized(800, 8000));
        assert_eq!(decoded_megabytes(12000, 9000), 432);
    }
}
