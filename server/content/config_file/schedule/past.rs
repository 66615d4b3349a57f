//! Special days already over: `special_days:` entries dated before today, most often last
//! year's holidays left in `docent.yaml`, which will never apply again (`past-special-day`).
//! Today is handed in by the loader (it reads the clock once), so tests pass a fixed date.

use crate::DiagnosticCode;
use crate::diagnostic::Diagnostic;
use crate::model::Located;
use crate::schedule::CalendarDate;

/// A `past-special-day` warning at each special day's date that is before `today`.
pub(crate) fn check_past_special_days(
    dates: &[Located<CalendarDate>],
    today: CalendarDate,
    out: &mut Vec<Diagnostic>,
) {
    for written in dates.iter().filter(|d| d.value < today) {
        let date = written.value;
        let next = next_same_day(date, today).map_or_else(String::new, |next| {
            format!(" If it comes back every year, write its next date, `date: {next}`;")
        });
        let message = format!(
            "{date} is already over (today is {today}), so these special hours will never \
             apply; it is probably last year's.{next} otherwise delete the entry."
        );
        out.push(Diagnostic::warning(
            DiagnosticCode::PastSpecialDay,
            &written.pos,
            message,
        ));
    }
}

/// The same month and day on or after `today` (none for a 29 February without a leap year
/// soon enough to name).
fn next_same_day(date: CalendarDate, today: CalendarDate) -> Option<CalendarDate> {
    let this_year = (date.month, date.day) >= (today.month, today.day);
    let year = if this_year {
        today.year
    } else {
        today.year + 1
    };
    CalendarDate::parse(&format!("{year:04}-{:02}-{:02}", date.month, date.day))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config_file::test_support::parse;

    fn day(text: &str) -> CalendarDate {
        CalendarDate::parse(text).expect("a date")
    }

    #[test]
    fn only_dates_before_today_are_warned_at_their_date() {
        let text = "schedule:\n  closed: closed.html\n  special_days:\n    \
                    - {date: 2025-12-25, hours: closed}\n    \
                    - {date: 2026-03-10, hours: closed}\n    \
                    - {date: 2026-12-24, hours: 09:00-13:00}\n";
        let file = parse(text);
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        let mut found = Vec::new();
        check_past_special_days(&file.special_dates, day("2026-03-10"), &mut found);
        let located: Vec<_> = (found.iter())
            .map(|d| (d.code.as_str(), &*d.file, d.line, d.column))
            .collect();
        // Today itself still counts: its hours apply until midnight.
        assert_eq!(located, [("past-special-day", "docent.yaml", 4, 14)]);
        let message = &found[0].message;
        assert!(message.contains("`date: 2026-12-25`"), "{message}");
        assert!(message.contains("today is 2026-03-10"), "{message}");
    }

    #[test]
    fn the_next_date_is_this_year_or_the_next() {
        let today = day("2026-06-01");
        assert_eq!(
            next_same_day(day("2025-12-25"), today),
            Some(day("2026-12-25"))
        );
        assert_eq!(
            next_same_day(day("2025-01-01"), today),
            Some(day("2027-01-01"))
        );
        assert_eq!(next_same_day(day("2024-02-29"), today), None);
    }
}
