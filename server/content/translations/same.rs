//! When a translation may be the same text as its original. A copied original is the commonest
//! unfinished translation (a CAT tool's "copy source to target", a spreadsheet cell filled
//! down), and a visitor in that language then hears the default language while the console
//! says the act is translated. But names and numbers are rightly the same in every language
//! (`Rembrandt`, `Mona Lisa`, `1642`, `10:00–18:00`), so a text is let through when it is
//! [`may_stay_the_same`]: `docent check` warns about any other (`translation-same-as-original`)
//! and `docent translations import` refuses a table that brings one.

/// Whether `text` may be its own translation: it has no letters (a number, a time, a
/// sign), is a single word (`Rembrandt`, `OK`), or every word starts with a capital letter or
/// a digit (a name or a title: `Mona Lisa`, `Van Gogh Museum`).
pub fn may_stay_the_same(text: &str) -> bool {
    let words: Vec<&str> = text.split_whitespace().collect();
    let no_letters = !text.chars().any(char::is_alphabetic);
    let capitalised = words.iter().all(|word| {
        let first = word.chars().find(|c| c.is_alphanumeric());
        first.is_none_or(|c| c.is_uppercase() || c.is_numeric())
    });
    no_letters || words.len() <= 1 || capitalised
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_numbers_and_single_words_may_stay_the_same() {
        for text in [
            "Rembrandt",
            "OK",
            "Mona Lisa",
            "Van Gogh Museum",
            "1642",
            "10:00–18:00",
            "«Nachtwache»",
        ] {
            assert!(may_stay_the_same(text), "{text:?}");
        }
    }

    #[test]
    fn sentences_may_not() {
        for text in [
            "Welcome to the museum!",
            "Good bye",
            "Leonardo da Vinci painted it",
        ] {
            assert!(!may_stay_the_same(text), "{text:?}");
        }
    }
}
