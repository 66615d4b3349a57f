//! Choosing among an act's alternative texts: random, but never the same alternative twice in a
//! row for the same act and variant (paper, 3.1: avoids "a tedious listening experience").

use std::collections::HashMap;

use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};

/// The random choice of alternatives, with memory of the last one per act and variant.
pub struct Chooser {
    rng: StdRng,
    last: HashMap<(usize, usize), usize>,
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

    /// Picks one of `count` alternatives of variant `variant` of act `act`.
    pub fn pick(&mut self, act: usize, variant: usize, count: usize) -> usize {
        if count <= 1 {
            return 0;
        }
        let previous = self.last.get(&(act, variant)).copied();
        let choice = match previous {
            // Choose among the others: skip over the previous index.
            Some(prev) if prev < count => {
                let i = self.rng.random_range(0..count - 1);
                if i >= prev { i + 1 } else { i }
            }
            _ => self.rng.random_range(0..count),
        };
        self.last.insert((act, variant), choice);
        choice
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn never_repeats_back_to_back_and_uses_every_alternative() {
        let mut chooser = Chooser::new(Some(7));
        let picks: Vec<usize> = (0..300).map(|_| chooser.pick(0, 0, 3)).collect();
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
        let picks: Vec<usize> = (0..10).map(|_| chooser.pick(1, 0, 2)).collect();
        assert!(picks.windows(2).all(|w| w[0] != w[1]));
        assert_eq!(chooser.pick(2, 0, 1), 0);
        assert_eq!(chooser.pick(2, 0, 1), 0);
    }

    #[test]
    fn the_same_seed_gives_the_same_choices() {
        let run = |seed| {
            let mut c = Chooser::new(Some(seed));
            (0..50).map(|i| c.pick(i % 4, i % 2, 5)).collect::<Vec<_>>()
        };
        assert_eq!(run(42), run(42));
        assert_ne!(run(42), run(43));
    }

    #[test]
    fn memory_is_kept_per_act_and_variant() {
        let mut chooser = Chooser::new(Some(1));
        for _ in 0..50 {
            let a = chooser.pick(0, 0, 2);
            let b = chooser.pick(0, 1, 2);
            assert_ne!(a, chooser.pick(0, 0, 2));
            assert_ne!(b, chooser.pick(0, 1, 2));
        }
    }
}
