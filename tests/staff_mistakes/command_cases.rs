//! Mistakes in commands and the files they name, and the bytes of the media files staff drop
//! into a bundle (headers built from the format specifications). Expectations as in
//! `acts_cases.rs`.

use super::Mistake;
use super::edits::Edit::{self, *};

const fn replace(file: &'static str, find: &'static str, with: &'static str) -> Edit {
    Replace { file, find, with }
}

const I: &str = "info.yaml";
const S: &str = "slideshow.yaml";

/// A QuickTime film straight from a phone (`ftyp` brand `qt  `).
pub const QUICKTIME: &[u8] = b"\0\0\0\x14ftypqt  \0\0\0\0qt  \0\0\0\x08free";
/// An iPhone photo (HEIC: `ftyp` brand `heic`, compatible `mif1`).
pub const HEIC: &[u8] = b"\0\0\0\x18ftypheic\0\0\0\0mif1heic\0\0\0\x08free";
/// A scanner's TIFF (little-endian header).
pub const TIFF: &[u8] = b"II*\0\x08\0\0\0\x01\0\0\x01\x03\0\x01\0\0\0\x10\0\0\0";
/// An MPEG-2 program stream, the old `.mpg` of a DVD.
pub const MPEG: &[u8] = b"\0\0\x01\xba\x44\0\x04\0\x04\x01\x01\x89\xc3\xf8\0\0\x01\xe0";

/// Commands and the files they name.
pub const COMMANDS: &[Mistake] = &[
    Mistake {
        name: "wrote the verb in lower case: `say`",
        edits: &[replace(
            I,
            "    - SAY Here we are.",
            "    - say Here we are.",
        )],
        expect: &[("unknown-verb", "info.yaml:67:7")],
    },
    Mistake {
        name: "DISPLAY_PAGE to a page that does not exist",
        edits: &[replace(
            I,
            "DISPLAY_PAGE floor-plan.html",
            "DISPLAY_PAGE floorplan.html",
        )],
        expect: &[("missing-file", "info.yaml:29:20")],
    },
    Mistake {
        name: "DISPLAY_PAGE with the page name in other upper and lower case",
        edits: &[replace(
            I,
            "DISPLAY_PAGE opening-hours.html",
            "DISPLAY_PAGE Opening-Hours.html",
        )],
        expect: &[("miscased-file", "info.yaml:16:20")],
    },
    Mistake {
        name: "DISPLAY_PAGE with a Windows backslash path",
        edits: &[replace(
            S,
            "DISPLAY_PAGE news/slide-1.html",
            "DISPLAY_PAGE news\\slide-1.html",
        )],
        expect: &[("path-outside-bundle", "slideshow.yaml:8:20")],
    },
    Mistake {
        name: "wrote `WAIT 20` without a unit",
        edits: &[replace(I, "    - WAIT 20s", "    - WAIT 20")],
        expect: &[("bad-argument", "info.yaml:78:12")],
    },
    Mistake {
        name: "swapped the waypoint to a point outside the library",
        edits: &[replace(
            I,
            "SET_WAYPOINT 18 4.5 90",
            "SET_WAYPOINT 18 45 90",
        )],
        expect: &[("waypoint-out-of-bounds", "info.yaml:64:20")],
    },
    Mistake {
        name: "PROJECT of the tour film straight from the phone (.mov)",
        edits: &[
            Write {
                file: "media/library-tour.mov",
                bytes: QUICKTIME,
            },
            replace(I, "PROJECT library-tour.webm", "PROJECT library-tour.mov"),
        ],
        expect: &[("media-converted", "info.yaml:77:15")],
    },
    Mistake {
        name: "PROJECT of an iPhone photo (.heic)",
        edits: &[
            Write {
                file: "media/IMG_2041.heic",
                bytes: HEIC,
            },
            replace(I, "PROJECT events-poster.png", "PROJECT IMG_2041.heic"),
        ],
        expect: &[("media-converted", "info.yaml:23:15")],
    },
    Mistake {
        name: "PROJECT of a scanned poster (.tiff)",
        edits: &[
            Write {
                file: "media/events-poster.tiff",
                bytes: TIFF,
            },
            replace(I, "PROJECT events-poster.png", "PROJECT events-poster.tiff"),
        ],
        expect: &[("media-converted", "info.yaml:23:15")],
    },
    Mistake {
        name: "PROJECT of the old DVD film (.mpg)",
        edits: &[
            Write {
                file: "media/library-tour.mpg",
                bytes: MPEG,
            },
            replace(I, "PROJECT library-tour.webm", "PROJECT library-tour.mpg"),
        ],
        expect: &[("media-converted", "info.yaml:77:15")],
    },
];
