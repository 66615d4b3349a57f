//! The finders of what a synthesiser reads differently from what the author sees: each
//! returns the first place of its kind in a text, with the words to quote.

/// Emoji and pictographs a synthesiser reads by name. Letters, digits, punctuation, currency
/// and ordinary symbols (©, °, €) are not among them.
pub(super) fn is_emoji(c: char) -> bool {
    matches!(u32::from(c),
        0x1F000..=0x1FAFF     // mahjong to symbols and pictographs extended-A
        | 0x2600..=0x27BF     // miscellaneous symbols, dingbats (☀ ✂ ❤)
        | 0x2B00..=0x2BFF     // arrows and stars such as ⭐
        | 0x1FC00..=0x1FFFD
        | 0xFE0F              // emoji presentation selector
        | 0x200D              // zero-width joiner inside emoji sequences
        | 0x2300..=0x23FF     // ⌚ ⏰ and friends
    )
}

/// The first web or e-mail address: `http://`, `https://`, `www.`, or `name@host.tld`.
pub(super) fn find_address(text: &str) -> Option<(usize, &str)> {
    let word_at = |start: usize| {
        let end = text[start..]
            .find(char::is_whitespace)
            .map_or(text.len(), |e| start + e);
        let word = text[start..end].trim_end_matches(['.', ',', ';', ':', '!', '?', ')']);
        (start, word)
    };
    for prefix in ["https://", "http://", "www."] {
        if let Some(at) = find_ignoring_case(text, prefix)
            && (at == 0 || !text.as_bytes()[at - 1].is_ascii_alphanumeric())
        {
            return Some(word_at(at));
        }
    }
    let at_sign = text.find('@')?;
    let start = text[..at_sign]
        .rfind(|c: char| c.is_whitespace() || c == '(' || c == '<')
        .map_or(0, |s| s + 1);
    let (start, word) = word_at(start);
    let (user, host) = word.split_once('@')?;
    let tld = host.rsplit_once('.').map(|(_, t)| t)?;
    (!user.is_empty() && tld.len() >= 2 && tld.chars().all(|c| c.is_ascii_alphabetic()))
        .then_some((start, word))
}

/// The byte offset of the first `needle` (ASCII, lower case) in `text`, whatever the case of
/// its letters. Every spoken text is searched, so no lower-case copy is made.
pub(super) fn find_ignoring_case(text: &str, needle: &str) -> Option<usize> {
    text.as_bytes()
        .windows(needle.len())
        .position(|window| window.eq_ignore_ascii_case(needle.as_bytes()))
}

/// The first HTML tag (`<b>`, `</a>`, `<br/>`), HTML entity (`&amp;`) or Markdown emphasis or
/// link (`**bold**`, `__bold__`, `[text](url)`).
pub(super) fn find_markup(text: &str) -> Option<(usize, &str)> {
    let bytes = text.as_bytes();
    for (at, c) in text.char_indices() {
        let rest = &text[at..];
        match c {
            '<' => {
                let inner = rest[1..].strip_prefix('/').unwrap_or(&rest[1..]);
                let end = rest.find('>').filter(|&e| e < 200);
                if inner.starts_with(|c: char| c.is_ascii_alphabetic())
                    && let Some(end) = end
                    && !rest[1..end].contains('<')
                {
                    return Some((at, &rest[..=end]));
                }
            }
            '&' => {
                let end = rest.find(';').filter(|&e| (2..=8).contains(&e))?;
                let name = &rest[1..end];
                if name.chars().all(|c| c.is_ascii_alphanumeric() || c == '#') {
                    return Some((at, &rest[..=end]));
                }
            }
            '*' | '_' if rest.len() > 2 && bytes[at + 1] == bytes[at] => {
                let marker = &rest[..2];
                if let Some(end) = rest[2..].find(marker)
                    && end > 0
                {
                    return Some((at, &rest[..end + 4]));
                }
            }
            '[' => {
                if let Some(close) = rest.find("](") {
                    let end = rest[close..].find(')').map(|e| close + e)?;
                    return Some((at, &rest[..=end]));
                }
            }
            _ => {}
        }
    }
    None
}

/// The first unfilled placeholder: `{name}`, `{{name}}`, `${name}`, `%s`/`%d`/`%1`, a
/// `[NAME]` in capitals, or `XXX`, `TODO`, `TBD`, `FIXME`, `Lorem ipsum`.
pub(super) fn find_placeholder(text: &str) -> Option<(usize, &str)> {
    for (at, c) in text.char_indices() {
        let rest = &text[at..];
        let found = match c {
            '{' => rest.find('}').map(|end| {
                let doubled = rest[end + 1..].starts_with('}');
                &rest[..=end + usize::from(doubled)]
            }),
            '$' if rest[1..].starts_with('{') => rest.find('}').map(|end| &rest[..=end]),
            '%' => {
                let spec = rest[1..].chars().next();
                let after = rest.get(2..).and_then(|r| r.chars().next());
                (matches!(spec, Some('s' | 'd')) && after.is_none_or(|c| !c.is_alphanumeric()))
                    .then(|| &rest[..2])
            }
            '[' => rest.find(']').map(|end| &rest[..=end]).filter(|inner| {
                let name = &inner[1..inner.len() - 1];
                !name.is_empty()
                    && name.chars().any(|c| c.is_ascii_uppercase())
                    && name
                        .chars()
                        .all(|c| c.is_ascii_uppercase() || c == '_' || c == ' ')
            }),
            _ => None,
        };
        if let Some(found) = found {
            return Some((at, found));
        }
    }
    const WORDS: [&str; 5] = ["XXX", "TODO", "TBD", "FIXME", "Lorem ipsum"];
    WORDS.iter().find_map(|w| {
        let at = text.find(w)?;
        let before_ok = text[..at]
            .chars()
            .next_back()
            .is_none_or(|c| !c.is_alphanumeric());
        let after_ok = text[at + w.len()..]
            .chars()
            .next()
            .is_none_or(|c| !c.is_alphanumeric());
        (before_ok && after_ok).then(|| (at, &text[at..at + w.len()]))
    })
}
