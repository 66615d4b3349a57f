//! Media judged by content: `PROJECT` files and the pictures and videos of pages that
//! Chromium cannot show are planned for conversion (a note at the argument or attribute),
//! what nothing converts is refused with what to do, and names that do not match the content
//! are reported. Headers are built
//! byte-exact from the format specifications; the playable samples are the shipped ones.

use crate::common;

use common::check::{bundle, check, loaded, places, yaml};
use docent_content::{ConvertInto, ConvertWhy, Severity};

/// An ISO base media `ftyp` box: major brand, minor version 0, compatible brands.
fn ftyp(major: &[u8; 4], compatible: &[&[u8; 4]]) -> Vec<u8> {
    let size = u32::try_from(16 + 4 * compatible.len()).expect("small box");
    let mut bytes = size.to_be_bytes().to_vec();
    bytes.extend_from_slice(b"ftyp");
    bytes.extend_from_slice(major);
    bytes.extend_from_slice(&[0; 4]);
    for brand in compatible {
        bytes.extend_from_slice(*brand);
    }
    bytes.extend_from_slice(b"\0\0\0\x08free");
    bytes
}

fn shipped(rel: &str) -> Vec<u8> {
    let root = common::repo().join("dialogs");
    std::fs::read(root.join(rel)).expect("shipped sample")
}

/// A bundle projecting each file in turn (one `PROJECT` a line, from line 3), with the files.
fn projecting(files: &[(&str, Vec<u8>)]) -> docent_content::LoadReport {
    let mut lines = vec!["- Label: SHOW".to_owned(), "  Cmds:".to_owned()];
    lines.extend(
        files
            .iter()
            .map(|(name, _)| format!("    - PROJECT {name}")),
    );
    let lines: Vec<&str> = lines.iter().map(String::as_str).collect();
    let dir = bundle(&[("acts.yaml", &yaml(&lines))]);
    for (name, bytes) in files {
        std::fs::write(dir.path().join("media").join(name), bytes).expect("media file");
    }
    check(dir.path())
}

/// The `media-converted` notes of `report`, as (format converted, place).
fn notes(report: &docent_content::LoadReport) -> Vec<(&'static str, String)> {
    let noted: Vec<_> = (report.diagnostics.iter())
        .filter(|d| d.code.as_str() == "media-converted")
        .inspect(|d| assert_eq!(d.severity, NOTE, "{d}"))
        .map(|d| format!("{}:{}:{}", d.file, d.line, d.column))
        .collect();
    let planned: Vec<_> = (report.conversions.iter())
        .map(|c| {
            (
                c.format,
                format!("{}:{}:{}", c.pos.file, c.pos.line, c.pos.column),
            )
        })
        .collect();
    assert_eq!(
        planned.iter().map(|(_, at)| at.clone()).collect::<Vec<_>>(),
        noted,
        "one note for each planned conversion, at its first use"
    );
    planned
}

const NOTE: Severity = Severity::Note;

#[test]
fn a_quicktime_film_is_converted_when_served_and_the_check_says_so() {
    let report = projecting(&[("film.mov", ftyp(b"qt  ", &[b"qt  "]))]);
    assert_eq!(notes(&report), [("QuickTime", "acts.yaml:3:15".to_owned())]);
    let d = &report.diagnostics[0];
    assert!(
        d.message.contains("`media/film.mov` is a QuickTime video")
            && d.message.contains("Docent converts it once with ffmpeg")
            && d.message.contains("your file is not changed"),
        "{}",
        d.message
    );
    let planned = &report.conversions[0];
    assert_eq!(planned.shown, "media/film.mov");
    assert_eq!(planned.into, ConvertInto::Video);
    assert_eq!(planned.why, ConvertWhy::Format);
    let bundle = loaded(report);
    assert_eq!(
        bundle.conversions.len(),
        1,
        "the bundle runs, with its plan"
    );
}

#[test]
fn content_chromium_cannot_show_behind_a_playable_name_is_converted_by_its_content() {
    let report = projecting(&[
        ("photo.jpg", ftyp(b"heic", &[b"mif1", b"heic"])),
        ("scan.png", b"II*\0\x08\0\0\0".to_vec()),
        ("clip.mp4", ftyp(b"qt  ", &[b"qt  "])),
        ("old.webm", b"\0\0\x01\xba\x44\0\x04\0\x04\x01".to_vec()),
        (
            "talk.ogv",
            b"OggS\0\x02\0\0\0\0\0\0\0\0\x01\0\0\0\0\0\0\0\0\0\0\0\x01\x2a\x80theora".to_vec(),
        ),
    ]);
    let formats: Vec<&str> = notes(&report).into_iter().map(|(f, _)| f).collect();
    assert_eq!(
        formats,
        ["HEIC", "TIFF", "QuickTime", "MPEG-1/2", "Ogg Theora"]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("`media/photo.jpg` is a HEIC picture")
    );
    let into: Vec<ConvertInto> = report.conversions.iter().map(|c| c.into).collect();
    use ConvertInto::{Picture, Video};
    assert_eq!(into, [Picture, Picture, Video, Video, Video]);
}

#[test]
fn formats_chromium_cannot_show_are_converted_whatever_their_name() {
    let samples: [(&str, Vec<u8>); 7] = [
        ("a.avi", b"RIFF\x24\0\0\0AVI LIST".to_vec()),
        (
            "a.wmv",
            b"\x30\x26\xb2\x75\x8e\x66\xcf\x11\xa6\xd9\0\xaa\0\x62\xce\x6c".to_vec(),
        ),
        ("a.flv", b"FLV\x01\x05\0\0\0\x09".to_vec()),
        ("a.3gp", ftyp(b"3gp4", &[b"isom", b"3gp4"])),
        ("a.mpg", b"\0\0\x01\xba\x44\0\x04\0\x04\x01".to_vec()),
        (
            "a.ts",
            [
                &[0x47u8, 0x40, 0, 0x10][..],
                &[0; 184],
                &[0x47, 0x40, 0, 0x11],
            ]
            .concat(),
        ),
        ("a.tiff", b"MM\0*\0\0\0\x08".to_vec()),
    ];
    let report = projecting(&samples);
    let formats: Vec<&str> = notes(&report).into_iter().map(|(f, _)| f).collect();
    assert_eq!(
        formats,
        [
            "AVI",
            "Windows Media",
            "Flash video",
            "3GP",
            "MPEG-1/2",
            "MPEG-TS",
            "TIFF"
        ]
    );
    assert_eq!(report.diagnostics.len(), 7, "{:?}", report.diagnostics);
}

#[test]
fn what_nothing_can_convert_is_still_refused_with_what_to_do() {
    let report = projecting(&[("tune.mid", b"MThd\0\0\0\x06\0\x01".to_vec())]);
    assert_eq!(
        places(&report),
        [("media-unplayable", "acts.yaml:3:15".to_owned())]
    );
    assert_eq!(report.diagnostics[0].severity, Severity::Error);
    assert!(report.conversions.is_empty());
}

/// A PNG's signature and `IHDR` header, `width` x `height`: what picture sizes are read from.
fn png_header(width: u32, height: u32) -> Vec<u8> {
    let mut bytes = b"\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR".to_vec();
    bytes.extend_from_slice(&width.to_be_bytes());
    bytes.extend_from_slice(&height.to_be_bytes());
    bytes.extend_from_slice(&[8, 6, 0, 0, 0, 0, 0, 0, 0]);
    bytes
}

#[test]
fn pictures_far_larger_than_any_screen_are_scaled_and_phone_photos_are_not() {
    let report = projecting(&[
        ("scan.png", png_header(12000, 9000)),
        ("phone.png", png_header(4032, 3024)),
        ("tall.png", png_header(800, 8000)),
    ]);
    let planned = notes(&report);
    assert_eq!(
        planned,
        [
            ("PNG", "acts.yaml:3:15".to_owned()),
            ("PNG", "acts.yaml:5:15".to_owned())
        ]
    );
    assert_eq!(
        report.conversions[0].why,
        ConvertWhy::Oversized {
            width: 12000,
            height: 9000
        }
    );
    let message = &report.diagnostics[0].message;
    assert!(
        message.contains("12000 x 9000 pixels") && message.contains("432 MB"),
        "{message}"
    );
}

#[test]
fn names_that_do_not_match_the_content_are_reported() {
    let png = shipped("poster-presenter/media/poster.png");
    let webm = shipped("museum-tour/media/card-punch.webm");
    let report = projecting(&[
        ("poster.jpeg", png.clone()),
        ("video.png", webm.clone()),
        ("picture.webm", png),
        ("film.mp4", webm),
    ]);
    let found: Vec<(&str, Severity, u32)> = report
        .diagnostics
        .iter()
        .map(|d| (d.code.as_str(), d.severity, d.line))
        .collect();
    assert_eq!(
        found,
        [
            ("media-misnamed", Severity::Warning, 3),
            ("media-misnamed", Severity::Error, 4),
            ("media-misnamed", Severity::Error, 5),
            ("media-misnamed", Severity::Warning, 6),
        ]
    );
    assert!(report.diagnostics[0].message.contains("end in .png"));
}

#[test]
fn the_projector_only_shows_the_endings_it_knows() {
    let report = projecting(&[
        ("song.mp3", b"ID3\x04\0\0\0\0\0\0".to_vec()),
        ("photo.avif", ftyp(b"avif", &[b"mif1", b"avif"])),
    ]);
    assert_eq!(
        places(&report),
        [
            ("media-unplayable", "acts.yaml:3:15".to_owned()),
            ("media-unplayable", "acts.yaml:4:15".to_owned()),
        ]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("-vn -c:a libopus \"media/song.webm\"")
    );
    assert!(
        report.diagnostics[1]
            .message
            .contains("\"media/photo.png\"")
    );
}

#[test]
fn real_playable_samples_pass_and_unrecognised_content_is_a_warning() {
    let report = projecting(&[
        ("poster.png", shipped("poster-presenter/media/poster.png")),
        ("video.webm", shipped("museum-tour/media/card-punch.webm")),
        ("card.webm", shipped("museum-tour/media/card-punch.webm")),
        ("clip.mp4", ftyp(b"isom", &[b"isom", b"avc1", b"mp41"])),
        ("broken.webm", b"<html>404 Not Found</html>".to_vec()),
    ]);
    assert_eq!(
        places(&report),
        [("media-unrecognised", "acts.yaml:7:15".to_owned())]
    );
    assert_eq!(report.diagnostics[0].severity, Severity::Warning);
    loaded(report);
}

#[test]
fn pictures_and_videos_of_pages_are_judged_by_content_at_the_attribute() {
    let page = yaml(&[
        "<meta charset=utf-8>",
        "<img src=\"images/scan.tif\" alt=\"\"> <img src=\"images/ok.png\" alt=\"\">",
        "<video src=\"/media/film.mov\" poster=\"images/ok.png\"></video>",
        "<img srcset=\"images/ok.png 1x, images/photo.jpg 2x\" alt=\"\">",
        "<div style=\"background-image: url(images/scan.tif)\"></div>",
    ]);
    let dir = bundle(&[
        ("acts.yaml", "- Label: A\n  Text: Hi\n"),
        ("pages/start.html", &page),
    ]);
    let files: [(&str, Vec<u8>); 4] = [
        ("pages/images/scan.tif", b"II*\0\x08\0\0\0".to_vec()),
        (
            "pages/images/ok.png",
            shipped("poster-presenter/media/poster.png"),
        ),
        ("pages/images/photo.jpg", ftyp(b"heic", &[b"mif1", b"heic"])),
        ("media/film.mov", ftyp(b"qt  ", &[b"qt  "])),
    ];
    for (rel, bytes) in &files {
        std::fs::create_dir_all(dir.path().join(rel).parent().expect("parent")).expect("dir");
        std::fs::write(dir.path().join(rel), bytes).expect("file");
    }
    let report = check(dir.path());
    // `scan.tif` is shown twice: converted once, noted at its first use.
    let planned = notes(&report);
    assert_eq!(
        planned,
        [
            ("TIFF", "pages/start.html:2:11".to_owned()),
            ("QuickTime", "pages/start.html:3:13".to_owned()),
            ("HEIC", "pages/start.html:4:32".to_owned()),
        ]
    );
    assert_eq!(report.diagnostics.len(), 3, "{:?}", report.diagnostics);
}

#[test]
fn a_file_named_as_a_film_whose_content_is_unknown_is_never_handed_to_ffmpeg() {
    // An `.mpg` that holds text (a playlist, a failed download): ffmpeg would follow a
    // playlist to files outside the bundle, so only content the sniff knows is converted.
    let acts = yaml(&[
        "- Label: RUN_VIDEO_EXHIBIT",
        "  Cmds:",
        "    - PROJECT Exhibit/video.mpg",
    ]);
    let dir = bundle(&[
        ("acts.yaml", &acts),
        (
            "media/Exhibit/video.mpg",
            "#EXTM3U\n#EXTINF:10,\nfile:/etc/passwd\n",
        ),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("media-unrecognised", "acts.yaml:3:15".to_owned())]
    );
    assert!(report.conversions.is_empty());
    assert!(
        report.diagnostics[0]
            .message
            .contains("is named as an MPEG-1/2 video")
    );
}

#[test]
fn a_scripted_svg_shown_as_a_picture_is_told_once_and_a_plain_one_passes() {
    let scripted = b"<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\">\n<script>document.querySelector('svg').append(years())</script>\n</svg>\n".to_vec();
    let handler = b"<svg xmlns=\"http://www.w3.org/2000/svg\"\n     onload=\"draw(evt)\"><g id=\"chart\"/></svg>".to_vec();
    let plain =
        b"<svg xmlns=\"http://www.w3.org/2000/svg\"><text>based on the map</text></svg>".to_vec();
    let report = projecting(&[
        ("timeline.svg", scripted.clone()),
        ("chart.svg", handler),
        ("map.svg", plain),
        ("timeline.svg", scripted),
    ]);
    assert_eq!(
        places(&report),
        [
            ("svg-script", "acts.yaml:3:15".to_owned()),
            ("svg-script", "acts.yaml:4:15".to_owned()),
        ],
        "once per file, the plain drawing passes"
    );
    assert!(report.diagnostics[0].message.contains("`<script>`"));
    assert!(report.diagnostics[1].message.contains("`onload=`"));
    assert_eq!(report.diagnostics[0].severity, Severity::Warning);
}

#[test]
fn a_scripted_svg_shown_by_a_page_and_an_act_is_told_once_at_its_first_place() {
    // The pages and each acts file are read on different threads: the warning must not
    // depend on which came first.
    let svg = "<svg xmlns=\"http://www.w3.org/2000/svg\"><script>draw()</script></svg>";
    let page = "<!doctype html><title>t</title><img src=\"/media/timeline.svg\" alt=\"\">";
    for _ in 0..5 {
        let dir = bundle(&[
            (
                "acts.yaml",
                "- Label: A\n  Cmds:\n    - PROJECT timeline.svg\n",
            ),
            (
                "more.yaml",
                "- Label: B\n  Cmds:\n    - PROJECT timeline.svg\n",
            ),
            ("pages/start.html", page),
            ("media/timeline.svg", svg),
        ]);
        let report = check(dir.path());
        assert_eq!(
            places(&report),
            [("svg-script", "acts.yaml:3:15".to_owned())]
        );
    }
}
