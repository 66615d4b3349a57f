//! A bundle copied the way a Mac copies a folder onto a USB stick or a network drive: an
//! AppleDouble `._name` beside every file and folder, a `.DS_Store` in every folder. Shared by
//! the content tests (what the check says) and the command-line tests (`--deny-warnings`).

#![allow(dead_code)] // Each test binary uses a different part of the helpers.

use std::fs;
use std::path::Path;

/// What a Mac writes as `._name` on a disk that has no room for Finder information: an
/// AppleDouble header (magic 00 05 16 07, version 2, "Mac OS X" filler, two entries) and
/// the entries' bytes, mostly zeros.
pub fn apple_double() -> Vec<u8> {
    let mut bytes = vec![0x00, 0x05, 0x16, 0x07, 0x00, 0x02, 0x00, 0x00];
    bytes.extend_from_slice(b"Mac OS X        ");
    bytes.extend_from_slice(&[0x00, 0x02]);
    bytes.extend_from_slice(&[0, 0, 0, 9, 0, 0, 0, 0x32, 0, 0, 0x0e, 0xb0]);
    bytes.extend_from_slice(&[0, 0, 0, 2, 0, 0, 0x0e, 0xe2, 0, 0, 0x01, 0x1e]);
    bytes.resize(4096, 0);
    bytes[0x32..0x3a].copy_from_slice(b"TEXTR*ch");
    bytes
}

/// Adds to the bundle at `root` what a Mac's copy leaves: `._name` beside every file and
/// folder, `.DS_Store` in every folder. Returns how many `._` files it wrote.
pub fn as_copied_from_a_mac(root: &Path) -> usize {
    let mut written = 0;
    let mut folders = vec![root.to_path_buf()];
    while let Some(folder) = folders.pop() {
        let names: Vec<_> = fs::read_dir(&folder)
            .expect("list")
            .flatten()
            .map(|e| e.file_name().into_string().expect("name"))
            .collect();
        for name in names {
            let path = folder.join(&name);
            if path.is_dir() {
                folders.push(path);
            }
            fs::write(folder.join(format!("._{name}")), apple_double()).expect("fork");
            written += 1;
        }
        fs::write(folder.join(".DS_Store"), b"\0\0\0\x01Bud1\0\0\x10\0").expect("ds");
    }
    written
}
