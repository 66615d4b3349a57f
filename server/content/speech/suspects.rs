//! One pass over a spoken text's bytes telling which finders can find anything in it. Nearly
//! every text is plain words, and the check reads every alternative of every act, so the
//! finders (each a scan of its own) run only where a byte they start from occurs.
//!
//! The rule that keeps this safe: a kind is left unflagged only when its finder certainly
//! finds nothing, i.e. every match of the finder contains the byte pattern flagged here. The
//! tests hold each finder against this pass on texts built from the finders' own triggers.

/// Which kinds of problem a text may contain; a kind left `false` is certainly absent.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub(super) struct Suspects {
    /// A character from U+2000 up (every emoji `is_emoji` knows starts with byte 0xE2 or more).
    pub emoji: bool,
    /// `@`, `://` (in every `http://`/`https://`), or `www.` in any case.
    pub address: bool,
    /// `<`, `&`, `*`, `_` or `[`.
    pub markup: bool,
    /// `{`, `$`, `%`, `[`, or the start of `XXX`, `TODO`, `TBD`, `FIXME`, `Lorem ipsum`.
    pub placeholder: bool,
}

impl Suspects {
    /// The kinds `text` may contain.
    pub fn of(text: &str) -> Self {
        let bytes = text.as_bytes();
        let mut found = Suspects::default();
        for (i, &byte) in bytes.iter().enumerate() {
            let next = bytes.get(i + 1).copied();
            match byte {
                0xE2..=0xFF => found.emoji = true,
                b'@' => found.address = true,
                b':' if bytes[i + 1..].starts_with(b"//") => found.address = true,
                b'.' if i >= 3 && bytes[i - 3..i].eq_ignore_ascii_case(b"www") => {
                    found.address = true;
                }
                b'<' | b'&' | b'*' | b'_' => found.markup = true,
                b'[' => {
                    found.markup = true;
                    found.placeholder = true;
                }
                b'{' | b'$' | b'%' => found.placeholder = true,
                b'X' if next == Some(b'X') => found.placeholder = true,
                b'T' if matches!(next, Some(b'O' | b'B')) => found.placeholder = true,
                b'F' if next == Some(b'I') => found.placeholder = true,
                b'L' if next == Some(b'o') => found.placeholder = true,
                _ => {}
            }
        }
        found
    }
}

#[cfg(test)]
mod tests {
    use rand::rngs::StdRng;
    use rand::{RngExt, SeedableRng};

    use super::super::finders::{find_address, find_markup, find_placeholder, is_emoji};
    use super::*;

    /// What the finders themselves find in `text`.
    fn found(text: &str) -> Suspects {
        Suspects {
            emoji: text.chars().any(is_emoji),
            address: find_address(text).is_some(),
            markup: find_markup(text).is_some(),
            placeholder: find_placeholder(text).is_some(),
        }
    }

    /// Every kind a finder finds is flagged.
    fn assert_covers(text: &str) {
        let (suspects, found) = (Suspects::of(text), found(text));
        for (kind, flagged, hit) in [
            ("emoji", suspects.emoji, found.emoji),
            ("address", suspects.address, found.address),
            ("markup", suspects.markup, found.markup),
            ("placeholder", suspects.placeholder, found.placeholder),
        ] {
            assert!(flagged || !hit, "{kind} in {text:?} was not flagged");
        }
    }

    #[test]
    fn plain_words_raise_no_suspicion() {
        let plain = "Welcome to the museum. This room shows the first computers, built in 1946; \
                     ask me anything, or tap Next.";
        assert_eq!(Suspects::of(plain), Suspects::default());
    }

    #[test]
    fn each_kind_is_flagged_where_its_finder_finds_it() {
        for text in [
            "Hi 😊 there",
            "❤",
            "See https://museum.org/x.",
            "HTTP://A.B",
            "Visit WWW.museum.org",
            "Mail info@museum.org today",
            "This is <b>bold</b>",
            "Tom &amp; Jerry",
            "Really **important**",
            "__x__",
            "[link](url)",
            "Hello {name}, welcome",
            "${x}",
            "You are %s",
            "Opens at [TIME] today",
            "XXX",
            "TODO write",
            "TBD",
            "FIXME",
            "Lorem ipsum dolor",
        ] {
            assert_covers(text);
            assert_ne!(Suspects::of(text), Suspects::default(), "{text:?}");
        }
    }

    #[test]
    fn random_texts_from_the_finders_triggers_are_always_covered() {
        // Pieces that start, end or almost make each finder's matches, mixed with words.
        const PIECES: [&str; 40] = [
            " ",
            "a",
            "word",
            ".",
            ",",
            ":",
            "/",
            "//",
            "@",
            "www",
            "WwW",
            "http",
            "https",
            "<",
            ">",
            "/>",
            "b",
            "&",
            ";",
            "amp",
            "#",
            "*",
            "_",
            "[",
            "]",
            "(",
            ")",
            "{",
            "}",
            "$",
            "%",
            "s",
            "d",
            "X",
            "TODO",
            "TB",
            "D",
            "FIXME",
            "Lorem ipsum",
            "😊",
        ];
        let mut rng = StdRng::seed_from_u64(10);
        for _ in 0..50_000 {
            let len = rng.random_range(1..12);
            let text: String = (0..len)
                .map(|_| PIECES[rng.random_range(0..PIECES.len())])
                .collect();
            assert_covers(&text);
        }
    }
}
