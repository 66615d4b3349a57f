//! Choosing among an act's alternative texts: random, but never the same alternative twice in a
//! row for the same act and variant (paper, 3.1: avoids "a tedious listening experience").
//!
//! The memory is keyed by label and variant name, not by position: a live reload reorders acts,
//! and a label keeps its meaning across reloads. If the act lost alternatives, a remembered
//! choice beyond the new count is ignored.

use std::collections::HashMap;

use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};

/// The random choice of alternatives, with memory of the last one per act and variant.
pub struct Chooser {
    rng: StdRng,
    /// Act label → variant name → the alternative chosen last. Nested so that a lookup by
    /// `&str` allocates nothing; only a first choice for an act or variant does.
    last: HashMap<String, HashMap<String, usize>>,
}

impl Chooser {
    /// A chooser seeded with `seed` (reproducible) or from the operating system.
    pub fn new(seed: Option<u64>) -> Self {
        let rng = match seed {
            Some(seed) => StdRng::seed_from_u64(seed),
            None => rand::make_rng(),
        };
        Chooser {
            rng,
            last: HashMap::new(),
        }
    }

    /// Picks one of `count` alternatives of variant `variant` of the act labelled `act`.
    pub fn pick(&mut self, act: &str, variant: &str, count: usize) -> usize {
        if count <= 1 {
            return 0;
        }
        let previous = (self.last.get(act)).and_then(|v| v.get(variant).copied());
        let choice = match previous {
            // Choose among the others: skip over the previous index.
            Some(prev) if prev < count => {
                let i = self.rng.random_range(0..count - 1);
                if i >= prev { i + 1 } else { i }
            }
            _ => self.rng.random_range(0..count),
        };
        let variants = match self.last.get_mut(act) {
            Some(variants) => variants,
            None => self.last.entry(act.to_owned()).or_default(),
        };
        match variants.get_mut(variant) {
            Some(last) => *last = choice,
            None => {
                variants.insert(variant.to_owned(), choice);
            }
        }
        choice
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn never_repeats_back_to_back_and_uses_every_alternative() {
        let mut chooser = Chooser::new(Some(7));
        let picks: Vec<usize> = (0..300).map(|_| chooser.pick("A", "Text", 3)).collect();
        assert!(picks.windows(2).all(|w| w[0] != w[1]));
        for alt in 0..3 {
            assert!(
                picks.iter().filter(|&&p| p == alt).count() > 60,
                "alternative {alt} starved"
            );
        }
    }

    #[test]
    fn two_alternatives_alternate_and_one_is_always_chosen() {
        let mut chooser = Chooser::new(None);
        let picks: Vec<usize> = (0..10).map(|_| chooser.pick("B", "Text", 2)).collect();
        assert!(picks.windows(2).all(|w| w[0] != w[1]));
        assert_eq!(chooser.pick("C", "Text", 1), 0);
        assert_eq!(chooser.pick("C", "Text", 1), 0);
    }

    #[test]
    fn the_same_seed_gives_the_same_choices() {
        let run = |seed| {
            let mut c = Chooser::new(Some(seed));
            let (acts, variants) = (["A", "B", "C", "D"], ["Text", "TextChild"]);
            (0..50)
                .map(|i| c.pick(acts[i % 4], variants[i % 2], 5))
                .collect::<Vec<_>>()
        };
        assert_eq!(run(42), run(42));
        assert_ne!(run(42), run(43));
    }

    #[test]
    fn memory_is_kept_per_act_and_variant() {
        let mut chooser = Chooser::new(Some(1));
        for _ in 0..50 {
            let a = chooser.pick("A", "Text", 2);
            let b = chooser.pick("A", "TextChild", 2);
            assert_ne!(a, chooser.pick("A", "Text", 2));
            assert_ne!(b, chooser.pick("A", "TextChild", 2));
        }
    }

    #[test]
    fn memory_follows_the_label_and_survives_fewer_alternatives() {
        let mut chooser = Chooser::new(Some(3));
        // A reload may leave an act with fewer alternatives: the old choice is out of range.
        for _ in 0..20 {
            chooser.pick("A", "Text", 5);
            let after = chooser.pick("A", "Text", 2);
            assert!(after < 2);
        }
        let first = chooser.pick("GREET", "Text", 2);
        assert_ne!(first, chooser.pick("GREET", "Text", 2));
    }
}
