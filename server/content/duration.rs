//! Durations as people write them in content and settings: `2s`, `500ms`, `1.5s`, `2m`, `1h`.
//!
//! A unit is always required: a bare `2` could mean seconds or milliseconds, and guessing
//! wrong makes a robot wait a thousand times too long.

use std::time::Duration;

/// Parses `<number><unit>` with unit `ms`, `s`, `m` or `h`; the number may have a fraction.
///
/// Returns `None` for bare numbers, negative or non-finite values, exponents, spaces between
/// number and unit, and values too large for a [`Duration`].
pub fn parse_duration(s: &str) -> Option<Duration> {
    let s = s.trim();
    let split = s.find(|c: char| !(c.is_ascii_digit() || c == '.'))?;
    let (number, unit) = s.split_at(split);
    let seconds_per_unit = match unit {
        "ms" => 0.001,
        "s" => 1.0,
        "m" => 60.0,
        "h" => 3600.0,
        _ => return None,
    };
    // Only digits with at most one dot: `f64::from_str` alone would also take `inf`, `1e3`.
    if !number.chars().any(|c| c.is_ascii_digit()) || number.matches('.').count() > 1 {
        return None;
    }
    let value: f64 = number.parse().ok()?;
    Duration::try_from_secs_f64(value * seconds_per_unit).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accepts_the_documented_forms() {
        assert_eq!(parse_duration("2s"), Some(Duration::from_secs(2)));
        assert_eq!(parse_duration("500ms"), Some(Duration::from_millis(500)));
        assert_eq!(parse_duration("1.5s"), Some(Duration::from_millis(1500)));
        assert_eq!(parse_duration("2m"), Some(Duration::from_secs(120)));
        assert_eq!(parse_duration("1.5m"), Some(Duration::from_secs(90)));
        assert_eq!(parse_duration("1h"), Some(Duration::from_secs(3600)));
        assert_eq!(parse_duration("0s"), Some(Duration::ZERO));
        assert_eq!(parse_duration(" 3s "), Some(Duration::from_secs(3)));
        assert_eq!(parse_duration(".5s"), Some(Duration::from_millis(500)));
    }

    #[test]
    fn rejects_bare_numbers_and_malformed_values() {
        for bad in [
            "",
            "2",
            "1.5",
            "s",
            "ms",
            "abc",
            "2 s",
            "-1s",
            "1e3s",
            "infs",
            "nans",
            "1..2s",
            "2sec",
            "2S",
            "1.2.3s",
            "2s3",
            "99999999999999999999999h",
        ] {
            assert_eq!(parse_duration(bad), None, "{bad:?} should be rejected");
        }
    }
}
