//! A credential held in memory: never printed by `Debug`, compared in constant time.

use std::fmt;

use rand::RngExt;
use rand::distr::Alphanumeric;
use subtle::ConstantTimeEq;

/// Length of a generated credential: 32 letters and digits, about 190 bits.
const GENERATED_LEN: usize = 32;

/// A credential (operator or dialog-manager token).
#[derive(Clone)]
pub struct Secret(String);

impl Secret {
    /// Wraps a credential given by the site (environment or `docent.yaml`).
    pub fn new(value: impl Into<String>) -> Self {
        Secret(value.into())
    }

    /// A fresh random credential, for a server started without one.
    pub fn generate() -> Self {
        let value = rand::rng()
            .sample_iter(Alphanumeric)
            .take(GENERATED_LEN)
            .map(char::from)
            .collect();
        Secret(value)
    }

    /// Whether `presented` is this credential. Takes the same time wherever the first
    /// difference lies (only the length can be learnt from timing).
    pub fn matches(&self, presented: &str) -> bool {
        self.0.as_bytes().ct_eq(presented.as_bytes()).into()
    }

    /// The credential itself, for printing once at start-up when it was generated.
    pub fn expose(&self) -> &str {
        &self.0
    }
}

impl fmt::Debug for Secret {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("Secret(***)")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_only_the_same_credential() {
        let secret = Secret::new("correct-horse-battery");
        assert!(secret.matches("correct-horse-battery"));
        assert!(!secret.matches("correct-horse-batterY"));
        assert!(!secret.matches("correct-horse"));
        assert!(!secret.matches(""));
    }

    #[test]
    fn debug_never_shows_the_value() {
        let secret = Secret::new("correct-horse-battery");
        assert_eq!(format!("{secret:?}"), "Secret(***)");
    }

    #[test]
    fn generated_credentials_are_long_and_differ() {
        let (a, b) = (Secret::generate(), Secret::generate());
        assert_eq!(a.expose().len(), GENERATED_LEN);
        assert!(a.expose().chars().all(|c| c.is_ascii_alphanumeric()));
        assert_ne!(a.expose(), b.expose());
    }
}
