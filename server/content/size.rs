//! Amounts of storage as people write them in settings: `4 GB`, `500MB`, `1.5 GiB`.
//!
//! A unit is always required (a bare `4` could be bytes or gigabytes). `KB`, `MB`, `GB` and
//! `TB` are powers of 1000 as disk makers and `df -H` count, `KiB` to `TiB` powers of 1024 as
//! `df -h` counts; the case of the unit does not matter.

/// Parses `<number> <unit>` (the space optional), the number with an optional fraction, into
/// bytes. `None` for bare numbers, unknown units, negative or non-finite values, and amounts
/// beyond `u64`.
pub fn parse_size(s: &str) -> Option<u64> {
    let s = s.trim();
    let split = s.find(|c: char| !(c.is_ascii_digit() || c == '.'))?;
    let (number, unit) = s.split_at(split);
    let factor: f64 = match unit.trim_start().to_ascii_lowercase().as_str() {
        "b" => 1.0,
        "kb" => 1e3,
        "mb" => 1e6,
        "gb" => 1e9,
        "tb" => 1e12,
        "kib" => 1024.0,
        "mib" => 1024f64.powi(2),
        "gib" => 1024f64.powi(3),
        "tib" => 1024f64.powi(4),
        _ => return None,
    };
    // Only digits with at most one dot: `f64::from_str` alone would also take `inf`, `1e3`.
    if !number.chars().any(|c| c.is_ascii_digit()) || number.matches('.').count() > 1 {
        return None;
    }
    let bytes = number.parse::<f64>().ok()? * factor;
    (bytes.is_finite() && bytes < u64::MAX as f64).then_some(bytes.round() as u64)
}

/// `bytes` as people read it: `4.0 GB`, `512.0 MB`, `900 B` (powers of 1000).
pub fn describe_size(bytes: u64) -> String {
    let units = [("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)];
    for (unit, size) in units {
        if bytes as f64 >= size {
            return format!("{:.1} {unit}", bytes as f64 / size);
        }
    }
    format!("{bytes} B")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accepts_the_documented_forms() {
        assert_eq!(parse_size("4 GB"), Some(4_000_000_000));
        assert_eq!(parse_size("500MB"), Some(500_000_000));
        assert_eq!(parse_size("1.5 GiB"), Some(1_610_612_736));
        assert_eq!(parse_size("2 mib"), Some(2 * 1024 * 1024));
        assert_eq!(parse_size("0 B"), Some(0));
    }

    #[test]
    fn refuses_what_could_be_misread() {
        for bad in [
            "4",
            "GB",
            "-1 GB",
            "1e3 MB",
            "inf GB",
            "4 gigabytes",
            "1.2.3 MB",
            "",
        ] {
            assert_eq!(parse_size(bad), None, "{bad:?}");
        }
        assert_eq!(parse_size("99999999999 TB"), None, "beyond u64");
    }

    #[test]
    fn sizes_are_described_in_the_largest_fitting_unit() {
        assert_eq!(describe_size(4_000_000_000), "4.0 GB");
        assert_eq!(describe_size(1_500_000), "1.5 MB");
        assert_eq!(describe_size(900), "900 B");
    }
}
