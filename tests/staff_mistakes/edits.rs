//! The edits of the staff-mistake suite: a fresh copy of the library terminal, then the few
//! file operations that make one real-world mistake (replace a line, save a file in another
//! encoding, rename, drop in a phone photo). Every edit checks that it changed something, so a
//! fixture edited later cannot turn a case into a silent no-op.

use std::fs;
use std::path::Path;

/// The realistic bundle every case starts from.
pub const FIXTURE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/library-terminal"
);

/// One file operation, with paths relative to the bundle folder.
pub enum Edit {
    /// Replaces the only occurrence of `find` in `file` with `with`.
    Replace {
        file: &'static str,
        find: &'static str,
        with: &'static str,
    },
    /// Writes `bytes` to `file`, creating or overwriting it.
    Write {
        file: &'static str,
        bytes: &'static [u8],
    },
    /// Copies a file of the bundle to a new name (the original stays).
    Copy {
        from: &'static str,
        to: &'static str,
    },
    /// Renames a file of the bundle.
    Rename {
        from: &'static str,
        to: &'static str,
    },
    /// Saves `file` again as Windows-1252 ("ANSI" in Notepad).
    SaveAsWindows1252 { file: &'static str },
    /// Saves `file` again as UTF-16 little-endian with a byte-order mark ("Unicode" in Notepad).
    SaveAsUtf16 { file: &'static str },
    /// Appends a pasted document of `words` words after the only occurrence of `find`.
    PasteDocument {
        file: &'static str,
        find: &'static str,
        words: usize,
    },
    /// Puts a UTF-8 byte-order mark at the start of `file`.
    AddByteOrderMark { file: &'static str },
    /// Turns every line end of every text file into CRLF (Windows).
    CrlfEverywhere,
}

/// A fresh temporary copy of the fixture.
pub fn fresh_copy() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("temp dir");
    copy_folder(Path::new(FIXTURE), dir.path());
    dir
}

fn copy_folder(from: &Path, to: &Path) {
    fs::create_dir_all(to).expect("folder");
    for entry in fs::read_dir(from).expect("read fixture folder") {
        let entry = entry.expect("entry");
        let target = to.join(entry.file_name());
        if entry.file_type().expect("type").is_dir() {
            copy_folder(&entry.path(), &target);
        } else {
            fs::copy(entry.path(), target).expect("copy file");
        }
    }
}

/// Applies `edit` to the bundle at `root`.
pub fn apply(root: &Path, edit: &Edit) {
    match *edit {
        Edit::Replace { file, find, with } => {
            let text = read_text(root, file);
            assert_eq!(text.matches(find).count(), 1, "`{find}` once in {file}");
            fs::write(root.join(file), text.replacen(find, with, 1)).expect("write");
        }
        Edit::Write { file, bytes } => {
            let path = root.join(file);
            fs::create_dir_all(path.parent().expect("parent")).expect("folders");
            fs::write(path, bytes).expect("write");
        }
        Edit::Copy { from, to } => {
            fs::copy(root.join(from), root.join(to)).expect("copy");
        }
        Edit::Rename { from, to } => fs::rename(root.join(from), root.join(to)).expect("rename"),
        Edit::SaveAsWindows1252 { file } => {
            let text = read_text(root, file);
            assert!(!text.is_ascii(), "{file} has a letter Windows-1252 changes");
            fs::write(root.join(file), windows_1252(&text)).expect("write");
        }
        Edit::SaveAsUtf16 { file } => {
            let text = read_text(root, file);
            let mut bytes = vec![0xFF, 0xFE];
            bytes.extend(text.encode_utf16().flat_map(u16::to_le_bytes));
            fs::write(root.join(file), bytes).expect("write");
        }
        Edit::PasteDocument { file, find, words } => {
            let sentence = "Members may borrow up to twelve items at a time for three weeks, \
                            and renew them twice unless another reader has reserved them. ";
            let per_sentence = sentence.split_whitespace().count();
            let pasted = sentence.repeat(words.div_ceil(per_sentence));
            let text = read_text(root, file);
            assert_eq!(text.matches(find).count(), 1, "`{find}` once in {file}");
            let with = format!("{find} {}", pasted.trim_end());
            fs::write(root.join(file), text.replacen(find, &with, 1)).expect("write");
        }
        Edit::AddByteOrderMark { file } => {
            let text = read_text(root, file);
            fs::write(root.join(file), format!("\u{feff}{text}")).expect("write");
        }
        Edit::CrlfEverywhere => crlf_everywhere(root),
    }
}

fn read_text(root: &Path, file: &str) -> String {
    fs::read_to_string(root.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"))
}

fn crlf_everywhere(folder: &Path) {
    for entry in fs::read_dir(folder).expect("read folder") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            crlf_everywhere(&path);
            continue;
        }
        let is_text = path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| matches!(e, "yaml" | "html" | "css"));
        if is_text {
            let text = fs::read_to_string(&path).expect("text file");
            assert!(!text.contains('\r'), "{} is already CRLF", path.display());
            fs::write(&path, text.replace('\n', "\r\n")).expect("write");
        }
    }
}

/// `text` in Windows-1252; every character of the fixture's pages and acts has a byte there.
fn windows_1252(text: &str) -> Vec<u8> {
    text.chars()
        .map(|c| match c {
            '\0'..='\u{7f}' | '\u{a0}'..='\u{ff}' => u8::try_from(u32::from(c)).expect("latin-1"),
            '€' => 0x80,
            '‘' => 0x91,
            '’' => 0x92,
            '“' => 0x93,
            '”' => 0x94,
            '–' => 0x96,
            '—' => 0x97,
            other => panic!("`{other}` has no byte in Windows-1252"),
        })
        .collect()
}
