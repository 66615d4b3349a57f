//! A text as YAML must spell it to read back exactly: plain when nothing in it can change
//! its meaning, else in double quotes with escapes. The cases follow what the loader warns
//! about (`acts_file/values.rs`, `acts_file/texts.rs`): `: ` makes a mapping, ` #` starts a
//! comment, `yes`/`no`/numbers are guessed as other types, a leading `-`, `[`, `{`, quote,
//! `&`, `*`, `!`, `|`, `>`, `%`, `@` or backtick means something else, and spaces at either
//! end or line breaks are lost or folded. Inside a flow list `[a, b]` a plain text also avoids
//! `,[]{}`. When in doubt, quote.

use std::borrow::Cow;
use std::fmt::Write;

/// Words YAML 1.1 or 1.2 reads as something other than text (compared in lower case).
const GUESSED_WORDS: [&str; 12] = [
    "y", "yes", "n", "no", "true", "false", "on", "off", "null", "~", ".inf", ".nan",
];

/// Where a text is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Context {
    /// A `- ` item or a value after `Key: `.
    Block,
    /// An item of a list written `[a, b]`.
    Flow,
}

/// `text` spelt for a YAML file, written in `context`.
pub fn yaml_text(text: &str, context: Context) -> Cow<'_, str> {
    if plain_is_safe(text, context) {
        Cow::Borrowed(text)
    } else {
        Cow::Owned(double_quoted(text))
    }
}

/// Whether `text` written without quotes reads back as exactly `text`, and as text.
fn plain_is_safe(text: &str, context: Context) -> bool {
    let Some(first) = text.chars().next() else {
        return false;
    };
    let starts_special = "-?:,[]{}#&*!|>'\"%@`".contains(first)
        || first.is_whitespace()
        || first.is_ascii_digit()
        || first == '+'
        || first == '.';
    let ends_special = text.ends_with(char::is_whitespace) || text.ends_with(':');
    let inner_special = text.contains(": ")
        || text.contains(" #")
        || text.contains('\t')
        || (context == Context::Flow && text.contains([',', '[', ']', '{', '}']))
        || text.chars().any(needs_escape);
    let guessed = GUESSED_WORDS.contains(&text.to_lowercase().as_str());
    !(starts_special || ends_special || inner_special || guessed)
}

/// Characters a plain text cannot hold as they are: line breaks and other control
/// characters, the byte order mark and Unicode's line and paragraph separators.
fn needs_escape(c: char) -> bool {
    c.is_control() || matches!(c, '\u{FEFF}' | '\u{2028}' | '\u{2029}')
}

/// `text` in double quotes, `\` and `"` escaped, special characters as escapes.
fn double_quoted(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 2);
    out.push('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            c if needs_escape(c) => {
                let _ = write!(out, "\\u{:04X}", u32::from(c));
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ordinary_sentences_stay_plain() {
        for text in [
            "Willkommen im Museum!",
            "Hallo, kleine Entdecker!",
            "Ça va? Très bien.",
            "Die Maschine wurde 1984 gebaut.",
            "C# ist eine Sprache",
            "Preis: 5 Euro".replace(": ", " ").as_str(),
        ] {
            assert_eq!(yaml_text(text, Context::Block), text, "{text:?}");
        }
        assert_eq!(yaml_text("Hallo, du", Context::Flow), "\"Hallo, du\"");
    }

    #[test]
    fn texts_yaml_would_change_are_quoted() {
        for (text, written) in [
            ("Note: this", r#""Note: this""#),
            ("yes", r#""yes""#),
            ("No", r#""No""#),
            ("1984", r#""1984""#),
            ("- a dash", r#""- a dash""#),
            ("a #hash", r##""a #hash""##),
            ("\"quoted\"", r#""\"quoted\"""#),
            ("line\nbreak", r#""line\nbreak""#),
            (" padded ", r#"" padded ""#),
            ("back\\slash, too", r#""back\\slash, too""#),
            ("bell\u{7}", r#""bell\u0007""#),
            ("ends with:", r#""ends with:""#),
            // Not from a translations table any more (refused as a formula), but quoted all
            // the same if it came.
            ("@at", r#""@at""#),
        ] {
            assert_eq!(yaml_text(text, Context::Flow), written, "{text:?}");
        }
    }
}
