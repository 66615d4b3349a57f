//! The kiosk's attract loop (`kiosk: attract:` in `docent.yaml`, or one per schedule range):
//! what an unused touchscreen shows to draw visitors near. Read by `config_file/attract.rs`,
//! handed to the kiosk shell as JSON (`static/attract.js` runs it) and never parsed again.

use std::time::Duration;

use serde::Serialize;

/// How long each attract page stays when `every` is not written.
pub const DEFAULT_EVERY: Duration = Duration::from_secs(10);

/// An attract loop: after `after` without a touch the kiosk cycles `pages` (each for `every`)
/// and/or triggers `act`; the first touch ends it and returns home.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct AttractLoop {
    /// Time without a touch before the loop starts.
    #[serde(rename = "after_ms", serialize_with = "millis")]
    pub after: Duration,
    /// Pages under `pages/` shown in turn; empty: the page on show stays (with `act`).
    pub pages: Vec<String>,
    /// How long each page stays; with an act and no pages, how often the act is triggered
    /// again (`None`: once).
    #[serde(rename = "every_ms", serialize_with = "optional_millis")]
    pub every: Option<Duration>,
    /// The act triggered when the loop starts (source `kiosk`, cause `attract`).
    pub act: Option<String>,
}

impl AttractLoop {
    /// How long each page stays on screen.
    pub fn page_time(&self) -> Duration {
        self.every.unwrap_or(DEFAULT_EVERY)
    }
}

fn millis<S: serde::Serializer>(d: &Duration, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_u64(u64::try_from(d.as_millis()).unwrap_or(u64::MAX))
}

fn optional_millis<S: serde::Serializer>(d: &Option<Duration>, s: S) -> Result<S::Ok, S::Error> {
    match d {
        Some(d) => millis(d, s),
        None => s.serialize_none(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_kiosk_gets_milliseconds_and_the_pages() {
        let attract = AttractLoop {
            after: Duration::from_secs(120),
            pages: vec!["attract/a.html".into()],
            every: None,
            act: Some("INVITE".into()),
        };
        let json = serde_json::to_value(&attract).expect("serializable");
        assert_eq!(
            json,
            serde_json::json!({"after_ms": 120_000, "pages": ["attract/a.html"], "every_ms": null, "act": "INVITE"})
        );
        assert_eq!(attract.page_time(), DEFAULT_EVERY);
    }
}
