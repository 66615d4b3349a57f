//! Files not saved as UTF-8, explained for the people who saved them. Windows editors save
//! "ANSI" (Windows-1252) or "Unicode" (UTF-16) unless told otherwise; Docent reads only UTF-8.
//! The message names the encoding the file was most likely saved in, the character that gave
//! it away, and how to save the file again as UTF-8.

/// The Windows-1252 characters of bytes 0x80 to 0x9F (undefined bytes as `None`); bytes 0xA0
/// to 0xFF are the Latin-1 characters of the same number.
const WINDOWS_1252_HIGH: [Option<char>; 32] = [
    Some('€'),
    None,
    Some('‚'),
    Some('ƒ'),
    Some('„'),
    Some('…'),
    Some('†'),
    Some('‡'),
    Some('ˆ'),
    Some('‰'),
    Some('Š'),
    Some('‹'),
    Some('Œ'),
    None,
    Some('Ž'),
    None,
    None,
    Some('‘'),
    Some('’'),
    Some('“'),
    Some('”'),
    Some('•'),
    Some('–'),
    Some('—'),
    Some('˜'),
    Some('™'),
    Some('š'),
    Some('›'),
    Some('œ'),
    None,
    Some('ž'),
    Some('Ÿ'),
];

/// How to save as UTF-8 in the editors museum staff use.
const SAVE_AS_UTF8: &str = "Open the file and save it again with the encoding UTF-8 (Notepad: \
                            File, Save as, Encoding UTF-8; LibreOffice: Save as, Edit filter \
                            settings, Unicode (UTF-8); VS Code: the encoding in the status bar, \
                            Save with encoding, UTF-8).";

/// Why a file's bytes are not UTF-8.
#[derive(Debug)]
pub(crate) struct NotUtf8 {
    /// The byte offset to report it at: the start for UTF-16, else the first byte that is not
    /// UTF-8.
    pub at: usize,
    /// UTF-16: no part of the file reads as text.
    pub utf16: bool,
    /// What happened and how to save the file as UTF-8, in words.
    pub message: String,
}

/// Why `bytes` are not UTF-8, or `None` when they are.
pub(crate) fn not_utf8(bytes: &[u8]) -> Option<NotUtf8> {
    // UTF-16 without a byte-order mark can be valid UTF-8 (NUL bytes and ASCII): look first.
    if is_utf16(bytes) {
        let message = format!(
            "This file is saved as UTF-16 (called \"Unicode\" in Notepad), but Docent reads \
             only UTF-8. {SAVE_AS_UTF8}"
        );
        return Some(NotUtf8 {
            at: 0,
            utf16: true,
            message,
        });
    }
    let at = std::str::from_utf8(bytes).err()?.valid_up_to();
    let character = bytes.get(at).and_then(|&b| windows_1252(b));
    let guess = match character {
        Some(c) => format!(
            " The character here is probably `{c}`, written in the older Windows encoding \
             (\"ANSI\", Windows-1252)."
        ),
        None => String::new(),
    };
    let message = format!(
        "This file is not saved as UTF-8, so Docent cannot read the character here.{guess} \
         {SAVE_AS_UTF8}"
    );
    Some(NotUtf8 {
        at,
        utf16: false,
        message,
    })
}

/// A UTF-16 byte-order mark, or NUL bytes every other byte as in UTF-16 text without one.
pub(crate) fn is_utf16(bytes: &[u8]) -> bool {
    if bytes.starts_with(b"\xff\xfe") || bytes.starts_with(b"\xfe\xff") {
        return true;
    }
    let head = &bytes[..bytes.len().min(64)];
    head.len() >= 4 && head.iter().filter(|&&b| b == 0).count() * 3 >= head.len()
}

/// The character byte `b` stands for in Windows-1252, for bytes outside ASCII.
fn windows_1252(b: u8) -> Option<char> {
    match b {
        0x80..=0x9F => WINDOWS_1252_HIGH[usize::from(b - 0x80)],
        0xA0..=0xFF => char::from_u32(u32::from(b)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_1252_and_utf16_are_told_apart_and_named() {
        assert!(not_utf8("Öffnungszeiten".as_bytes()).is_none());
        let found = not_utf8(b"- Label: A\n  Text: \xd6ffnungszeiten\n").expect("1252");
        assert_eq!((found.at, found.utf16), (19, false));
        assert!(found.message.contains("probably `Ö`"), "{}", found.message);
        let found = not_utf8(b"caf\x80").expect("1252");
        assert!(found.message.contains("`€`"), "{}", found.message);
        let utf16: Vec<u8> = [0xFF, 0xFE]
            .into_iter()
            .chain("- Label: A".encode_utf16().flat_map(u16::to_le_bytes))
            .collect();
        let found = not_utf8(&utf16).expect("utf-16");
        assert_eq!((found.at, found.utf16), (0, true));
        assert!(found.message.contains("UTF-16"), "{}", found.message);
        let no_mark: Vec<u8> = "- Label: A"
            .encode_utf16()
            .flat_map(u16::to_le_bytes)
            .collect();
        assert!(not_utf8(&no_mark).expect("utf-16").utf16);
    }
}
