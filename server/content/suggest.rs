//! "Did you mean ...?" for labels, keys, verbs, contexts and file names.
//!
//! Comparison ignores case, because the commonest slip is `label` for `Label` or `say` for
//! `SAY`. A candidate is offered only when it is close enough that a person would see the
//! connection; an unrelated word gets no suggestion rather than a confusing one.

/// The candidate closest to `word`, or `None` when nothing is plausibly what was meant.
///
/// A candidate qualifies when, ignoring case, it equals `word`, lies within a small edit
/// distance (about one edit per three characters), or is an abbreviation of it (`Cmds` for
/// `Commands`: one word's letters appear in order in the other). Ties go to the
/// alphabetically first candidate so the answer never depends on iteration order.
pub fn closest<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let word_lower = word.to_lowercase();
    let mut best: Option<(usize, &'a str)> = None;
    for candidate in candidates {
        let Some(score) = score(&word_lower, &candidate.to_lowercase()) else {
            continue;
        };
        let better = match best {
            None => true,
            Some((best_score, best_candidate)) => (score, candidate) < (best_score, best_candidate),
        };
        if better {
            best = Some((score, candidate));
        }
    }
    best.map(|(_, candidate)| candidate)
}

/// `" Did you mean `X`?"` for the closest candidate, or an empty string: ready to append to
/// a sentence.
pub(crate) fn did_you_mean<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> String {
    closest(word, candidates).map_or_else(String::new, |s| format!(" Did you mean `{s}`?"))
}

/// Lower is closer; `None` means "not a plausible match". Both arguments are lower-cased.
fn score(word: &str, candidate: &str) -> Option<usize> {
    if word.is_empty() || candidate.is_empty() {
        return None;
    }
    let distance = strsim::damerau_levenshtein(word, candidate);
    let shorter = word.chars().count().min(candidate.chars().count());
    let longer = word.chars().count().max(candidate.chars().count());
    if distance <= (shorter / 3).max(1) && distance < shorter {
        return Some(distance);
    }
    // Abbreviations are far apart by edit distance but obvious to a reader.
    let (short, long) = if word.len() <= candidate.len() {
        (word, candidate)
    } else {
        (candidate, word)
    };
    if shorter >= 3
        && shorter * 2 >= longer
        && is_subsequence(short, long)
        && same_start(short, long)
    {
        return Some(distance);
    }
    None
}

fn is_subsequence(short: &str, long: &str) -> bool {
    let mut long_chars = long.chars();
    short.chars().all(|c| long_chars.any(|l| l == c))
}

fn same_start(a: &str, b: &str) -> bool {
    a.chars().next() == b.chars().next()
}

#[cfg(test)]
mod tests {
    use super::*;

    const KEYS: [&str; 3] = ["Label", "Text", "Cmds"];

    #[test]
    fn suggests_keys_for_common_slips() {
        assert_eq!(closest("Lable", KEYS), Some("Label"));
        assert_eq!(closest("label", KEYS), Some("Label"));
        assert_eq!(closest("Commands", KEYS), Some("Cmds"));
        assert_eq!(closest("Comands", KEYS), Some("Cmds"));
        assert_eq!(closest("text", KEYS), Some("Text"));
        assert_eq!(closest("Txt", KEYS), Some("Text"));
    }

    #[test]
    fn suggests_verbs_ignoring_case() {
        let verbs = [
            "SAY",
            "PROJECT",
            "DISPLAY_PAGE",
            "SET_WAYPOINT",
            "DRIVE_START",
            "DRIVE_STOP",
            "WAIT",
        ];
        assert_eq!(closest("say", verbs), Some("SAY"));
        assert_eq!(closest("DISPLAY", verbs), Some("DISPLAY_PAGE"));
        assert_eq!(closest("DRIVE_STRAT", verbs), Some("DRIVE_START"));
        assert_eq!(closest("PROJETC", verbs), Some("PROJECT"));
        assert_eq!(closest("WAYT", verbs), Some("WAIT"));
    }

    #[test]
    fn unrelated_words_get_no_suggestion() {
        assert_eq!(closest("Banana", KEYS), None);
        assert_eq!(closest("X", KEYS), None);
        assert_eq!(closest("", KEYS), None);
        assert_eq!(closest("GOODBYE", ["WELCOME", "OK", "WHERE_FROM"]), None);
        assert_eq!(closest("anything", std::iter::empty()), None);
    }

    #[test]
    fn ties_are_broken_alphabetically() {
        assert_eq!(closest("AB", ["AC", "AA"]), Some("AA"));
        assert_eq!(closest("AB", ["AA", "AC"]), Some("AA"));
    }
}
