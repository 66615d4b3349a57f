//! How `docent corpus` writes numbers for people: counts with their noun, sizes, times of
//! day, and lengths of time.

/// `1 session`, `3 sessions`.
pub(super) fn count(n: usize, thing: &str) -> String {
    if n == 1 {
        format!("1 {thing}")
    } else {
        format!("{n} {thing}s")
    }
}

/// `812 B`, `47.1 KiB`, `3.2 MiB`.
pub(super) fn size(bytes: u64) -> String {
    let mut value = bytes as f64;
    for unit in ["B", "KiB", "MiB", "GiB"] {
        if value < 1024.0 || unit == "GiB" {
            return if unit == "B" {
                format!("{bytes} B")
            } else {
                format!("{value:.1} {unit}")
            };
        }
        value /= 1024.0;
    }
    unreachable!("GiB returns")
}

/// `2026-11-24T10:15:02.629Z` as `2026-11-24 10:15:02`.
pub(super) fn minute_and_second(time: &str) -> String {
    match time.get(..19) {
        Some(head) if time.is_char_boundary(19) => head.replacen('T', " ", 1),
        _ => time.to_owned(),
    }
}

/// `18ms`, `4.2s`, `12m 04s`, `1h 02m 03s`.
pub(super) fn short_duration(us: u64) -> String {
    if us < 999_500 {
        // Rounded as `long_duration` rounds, so `list` and `show` agree.
        return format!("{}ms", (us + 500) / 1000);
    }
    let seconds = us / 1_000_000;
    match seconds {
        0 => format!("{:.1}s", us as f64 / 1e6),
        1..60 => format!("{:.1}s", us as f64 / 1e6),
        60..3600 => format!("{}m {:02}s", seconds / 60, seconds % 60),
        _ => format!(
            "{}h {:02}m {:02}s",
            seconds / 3600,
            seconds / 60 % 60,
            seconds % 60
        ),
    }
}

/// `4.183s`, `12m 04.183s`, `1h 02m 03.000s`: to the millisecond.
pub(super) fn long_duration(us: u64) -> String {
    let minutes = us / 60_000_000;
    let rest = (us % 60_000_000) as f64 / 1e6;
    match minutes {
        0 => format!("{rest:.3}s"),
        1..60 => format!("{minutes}m {rest:06.3}s"),
        _ => format!("{}h {:02}m {rest:06.3}s", minutes / 60, minutes % 60),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_sizes_and_times_read_the_way_a_person_writes_them() {
        assert_eq!(short_duration(18_400), "18ms");
        assert_eq!(short_duration(22_600), "23ms");
        assert_eq!(short_duration(999_700), "1.0s");
        assert_eq!(short_duration(4_200_000), "4.2s");
        assert_eq!(short_duration(724_183_000), "12m 04s");
        assert_eq!(short_duration(3_723_000_000), "1h 02m 03s");
        assert_eq!(long_duration(1_776), "0.002s");
        assert_eq!(long_duration(724_183_000), "12m 04.183s");
        assert_eq!(long_duration(3_723_000_000), "1h 02m 03.000s");
        assert_eq!(size(812), "812 B");
        assert_eq!(size(48_213), "47.1 KiB");
        assert_eq!(size(3_355_443), "3.2 MiB");
        assert_eq!(
            minute_and_second("2026-11-24T10:15:02.629Z"),
            "2026-11-24 10:15:02"
        );
        assert_eq!(minute_and_second("yesterday"), "yesterday");
        assert_eq!(
            (count(1, "file"), count(2, "file")),
            ("1 file".into(), "2 files".into())
        );
    }
}
