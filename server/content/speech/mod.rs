//! What the robot will really say: checks on every spoken text (each `Text...` alternative and
//! every `SAY` argument) for things a speech synthesiser reads out differently from what the
//! author sees: emoji (read as their names), web and e-mail addresses (spelt out), markup and
//! unfilled placeholders (read out as symbols), and texts too long for a visitor's tap.
//!
//! The rule for severity: an error when the robot would certainly say something the author did
//! not mean (an emoji's name, `{name}`, a tag), a warning when it may be intended (an address,
//! a long text). Texts far above the length limit are errors too.

use std::time::Duration;

mod finders;
mod suspects;

use finders::{find_address, find_markup, find_placeholder, is_emoji};
use suspects::Suspects;

use crate::DiagnosticCode;
use crate::config::SpeechConfig;
use crate::diagnostic::Diagnostic;
use crate::model::Pos;

/// Texts over this many times `speech.max_seconds` are errors, not warnings.
const FAR_ABOVE: u32 = 4;

/// How long `text` takes to say at `rate_wpm`: words over rate, plus a short pause. The `log`
/// speech adapter paces itself by this, and the length check estimates with it.
pub fn speaking_time(text: &str, rate_wpm: u32) -> Duration {
    let words = word_count(text).max(1) as f64;
    Duration::from_secs_f64(words * 60.0 / f64::from(rate_wpm.max(1)) + 0.1)
}

/// Words separated by white space, as `split_whitespace` counts them; ASCII texts (nearly
/// all) are counted byte by byte, since every spoken text is counted at each load.
fn word_count(text: &str) -> usize {
    if !text.is_ascii() {
        return text.split_whitespace().count();
    }
    // `char::is_whitespace` on ASCII: the ASCII white space plus the vertical tab.
    let space = |b: u8| b.is_ascii_whitespace() || b == 0x0B;
    let bytes = text.as_bytes();
    let starts = bytes
        .windows(2)
        .filter(|pair| space(pair[0]) && !space(pair[1]))
        .count();
    starts + usize::from(bytes.first().is_some_and(|&b| !space(b)))
}

/// A spoken text and where it was written.
pub(crate) struct SpokenText<'a> {
    /// The text exactly as Docent will hand it to the speech device.
    pub text: &'a str,
    /// Where the text (or its opening quote) starts.
    pub pos: &'a Pos,
    /// Character offset from `pos` where `text` appears unchanged, if it does; lets a problem
    /// point at the very character.
    pub verbatim_at: Option<u32>,
}

impl SpokenText<'_> {
    /// The position of the character at byte `at` of the text, or of the text's start.
    fn pos_of(&self, at: usize) -> Pos {
        let (Some(offset), Some(before)) = (self.verbatim_at, self.text.get(..at)) else {
            return self.pos.clone();
        };
        let chars = u32::try_from(before.chars().count()).unwrap_or(0);
        let mut pos = self.pos.clone();
        pos.column = pos.column.saturating_add(offset).saturating_add(chars);
        pos
    }
}

/// Checks one spoken text; problems are appended to `out`.
pub(crate) fn check_spoken(
    spoken: &SpokenText<'_>,
    speech: &SpeechConfig,
    out: &mut Vec<Diagnostic>,
) {
    let text = spoken.text;
    let suspects = Suspects::of(text);
    if suspects.emoji
        && let Some((at, emoji)) = text.char_indices().find(|&(_, c)| is_emoji(c))
    {
        let message = format!(
            "This text contains the emoji {emoji}. The robot reads an emoji out by its name \
             (for example \"smiling face with smiling eyes\"). Remove it, or write in words \
             what the robot should say."
        );
        out.push(Diagnostic::error(
            DiagnosticCode::SpeechEmoji,
            &spoken.pos_of(at),
            message,
        ));
    }
    if suspects.address
        && let Some((at, address)) = find_address(text)
    {
        let message = if address.contains('@') {
            format!(
                "The robot reads the e-mail address `{address}` sign by sign (\"at\", \"dot\", \
                 every letter it cannot say as a word). Write it the way it should sound, for \
                 example \"write to our desk, see the address on my screen\", and show the \
                 address on a page instead."
            )
        } else {
            format!(
                "The robot spells out `{address}` sign by sign (\"h t t p s colon slash \
                 slash…\"). Write it the way it should sound, for example \"our website, museum \
                 dot org\", and show the address on a page instead."
            )
        };
        out.push(Diagnostic::warning(
            DiagnosticCode::SpeechAddress,
            &spoken.pos_of(at),
            message,
        ));
    }
    if suspects.markup
        && let Some((at, markup)) = find_markup(text)
    {
        let message = format!(
            "`{markup}` is formatting (HTML or Markdown), not words: the robot reads its signs \
             out or stumbles over them. Remove it; speech has no bold or links."
        );
        out.push(Diagnostic::error(
            DiagnosticCode::SpeechMarkup,
            &spoken.pos_of(at),
            message,
        ));
    }
    if suspects.placeholder
        && let Some((at, placeholder)) = find_placeholder(text)
    {
        let message = format!(
            "`{placeholder}` looks like a placeholder that was never filled in. Docent does not \
             replace anything in a text: the robot would say it as written. Write the real words."
        );
        out.push(Diagnostic::error(
            DiagnosticCode::SpeechPlaceholder,
            &spoken.pos_of(at),
            message,
        ));
    }
    check_length(spoken, speech, out);
}

fn check_length(spoken: &SpokenText<'_>, speech: &SpeechConfig, out: &mut Vec<Diagnostic>) {
    let limit = speech.max_seconds;
    let seconds = speaking_time(spoken.text, speech.rate_wpm).as_secs_f64();
    if seconds <= f64::from(limit) {
        return;
    }
    let words = spoken.text.split_whitespace().count();
    let said = format!(
        "Saying this text takes about {} ({words} words at {} words per minute)",
        spoken_duration(seconds),
        speech.rate_wpm
    );
    let far = limit.saturating_mul(FAR_ABOVE);
    if seconds > f64::from(far) {
        let message = format!(
            "{said}, far more than the {limit} s a text may take (`speech.max_seconds` in \
             docent.yaml); texts over {far} s are refused, since a visitor's tap would start \
             all of it and nobody could stop it but the operator. Was a whole document pasted \
             here? Split it into short acts, one for each thing the visitor can ask."
        );
        out.push(Diagnostic::error(
            DiagnosticCode::SpeechTooLong,
            spoken.pos,
            message,
        ));
    } else {
        let message = format!(
            "{said}, more than the {limit} s a text may take (`speech.max_seconds` in \
             docent.yaml). Visitors rarely listen that long: split it into shorter acts, or \
             raise `speech.max_seconds` if this length is wanted."
        );
        out.push(Diagnostic::warning(
            DiagnosticCode::SpeechTooLong,
            spoken.pos,
            message,
        ));
    }
}

/// `45 s`, `2 min 10 s`.
fn spoken_duration(seconds: f64) -> String {
    let whole = seconds.round() as u64;
    match (whole / 60, whole % 60) {
        (0, s) => format!("{s} s"),
        (m, 0) => format!("{m} min"),
        (m, s) => format!("{m} min {s} s"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn codes(text: &str) -> Vec<(&'static str, u32)> {
        let pos = Pos::new("acts.yaml", 4, 7);
        let spoken = SpokenText {
            text,
            pos: &pos,
            verbatim_at: Some(2),
        };
        let mut out = Vec::new();
        check_spoken(
            &spoken,
            &crate::config::SiteConfig::default().speech,
            &mut out,
        );
        out.iter().map(|d| (d.code.as_str(), d.column)).collect()
    }

    #[test]
    fn ordinary_texts_pass() {
        for text in [
            "Welcome to the museum! It is 20 °C in here, entry costs 5 € (10 % off today).",
            "Room 4, 2nd floor; ask at the desk & enjoy.",
            "The years 1980–1990 <- an arrow is fine, 3 < 4 and 5 > 2.",
            "Our e-mail desk opens at 10:00. C# and F* are languages.",
        ] {
            assert_eq!(codes(text), [], "{text}");
        }
    }

    #[test]
    fn emoji_addresses_markup_and_placeholders_are_found_at_their_character() {
        assert_eq!(codes("Hi 😊 there"), [("speech-emoji", 12)]);
        assert_eq!(codes("See https://museum.org/x."), [("speech-address", 13)]);
        assert_eq!(codes("Visit www.museum.org"), [("speech-address", 15)]);
        assert_eq!(
            codes("Mail info@museum.org today"),
            [("speech-address", 14)]
        );
        assert_eq!(codes("This is <b>bold</b>"), [("speech-markup", 17)]);
        assert_eq!(codes("Tom &amp; Jerry"), [("speech-markup", 13)]);
        assert_eq!(codes("Really **important**"), [("speech-markup", 16)]);
        assert_eq!(codes("Hello {name}, welcome"), [("speech-placeholder", 15)]);
        assert_eq!(codes("Hello {{ name }}"), [("speech-placeholder", 15)]);
        assert_eq!(codes("Opens at [TIME] today"), [("speech-placeholder", 18)]);
        assert_eq!(codes("You are %s"), [("speech-placeholder", 17)]);
        assert_eq!(
            codes("TODO write the greeting"),
            [("speech-placeholder", 9)]
        );
    }

    #[test]
    fn addresses_are_found_in_any_case() {
        assert_eq!(codes("See HTTPS://Museum.org"), [("speech-address", 13)]);
        assert_eq!(codes("Visit WWW.museum.org"), [("speech-address", 15)]);
        assert_eq!(codes("Not an awww.address"), []);
        assert_eq!(finders::find_ignoring_case("ab", "abc"), None);
    }

    #[test]
    fn long_texts_warn_and_far_longer_ones_are_errors() {
        // 160 words a minute: 30 s is 80 words.
        let words = |n: usize| vec!["word"; n].join(" ");
        assert_eq!(codes(&words(79)), []);
        assert_eq!(codes(&words(81)), [("speech-too-long", 7)]);
        let pos = Pos::new("a.yaml", 1, 1);
        let long = words(400);
        let spoken = SpokenText {
            text: &long,
            pos: &pos,
            verbatim_at: None,
        };
        let mut out = Vec::new();
        check_spoken(
            &spoken,
            &crate::config::SiteConfig::default().speech,
            &mut out,
        );
        assert!(out[0].is_error());
        assert!(out[0].message.contains("2 min 30 s"), "{}", out[0].message);
        assert_eq!(spoken_duration(59.6), "1 min");
    }

    #[test]
    fn words_are_counted_as_split_whitespace_counts_them() {
        for text in [
            "",
            " ",
            "one",
            " one  two\tthree\r\nfour ",
            "a\u{0B}b\u{0C}c",
            "Grüße\u{A0}aus Wien",
            "\u{2003}em space",
        ] {
            assert_eq!(
                word_count(text),
                text.split_whitespace().count(),
                "{text:?}"
            );
        }
    }
}
