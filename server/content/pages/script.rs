//! What page scripts depend on: the `data-act-after` delay rule (the one the page script
//! applies) and `docent.trigger("LABEL")` literals in JavaScript.

use std::time::Duration;

/// The delay a `data-act-after` value asks for (`500ms`, `20s`, `1.5s`, `1m`: a number and
/// its unit, spaces allowed around them), or `None` when it is not one. The one rule: the
/// server serves pages with the delay added in milliseconds (`http::act_timers`), which is
/// all the page script reads.
pub fn act_delay(text: &str) -> Option<Duration> {
    let text = text.trim_matches(is_js_space);
    let digits = |s: &str| s.find(|c: char| !c.is_ascii_digit()).unwrap_or(s.len());
    let whole = digits(text);
    if whole == 0 {
        return None;
    }
    let mut number_end = whole;
    if let Some(fraction) = text[whole..].strip_prefix('.') {
        let len = digits(fraction);
        if len == 0 {
            return None;
        }
        number_end = whole + 1 + len;
    }
    let number: f64 = text[..number_end].parse().ok()?;
    let unit = text[number_end..].trim_start_matches(is_js_space);
    let millis = match unit {
        "ms" => number,
        "s" => number * 1000.0,
        "m" => number * 60_000.0,
        _ => return None,
    };
    Duration::try_from_secs_f64(millis / 1000.0).ok()
}

/// JavaScript's `\s`: the characters its regular expressions count as white space.
fn is_js_space(c: char) -> bool {
    matches!(
        c,
        '\t' | '\n' | '\u{b}' | '\u{c}' | '\r' | ' ' | '\u{a0}' | '\u{1680}' | '\u{2000}'
            ..='\u{200a}'
                | '\u{2028}'
                | '\u{2029}'
                | '\u{202f}'
                | '\u{205f}'
                | '\u{3000}'
                | '\u{feff}'
    )
}

/// Every `docent.trigger("LABEL")` (or `'LABEL'`, or a template literal without `${`) in
/// `js`, with the byte offset of the label. Comments and other strings are skipped, so a
/// commented-out call is not counted.
pub(crate) fn trigger_literals(js: &str) -> Vec<(String, usize)> {
    let bytes = js.as_bytes();
    let mut found = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'/' if bytes.get(i + 1) == Some(&b'/') => {
                i = js[i..].find('\n').map_or(bytes.len(), |n| i + n);
            }
            b'/' if bytes.get(i + 1) == Some(&b'*') => {
                i = js[i + 2..]
                    .find("*/")
                    .map_or(bytes.len(), |n| i + 2 + n + 2);
            }
            quote @ (b'"' | b'\'' | b'`') => i = string_end(bytes, i + 1, quote),
            c if c.is_ascii_alphabetic() || c == b'_' || c == b'$' => {
                let start = i;
                while i < bytes.len()
                    && (bytes[i].is_ascii_alphanumeric() || b"_$".contains(&bytes[i]))
                {
                    i += 1;
                }
                if &js[start..i] == "docent"
                    && let Some((label, at, end)) = trigger_call(js, i)
                {
                    found.push((label, at));
                    i = end;
                }
            }
            _ => i += 1,
        }
    }
    found
}

/// After `docent`: `.trigger(` and a string literal; the label, its offset and where the
/// literal ends.
fn trigger_call(js: &str, mut i: usize) -> Option<(String, usize, usize)> {
    let skip_space = |i: usize| i + (js[i..].len() - js[i..].trim_start().len());
    i = skip_space(i);
    i = skip_space(i + js[i..].strip_prefix('.').map(|_| 1)?);
    i = skip_space(i + js[i..].strip_prefix("trigger").map(|_| "trigger".len())?);
    i = skip_space(i + js[i..].strip_prefix('(').map(|_| 1)?);
    let quote = *js.as_bytes().get(i).filter(|q| b"\"'`".contains(q))?;
    let end = string_end(js.as_bytes(), i + 1, quote);
    let label = js.get(i + 1..end.saturating_sub(1))?;
    if label.contains('\\') || (quote == b'`' && label.contains("${")) {
        return None;
    }
    Some((label.to_owned(), i + 1, end))
}

/// The index just past the closing `quote` of a string starting at `i`.
fn string_end(bytes: &[u8], mut i: usize, quote: u8) -> usize {
    while i < bytes.len() {
        match bytes[i] {
            b'\\' => i += 2,
            b'\n' if quote != b'`' => return i,
            b if b == quote => return i + 1,
            _ => i += 1,
        }
    }
    bytes.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delays_follow_the_page_script_rule() {
        assert_eq!(act_delay("20s"), Some(Duration::from_secs(20)));
        assert_eq!(act_delay(" 1.5 m\n"), Some(Duration::from_secs(90)));
        assert_eq!(act_delay("500ms"), Some(Duration::from_millis(500)));
        assert_eq!(act_delay("\u{a0}2s"), Some(Duration::from_secs(2)));
        for bad in [
            "20", "20 sec", "2,5s", ".5s", "5.s", "1h", "20S", "-1s", "", "1e3ms",
        ] {
            assert_eq!(act_delay(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn trigger_literals_skip_comments_and_strings() {
        let js = "// docent.trigger('OLD')\nconst a = \"docent.trigger('NO')\";\n\
                  docent.trigger(\"A\", {context: 'x'}); window.docent . trigger ( 'B' );\n\
                  docent.trigger(`C`); docent.trigger(`${x}`); docent.trigger(label);";
        let found: Vec<String> = trigger_literals(js).into_iter().map(|f| f.0).collect();
        assert_eq!(found, ["A", "B", "C"]);
        let (_, at) = &trigger_literals("  docent.trigger('GO')")[0];
        assert_eq!(*at, 18);
    }
}
