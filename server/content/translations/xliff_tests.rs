//! The XLIFF reader's cost and limits, on generated tables (`bench/xliff_table.rs`).

use super::*;

#[path = "../../../bench/xliff_table.rs"]
mod generated;

fn en() -> Language {
    Language::parse("en").expect("tag")
}

/// Regression (issue 24): reading took time with the square of the file's size (each
/// element's line counted from the start again: 2 MB took 49 s, 4 MB did not finish). The
/// work counted (bytes and open elements looked at) now grows with the size: 4 MB costs 4
/// times 1 MB, and about one look per byte.
#[test]
fn reading_a_table_takes_work_in_proportion_to_its_size() {
    let read = |min_bytes: usize| {
        let (text, units) = generated::table(min_bytes);
        let mut work = 0;
        let table = read_counting(text.as_bytes(), &en(), None, &mut work).expect("read");
        assert_eq!(table.entries.len(), units);
        let last = table.entries.last().expect("entries");
        assert_eq!(last.key, format!("ROOM_{units}/Text/1"));
        assert_eq!(last.place, Place::Line(5 * units));
        (text.len() as f64, work as f64)
    };
    let (small, small_work) = read(1 << 20);
    let (big, big_work) = read(4 << 20);
    let growth = big_work / small_work;
    let size = big / small;
    assert!(
        growth < size * 1.05,
        "4 MB took {growth:.2} times the work of 1 MB, {size:.2} times its size"
    );
    assert!(
        big_work < 2.0 * big,
        "{big_work} looks for {big} bytes: more than one per byte"
    );
}

/// Regression (issue 24): deep nesting made every text look through all the open elements.
/// Deeper than [`MAX_DEPTH`] is refused at the line it goes too deep.
#[test]
fn elements_nested_too_deep_are_refused_at_their_line() {
    let error =
        read_xliff(generated::nested(200_000).as_bytes(), &en(), None).expect_err("too deep");
    // Five elements are open around the first `<g>`, on line 2; the k-th `<g>` is on line
    // k + 1, and the one that goes too deep is element MAX_DEPTH + 1.
    let too_deep = MAX_DEPTH + 1 - 5;
    let line = too_deep + 1;
    assert_eq!(
        error.to_string(),
        format!(
            "line {line}: elements are nested more than {MAX_DEPTH} deep, which no XLIFF file \
             of translations needs (Docent's nest 5 deep); export the table again and fill \
             that in"
        )
    );
    let within = read_xliff(generated::nested(too_deep - 1).as_bytes(), &en(), None);
    let within = within.expect("as deep as allowed");
    assert!(
        within.notes[0].contains("markup (<g>)"),
        "{:?}",
        within.notes
    );
}

/// Issue 26: a target a CAT tool marks unfinished keeps that `state` for the import to refuse,
/// in XLIFF 1.2 (on the target) and 2.0 (on the segment); `translated` and
/// `needs-review-translation` are finished.
#[test]
fn unfinished_states_are_kept_in_both_versions() {
    let v12 = r#"<xliff version="1.2"><file source-language="en" target-language="de"><body>
<trans-unit id="A/Text/1"><source>a</source><target state="new">x</target></trans-unit>
<trans-unit id="B/Text/1"><source>b</source><target state="needs-review-translation">y</target></trans-unit>
<trans-unit id="C/Text/1"><source>c</source><target state="translated">z</target></trans-unit>
</body></file></xliff>"#;
    let table = read_xliff(v12.as_bytes(), &en(), None).expect("read");
    let states: Vec<Option<&str>> = (table.entries.iter())
        .map(|e| e.unfinished.as_deref())
        .collect();
    assert_eq!(states, [Some("new"), None, None]);

    let v20 = r#"<xliff version="2.0" srcLang="en" trgLang="de"><file id="f">
<unit id="A/Text/1"><segment state="initial"><source>a</source><target>x</target></segment></unit>
<unit id="B/Text/1"><segment state="final"><source>b</source><target>y</target></segment></unit>
</file></xliff>"#;
    let table = read_xliff(v20.as_bytes(), &en(), None).expect("read");
    assert_eq!(table.language, "de");
    let read: Vec<(&str, Option<&str>, &str, Option<&str>)> = (table.entries.iter())
        .map(|e| {
            let source = e.source.as_deref();
            (
                e.key.as_str(),
                source,
                e.translation.as_str(),
                e.unfinished.as_deref(),
            )
        })
        .collect();
    assert_eq!(
        read,
        [
            ("A/Text/1", Some("a"), "x", Some("initial")),
            ("B/Text/1", Some("b"), "y", None)
        ]
    );
}
