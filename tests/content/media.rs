//! Media judged by content: `PROJECT` files and the pictures and videos of pages that
//! Chromium cannot show are refused at the argument or attribute, with the `ffmpeg` command
//! that converts them; names that do not match the content are reported. Headers are built
//! byte-exact from the format specifications; the playable samples are the shipped ones.

use crate::common;

use common::check::{bundle, check, loaded, places, yaml};
use docent_content::Severity;

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

#[test]
fn a_quicktime_film_is_refused_with_the_command_that_converts_it() {
    let report = projecting(&[("film.mov", ftyp(b"qt  ", &[b"qt  "]))]);
    assert_eq!(
        places(&report),
        [("media-unplayable", "acts.yaml:3:15".to_owned())]
    );
    let d = &report.diagnostics[0];
    assert_eq!(d.severity, Severity::Error);
    assert!(
        d.message.contains(
            "ffmpeg -i \"media/film.mov\" -c:v libvpx-vp9 -b:v 0 -crf 32 -c:a libopus \
             \"media/film.webm\""
        ),
        "{}",
        d.message
    );
}

#[test]
fn unplayable_content_behind_a_playable_name_is_refused() {
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
    let found: Vec<(&str, u32, u32)> = report
        .diagnostics
        .iter()
        .map(|d| (d.code.as_str(), d.line, d.column))
        .collect();
    assert_eq!(
        found,
        [
            ("media-unplayable", 3, 15),
            ("media-unplayable", 4, 15),
            ("media-unplayable", 5, 15),
            ("media-unplayable", 6, 15),
            ("media-unplayable", 7, 15),
        ]
    );
    let heic = &report.diagnostics[0].message;
    assert!(
        heic.contains("HEIC picture although its name ends in .jpg"),
        "{heic}"
    );
    assert!(
        heic.contains("ffmpeg -i \"media/photo.jpg\" -q:v 2 \"media/photo-converted.jpg\""),
        "{heic}"
    );
    assert!(heic.contains("Preview"), "{heic}");
    assert!(report.diagnostics[1].message.contains("TIFF"));
    assert!(report.diagnostics[3].message.contains("MPEG-1/2"));
    assert!(report.diagnostics[4].message.contains("Ogg Theora"));
}

#[test]
fn formats_chromium_cannot_show_are_refused_whatever_their_name() {
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
    let codes: Vec<&str> = report.diagnostics.iter().map(|d| d.code.as_str()).collect();
    assert_eq!(codes, ["media-unplayable"; 7], "{:?}", report.diagnostics);
    assert!(
        report
            .diagnostics
            .iter()
            .all(|d| d.message.contains("ffmpeg -i"))
    );
}

#[test]
fn names_that_do_not_match_the_content_are_reported() {
    let png = shipped("poster-presenter/media/poster.png");
    let webm = shipped("paper-fig4/media/Exhibit/video.webm");
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
        ("video.webm", shipped("paper-fig4/media/Exhibit/video.webm")),
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
    assert_eq!(
        places(&report),
        [
            ("media-unplayable", "pages/start.html:2:11".to_owned()),
            ("media-unplayable", "pages/start.html:3:13".to_owned()),
            ("media-unplayable", "pages/start.html:4:32".to_owned()),
            ("media-unplayable", "pages/start.html:5:35".to_owned()),
        ]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("ffmpeg -i \"pages/images/scan.tif\" \"pages/images/scan.png\"")
    );
}

#[test]
fn the_papers_original_mpeg_video_is_refused() {
    // Fig. 4 of the paper projects `Exhibit/video.mpg`; the projector never showed it.
    let acts = yaml(&[
        "- Label: RUN_VIDEO_EXHIBIT",
        "  Cmds:",
        "    - PROJECT Exhibit/video.mpg",
    ]);
    let dir = bundle(&[
        ("acts.yaml", &acts),
        ("media/Exhibit/video.mpg", "placeholder"),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("media-unplayable", "acts.yaml:3:15".to_owned())]
    );
    assert!(report.bundle.is_none());
}
