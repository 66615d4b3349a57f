//! [`Open`]: a value of one of the protocol's closed sets as an event carries it, which a reader
//! of an older Docent may find holds a value added since. Error codes are added without a new
//! event format (`docs/CORPUS.md`), and an export of a newer Docent's log must still show them
//! as written, as it always did, rather than call the line damaged.

use std::fmt;

use serde::de::{DeserializeOwned, IntoDeserializer, value::StrDeserializer};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A value of the closed set `T`, or, read back, one a newer Docent wrote.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Open<T> {
    /// A value this Docent knows (the only kind it writes).
    Known(T),
    /// A value this Docent does not know, as written.
    Newer(String),
}

impl<T> From<T> for Open<T> {
    fn from(value: T) -> Self {
        Open::Known(value)
    }
}

impl<T: Serialize> Serialize for Open<T> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Open::Known(value) => value.serialize(serializer),
            Open::Newer(name) => serializer.serialize_str(name),
        }
    }
}

impl<'de, T: DeserializeOwned> Deserialize<'de> for Open<T> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        let known: StrDeserializer<'_, serde::de::value::Error> = name.as_str().into_deserializer();
        Ok(match T::deserialize(known) {
            Ok(value) => Open::Known(value),
            Err(_) => Open::Newer(name),
        })
    }
}

impl<T: fmt::Display> fmt::Display for Open<T> {
    /// The value as written in the corpus.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Open::Known(value) => value.fmt(f),
            Open::Newer(name) => f.write_str(name),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ErrorCode;

    #[test]
    fn a_known_code_reads_as_itself_and_a_newer_one_as_written() {
        let known: Open<ErrorCode> = serde_json::from_str("\"rate-limited\"").unwrap();
        assert_eq!(known, Open::Known(ErrorCode::RateLimited));
        assert_eq!(known.to_string(), "rate-limited");
        let newer: Open<ErrorCode> = serde_json::from_str("\"too-sleepy\"").unwrap();
        assert_eq!(newer, Open::Newer("too-sleepy".into()));
        assert_eq!(serde_json::to_string(&newer).unwrap(), "\"too-sleepy\"");
        assert_eq!(newer.to_string(), "too-sleepy");
        assert!(
            serde_json::from_str::<Open<ErrorCode>>("3").is_err(),
            "not a name"
        );
    }
}
