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

/// Why `bytes` are not UTF-8, in words, and the byte offset to report it at: the start for
/// UTF-16, else the first byte that is not UTF-8. `None` when the bytes are UTF-8.
pub(crate) fn not_utf8(bytes: &[u8]) -> Option<(usize, String)> {
    let error = std::str::from_utf8(bytes).err()?;
    let utf16 = bytes.starts_with(&[0xFF, 0xFE])
        || bytes.starts_with(&[0xFE, 0xFF])
        || bytes.iter().take(200).filter(|&&b| b == 0).count() > 10;
    if utf16 {
        let message = format!(
            "This file is saved as UTF-16 (called \"Unicode\" in Notepad), but Docent reads \
             only UTF-8. {SAVE_AS_UTF8}"
        );
        return Some((0, message));
    }
    let at = error.valid_up_to();
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
    Some((at, message))
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
        let (at, message) = not_utf8(b"- Label: A\n  Text: \xd6ffnungszeiten\n").expect("1252");
        assert_eq!(at, 19);
        assert!(message.contains("probably `Ö`"), "{message}");
        let (_, message) = not_utf8(b"caf\x80").expect("1252");
        assert!(message.contains("`€`"), "{message}");
        let utf16: Vec<u8> = [0xFF, 0xFE]
            .into_iter()
            .chain("- Label: A".encode_utf16().flat_map(u16::to_le_bytes))
            .collect();
        let (at, message) = not_utf8(&utf16).expect("utf-16");
        assert_eq!(at, 0);
        assert!(message.contains("UTF-16"), "{message}");
    }
}
