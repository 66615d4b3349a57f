//! Bundles from anywhere: a folder copied from a Mac (an AppleDouble `._name` beside every
//! file, `.DS_Store` in every folder), opened on Windows or left with editor backups checks as
//! its author sees it, with one note naming what was ignored (no warning: `--deny-warnings`
//! passes it); and an acts file disabled by renaming is told once, with the acts it holds.

use crate::common;

use std::fs;

use common::check::{check_all, places};
use common::mac_copy::as_copied_from_a_mac;
use docent_content::{Colour, Severity, render_diagnostics};

/// A 1×1 PNG: a real picture, whatever the check sniffs.
const PNG: &[u8] = b"\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x01\x00\x00\x00\x01\x08\x06\x00\x00\x00\x1f\x15\xc4\x89\x00\x00\x00\x0d\x49\x44\x41\x54\x78\xda\x63\x64\x60\xf8\x5f\x0f\x00\x02\x87\x01\x80\xeb\x47\xba\x92\x00\x00\x00\x00\x49\x45\x4e\x44\xae\x42\x60\x82";

/// The bundle every test starts from: two acts, a page, a style sheet, a picture.
fn clean_bundle() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("temp dir");
    let files: [(&str, &[u8]); 5] = [
        (
            "acts.yaml",
            b"- Label: WELCOME\n  Text: Hello!\n- Label: PHOTO\n  Cmds: [PROJECT photo.png]\n",
        ),
        ("docent.yaml", b"home: index.html\n"),
        (
            "pages/index.html",
            b"<!doctype html><meta charset=\"utf-8\"><link rel=\"stylesheet\" href=\"style.css\">\
              <button data-act=\"PHOTO\">Photo</button>",
        ),
        ("pages/style.css", b"body { color: #123; }\n"),
        ("media/photo.png", PNG),
    ];
    for (rel, bytes) in files {
        let path = dir.path().join(rel);
        fs::create_dir_all(path.parent().expect("parent")).expect("folders");
        fs::write(path, bytes).expect("write");
    }
    dir
}

#[test]
fn a_bundle_copied_from_a_mac_checks_clean_but_for_one_note_on_what_was_ignored() {
    let dir = clean_bundle();
    assert_eq!(places(&check_all(dir.path())), []);
    let forks = as_copied_from_a_mac(dir.path());
    // acts.yaml, docent.yaml, pages, media; index.html, style.css; photo.png.
    assert_eq!(forks, 7);

    let report = check_all(dir.path());
    // The forks of the folders themselves (`._pages`, `._media`) are at the top; the rest lie
    // beside the files in pages/ and media/. The note is at the first ignored file.
    assert_eq!(
        places(&report),
        [("ignored-files", ".DS_Store:1:1".to_owned())]
    );
    let note = &report.diagnostics[0];
    assert_eq!(note.severity, Severity::Note);
    assert!(
        note.message.contains("ignored 10 file(s)")
            && note.message.contains("7 Mac resource fork(s)")
            && note.message.contains("3 Mac Finder settings (`.DS_Store`)"),
        "{}",
        note.message
    );
    assert!(report.bundle.is_some(), "the bundle is served");
    // Read as a page, `._index.html` would have been refused as a UTF-16 page: it is not read.
    assert!(report.diagnostics.iter().all(|d| d.code != "file-encoding"));
    // Printed, the binary file shows its place, not its bytes.
    let printed = render_diagnostics(dir.path(), &report.diagnostics, Colour::Plain);
    assert!(
        printed.contains("note[ignored-files]")
            && printed.contains("at .DS_Store:1:1")
            && !printed.contains('\0'),
        "{printed}"
    );
}

#[test]
fn windows_files_and_editor_backups_are_ignored_and_never_suggested() {
    let dir = clean_bundle();
    for (rel, text) in [
        ("pages/Thumbs.db", "\u{1}thumbs"),
        ("media/desktop.ini", "[.ShellClassInfo]\n"),
        ("pages/index.html~", "<p>old</p>"),
        ("pages/style.css.bak", "body {}"),
        ("pages/.index.html.swp", "b0VIM 9.0"),
        (".#acts.yaml", "user@host.1234"),
        ("docent.yaml~", "home: index.html\n"),
        ("media/photo.png.bak", "old"),
    ] {
        fs::write(dir.path().join(rel), text).expect("write");
    }
    // A misspelt picture: the suggestion is the picture, never its backup.
    let acts = fs::read_to_string(dir.path().join("acts.yaml")).expect("acts");
    fs::write(
        dir.path().join("acts.yaml"),
        acts.replace("photo.png]", "photo.pgn]"),
    )
    .expect("acts");
    let report = check_all(dir.path());
    assert_eq!(
        places(&report),
        [
            ("ignored-files", ".#acts.yaml:1:1".to_owned()),
            ("missing-file", "acts.yaml:4:18".to_owned()),
        ]
    );
    let ignored = &report.diagnostics[0].message;
    assert!(
        ignored.contains("ignored 8 file(s)")
            && ignored.contains("1 Windows thumbnail cache(s)")
            && ignored.contains("1 Windows folder settings")
            && ignored.contains("6 editor backup(s)"),
        "{ignored}"
    );
    let missing = &report.diagnostics[1].message;
    assert!(
        missing.contains("Did you mean `photo.png`?") && !missing.contains(".bak"),
        "{missing}"
    );
}

#[test]
fn an_acts_file_disabled_by_renaming_is_told_once_with_the_acts_it_holds() {
    let dir = clean_bundle();
    // Renamed to switch the tour off: its acts vanish from the console.
    let tour = "- Label: TOUR_START\n  Text: Follow me!\n- Label: TOUR_END\n  Text: That was \
                the tour.\n- Label: WELCOME\n  Text: Hello!\n";
    fs::write(dir.path().join("tour.yaml.disabled"), tour).expect("tour");
    // An editor's backup of acts.yaml: every act in it is loaded, so nothing vanished.
    let acts = fs::read(dir.path().join("acts.yaml")).expect("acts");
    fs::write(dir.path().join("acts.yml~"), acts).expect("backup");
    let report = check_all(dir.path());
    assert_eq!(
        places(&report),
        [
            ("ignored-files", "acts.yml~:1:1".to_owned()),
            ("disabled-acts-file", "tour.yaml.disabled:1:1".to_owned()),
        ]
    );
    let disabled = &report.diagnostics[1];
    assert_eq!(disabled.severity, Severity::Warning);
    assert!(
        disabled
            .message
            .contains("`tour.yaml.disabled` holds 3 act(s)")
            && disabled
                .message
                .contains("2 of them are in no loaded acts file")
            && disabled
                .message
                .contains("not loaded: `TOUR_START`, `TOUR_END`.")
            && disabled
                .message
                .contains("Rename the file back to end in .yaml"),
        "{}",
        disabled.message
    );
    assert!(
        report.diagnostics[0].message.contains("1 editor backup(s)"),
        "{}",
        report.diagnostics[0].message
    );
    // A file with such a name but no acts (an archive, say) is none of Docent's business.
    fs::remove_file(dir.path().join("tour.yaml.disabled")).expect("remove");
    fs::remove_file(dir.path().join("acts.yml~")).expect("remove");
    fs::write(dir.path().join("tour.yaml.zip"), b"PK\x03\x04\0\0").expect("zip");
    assert_eq!(places(&check_all(dir.path())), []);
}
