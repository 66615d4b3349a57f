//! A JPEG's EXIF orientation: cameras and phones store a portrait photo sideways and say how
//! to turn it. Chromium turns it; a scaled copy without the tag would not be, so such a photo
//! is not scaled (see `MediaSniffs::plan_if_oversized`).

/// The orientation tag (1 to 8; 1 is upright) of the JPEG starting with `head`, if it has one.
pub(super) fn jpeg_orientation(head: &[u8]) -> Option<u16> {
    let mut at = 2; // after the start-of-image marker
    while head.get(at) == Some(&0xff) {
        let marker = *head.get(at + 1)?;
        let length = usize::from(u16::from_be_bytes([*head.get(at + 2)?, *head.get(at + 3)?]));
        let data = head.get(at + 4..at + 2 + length)?;
        if marker == 0xe1 && data.starts_with(b"Exif\0\0") {
            return tiff_orientation(&data[6..]);
        }
        if marker == 0xda {
            return None; // the picture itself starts: no EXIF before it
        }
        at += 2 + length;
    }
    None
}

/// The orientation tag (0x0112) of the first IFD of a TIFF structure.
fn tiff_orientation(tiff: &[u8]) -> Option<u16> {
    let big = match tiff.get(..2)? {
        b"MM" => true,
        b"II" => false,
        _ => return None,
    };
    let u16_at = |i: usize| {
        let b = [*tiff.get(i)?, *tiff.get(i + 1)?];
        Some(if big {
            u16::from_be_bytes(b)
        } else {
            u16::from_le_bytes(b)
        })
    };
    let u32_at = |i: usize| {
        let b = [
            *tiff.get(i)?,
            *tiff.get(i + 1)?,
            *tiff.get(i + 2)?,
            *tiff.get(i + 3)?,
        ];
        Some(if big {
            u32::from_be_bytes(b)
        } else {
            u32::from_le_bytes(b)
        })
    };
    let ifd = usize::try_from(u32_at(4)?).ok()?;
    let entries = usize::from(u16_at(ifd)?);
    (0..entries)
        .map(|n| ifd + 2 + 12 * n)
        .find(|&entry| u16_at(entry) == Some(0x0112))
        .and_then(|entry| u16_at(entry + 8))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A JPEG head with an EXIF block whose first IFD holds the orientation `value`.
    fn jpeg_with_orientation(value: u16, big: bool) -> Vec<u8> {
        let word = |v: u16| {
            if big {
                v.to_be_bytes()
            } else {
                v.to_le_bytes()
            }
        };
        let long = |v: u32| {
            if big {
                v.to_be_bytes()
            } else {
                v.to_le_bytes()
            }
        };
        let mut tiff = if big { b"MM".to_vec() } else { b"II".to_vec() };
        tiff.extend(word(42));
        tiff.extend(long(8));
        tiff.extend(word(1)); // one entry
        tiff.extend(word(0x0112));
        tiff.extend(word(3)); // SHORT
        tiff.extend(long(1));
        tiff.extend(word(value));
        tiff.extend([0, 0]);
        tiff.extend(long(0));
        let mut data = b"Exif\0\0".to_vec();
        data.extend(tiff);
        let mut jpeg = vec![0xff, 0xd8, 0xff, 0xe0, 0, 4, 0, 0]; // an APP0 first
        jpeg.extend([0xff, 0xe1]);
        jpeg.extend(u16::try_from(data.len() + 2).expect("small").to_be_bytes());
        jpeg.extend(data);
        jpeg.extend([0xff, 0xda, 0, 2]);
        jpeg
    }

    #[test]
    fn the_orientation_is_read_in_either_byte_order_and_absent_is_none() {
        assert_eq!(jpeg_orientation(&jpeg_with_orientation(6, false)), Some(6));
        assert_eq!(jpeg_orientation(&jpeg_with_orientation(8, true)), Some(8));
        assert_eq!(jpeg_orientation(&[0xff, 0xd8, 0xff, 0xda, 0, 2]), None);
        assert_eq!(jpeg_orientation(b"\xff\xd8\xff\xe1\x00"), None, "cut short");
    }
}
