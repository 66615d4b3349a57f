//! Media by content: what a `PROJECT` file or a picture or video of a page really is (see
//! [`sniff`]), whether the projector or a page can show it, and when not, whether Docent
//! converts it when served (see [`convert`]) or the author must (the `ffmpeg` command).
//!
//! Each file is read once (the first few KB), however many acts and pages use it.

mod advice;
pub mod convert;
mod exif;
pub(crate) mod sniff;
mod svg;

use std::cell::RefCell;
use std::collections::HashMap;
use std::io::Read;
use std::path::{Path, PathBuf};

use crate::DiagnosticCode;
use crate::args::{MediaKind, PROJECTOR_IMAGES, PROJECTOR_VIDEOS};
use crate::diagnostic::Diagnostic;
use crate::model::Pos;
use advice::convert_advice;
use convert::{Conversion, ConvertWhy};
use sniff::{Format, Kind, SNIFF_BYTES, Support, by_extension};

/// Where a file is shown, which decides what it must be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ShownBy {
    /// `PROJECT`: the projector picks a picture or a video element by the file's ending.
    Projector,
    /// A page's `<img>`, `srcset`, `poster` or CSS `url()`.
    PageImage,
    /// A page's `<video>` or `<audio>` source.
    PagePlayer,
}

/// The first bytes of each media file, sniffed once, and the conversions planned.
#[derive(Default)]
pub(crate) struct MediaSniffs {
    formats: RefCell<HashMap<PathBuf, Option<&'static Format>>>,
    planned: RefCell<Vec<Conversion>>,
    /// Problems told once per file (a scripted SVG), with their file: merged across workers.
    once: RefCell<Vec<(PathBuf, Diagnostic)>>,
    /// Photos already sized: once each, however many pages show them.
    looked_into: RefCell<std::collections::HashSet<PathBuf>>,
    /// The script each SVG looked into has, if any.
    scripts: RefCell<HashMap<PathBuf, Option<String>>>,
}

/// How much of a JPEG is read for its EXIF block (it comes first, within 64 KiB).
const EXIF_BYTES: u64 = 128 << 10;

impl MediaSniffs {
    /// The format of the file at `path` (a path the bundle gate returned), or `None` when
    /// its first bytes match no known format or it cannot be read.
    pub fn format_of(&self, path: &Path) -> Option<&'static Format> {
        if let Some(format) = self.formats.borrow().get(path) {
            return *format;
        }
        let mut head = Vec::with_capacity(SNIFF_BYTES);
        let read = std::fs::File::open(path)
            .and_then(|f| f.take(SNIFF_BYTES as u64).read_to_end(&mut head));
        let format = read.ok().and_then(|_| sniff::sniff(&head));
        self.formats.borrow_mut().insert(path.to_owned(), format);
        format
    }

    /// Reports at `pos` why the file `shown` (named from the bundle root, e.g.
    /// `media/film.mov`, found at `path`) cannot be shown where it is used, if it cannot, and
    /// plans its conversion when Docent can make it showable.
    pub fn check(
        &self,
        path: &Path,
        shown: &str,
        by: ShownBy,
        pos: &Pos,
        out: &mut Vec<Diagnostic>,
    ) {
        let ext = shown
            .rsplit_once('.')
            .map(|(_, ext)| ext.to_ascii_lowercase())
            .filter(|ext| !ext.contains('/'))
            .unwrap_or_default();
        let named = by_extension(&ext);
        let content = self.format_of(path);
        // The projector picks a picture or a video element by the name: a name it does not
        // know shows nothing, unless it names a format Docent converts (then the name says
        // which element).
        if by == ShownBy::Projector
            && MediaKind::of(shown).is_none()
            && !named.is_some_and(|n| n.support == Support::Converted)
        {
            let what = content.or(named);
            let advice = what.map_or(String::new(), |f| convert_advice(shown, f, by));
            let message = format!(
                "The projector shows pictures ending in .{} and plays videos ending in .{}; \
                 `{shown}` is none of these, so nothing would be shown.{advice}",
                PROJECTOR_IMAGES.join(", ."),
                PROJECTOR_VIDEOS.join(", .")
            );
            out.push(Diagnostic::error(
                DiagnosticCode::MediaUnplayable,
                pos,
                message,
            ));
            return;
        }
        match (content, named) {
            (Some(real), _) if real.support == Support::No => unplayable(shown, real, by, pos, out),
            (Some(real), _) if real.support == Support::Converted => {
                // Converted by content: a QuickTime film named `.mp4` is converted too, but a
                // picture where a film is expected would still never appear.
                if shown_as_wrong_kind(real, &ext, by) {
                    misnamed(shown, &ext, real, by, pos, out);
                } else {
                    self.plan(Conversion::of_format(path.to_owned(), shown, real, pos));
                }
            }
            (Some(real), _) if !real.extensions.contains(&ext.as_str()) => {
                misnamed(shown, &ext, real, by, pos, out);
            }
            (Some(real), _) if wrong_kind(real.kind, by) => {
                let message = format!(
                    "`{shown}` is {}, but it is used here as {}. Use a {} here, or show this \
                     file with the right element.",
                    described(real),
                    expected_kind(by),
                    expected_kind(by)
                );
                out.push(Diagnostic::error(
                    DiagnosticCode::MediaMisnamed,
                    pos,
                    message,
                ));
            }
            (Some(real), _) if real.name == sniff::SVG.name => {
                self.scripted_svg(path, shown, pos);
            }
            (Some(real), _) => self.plan_if_oversized(path, shown, real, pos),
            (None, Some(name)) if name.support == Support::No => {
                unplayable(shown, name, by, pos, out);
            }
            // Not recognised by its first bytes, whatever its name says: never handed to ffmpeg,
            // which would follow a playlist or a list of files to places outside the bundle.
            (None, Some(name)) => {
                let message = format!(
                    "`{shown}` is named as {}, but its content is not one: the file may be \
                     damaged, empty, or something else saved under this name. Open it on a \
                     computer to check, and save or export it again as {}.",
                    described(name),
                    name.name
                );
                out.push(Diagnostic::warning(
                    DiagnosticCode::MediaUnrecognised,
                    pos,
                    message,
                ));
            }
            (None, None) => {}
        }
    }

    /// Plans `conversion` unless its file is planned already (the first use is kept, and the
    /// page of this one added).
    fn plan(&self, conversion: Conversion) {
        let mut planned = self.planned.borrow_mut();
        match planned.iter_mut().find(|c| c.path == conversion.path) {
            Some(known) => known.used_again_at(&conversion.pos),
            None => planned.push(conversion),
        }
    }

    /// Plans scaling a picture Chromium shows but that is far larger than any screen.
    fn plan_if_oversized(&self, path: &Path, shown: &str, format: &Format, pos: &Pos) {
        // Animated GIFs and vector pictures are left alone; only photos and scans are scaled.
        if ![sniff::PNG.name, sniff::JPEG.name, sniff::WEBP.name].contains(&format.name) {
            return;
        }
        if !self.looked_into.borrow_mut().insert(path.to_owned()) {
            // Sized already: if it is to be scaled, this page shows it too.
            let mut planned = self.planned.borrow_mut();
            if let Some(known) = planned.iter_mut().find(|c| c.path == path) {
                known.used_again_at(pos);
            }
            return;
        }
        // A photo to be turned (EXIF) stays as it is: the scaled copy would lose the tag.
        if format.name == sniff::JPEG.name && self.turned(path) {
            return;
        }
        let Ok(size) = imagesize::size(path) else {
            return;
        };
        let (Ok(width), Ok(height)) = (u32::try_from(size.width), u32::try_from(size.height))
        else {
            return;
        };
        if convert::is_oversized(width, height) {
            self.plan(Conversion {
                why: ConvertWhy::Oversized { width, height },
                ..Conversion::of_format(path.to_owned(), shown, format, pos)
            });
        }
    }

    /// Whether the JPEG at `path` says to turn it (an EXIF orientation other than upright).
    fn turned(&self, path: &Path) -> bool {
        let mut head = Vec::new();
        let read =
            std::fs::File::open(path).and_then(|f| f.take(EXIF_BYTES).read_to_end(&mut head));
        read.is_ok() && exif::jpeg_orientation(&head).is_some_and(|o| o != 1)
    }

    /// What the checks found: the conversions planned, each file once, in the order first
    /// seen, and the problems told once per file.
    pub fn take_findings(&self) -> MediaFindings {
        MediaFindings {
            conversions: std::mem::take(&mut self.planned.borrow_mut()),
            once: std::mem::take(&mut self.once.borrow_mut()),
        }
    }
}

/// What the media checks of one reading thread found.
#[derive(Default)]
pub(crate) struct MediaFindings {
    conversions: Vec<Conversion>,
    once: Vec<(PathBuf, Diagnostic)>,
}

impl MediaFindings {
    /// The findings of every thread as one: a file planned or told by two threads once, at
    /// its first use in the bundle's order (never by which thread came first), with the pages
    /// of both. Returns the conversions and the problems to report.
    pub(crate) fn merge(all: Vec<MediaFindings>) -> (Vec<Conversion>, Vec<Diagnostic>) {
        let (mut conversions, mut once): (Vec<_>, Vec<_>) = (Vec::new(), Vec::new());
        for mut found in all {
            conversions.append(&mut found.conversions);
            once.append(&mut found.once);
        }
        conversions.sort_by(|a, b| (&a.pos, &a.path).cmp(&(&b.pos, &b.path)));
        let mut merged: Vec<Conversion> = Vec::with_capacity(conversions.len());
        for conversion in conversions {
            match merged.iter_mut().find(|c| c.path == conversion.path) {
                Some(first) => {
                    for page in conversion.pages {
                        if !first.pages.contains(&page) {
                            first.pages.push(page);
                        }
                    }
                }
                None => merged.push(conversion),
            }
        }
        let place = |d: &Diagnostic| (d.file.clone(), d.line, d.column);
        once.sort_by_key(|(path, d)| (place(d), path.clone()));
        let mut seen = std::collections::HashSet::new();
        let told = (once.into_iter())
            .filter(|(path, _)| seen.insert(path.clone()))
            .map(|(_, d)| d)
            .collect();
        (merged, told)
    }
}

/// A format neither Chromium nor the converter can show.
fn unplayable(shown: &str, format: &Format, by: ShownBy, pos: &Pos, out: &mut Vec<Diagnostic>) {
    let message = format!(
        "`{shown}` is {}, which Chromium on the kiosk and projector cannot show, and Docent \
         cannot convert.{}",
        described(format),
        convert_advice(shown, format, by)
    );
    out.push(Diagnostic::error(
        DiagnosticCode::MediaUnplayable,
        pos,
        message,
    ));
}

/// Whether a file Docent converts is used where its kind never appears (a photo as a film).
fn shown_as_wrong_kind(real: &Format, ext: &str, by: ShownBy) -> bool {
    match by {
        ShownBy::Projector => {
            let as_image = by_extension(ext)
                .map_or(PROJECTOR_IMAGES.contains(&ext), |f| f.kind == Kind::Image);
            as_image != (real.kind == Kind::Image)
        }
        _ => wrong_kind(real.kind, by),
    }
}

/// A playable file whose name says another format.
fn misnamed(
    shown: &str,
    ext: &str,
    real: &'static Format,
    by: ShownBy,
    pos: &Pos,
    out: &mut Vec<Diagnostic>,
) {
    let usual = real.extensions[0];
    let rename = format!("Rename it to end in .{usual} (and change the places that name it).");
    // The projector, and the page element, choose by the name: a video named as a picture
    // (or the other way round) is never shown.
    let named_kind = by_extension(ext).map(|f| f.kind);
    let breaks = match by {
        ShownBy::Projector => {
            let as_image = PROJECTOR_IMAGES.contains(&ext);
            as_image != (real.kind == Kind::Image)
        }
        _ => {
            wrong_kind(real.kind, by)
                || named_kind.is_some_and(|k| (k == Kind::Image) != (real.kind == Kind::Image))
        }
    };
    if breaks {
        let message = format!(
            "`{shown}` is {}, but its name ends in .{ext}, so it is shown as {} and never \
             appears. {rename}",
            described(real),
            expected_kind(by_kind_of_ext(ext, by)),
        );
        out.push(Diagnostic::error(
            DiagnosticCode::MediaMisnamed,
            pos,
            message,
        ));
    } else {
        let message = format!(
            "`{shown}` is {}, but its name ends in .{ext}. It shows, but the name misleads \
             people and programs. {rename}",
            described(real)
        );
        out.push(Diagnostic::warning(
            DiagnosticCode::MediaMisnamed,
            pos,
            message,
        ));
    }
}

fn by_kind_of_ext(ext: &str, by: ShownBy) -> ShownBy {
    match by {
        ShownBy::Projector if PROJECTOR_IMAGES.contains(&ext) => ShownBy::PageImage,
        ShownBy::Projector => ShownBy::PagePlayer,
        other => other,
    }
}

fn wrong_kind(kind: Kind, by: ShownBy) -> bool {
    match by {
        ShownBy::Projector => false,
        ShownBy::PageImage => kind != Kind::Image,
        ShownBy::PagePlayer => kind == Kind::Image,
    }
}

fn expected_kind(by: ShownBy) -> &'static str {
    match by {
        ShownBy::PageImage => "a picture",
        ShownBy::PagePlayer | ShownBy::Projector => "a video or sound",
    }
}

fn described(format: &Format) -> String {
    let what = match format.kind {
        Kind::Image => "picture",
        Kind::Video => "video",
        Kind::Audio => "sound file",
    };
    format!("{} {} {what}", convert::article(format.name), format.name)
}
