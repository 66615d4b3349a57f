//! What the corpus says about a visitor's touch: why a kiosk sent a trigger or a page report
//! (a touch, or the page's own timer, idle return or script) and which element was touched.
//! Only a touch starts a visitor session and counts as activity; the rest are the screen's
//! own doing and must not look like a visitor in the corpus.

use serde::{Deserialize, Serialize};

/// The longest element description kept, in characters; a longer one is cut and ends in `…`.
pub const ELEMENT_CHARS: usize = 160;

/// Why a kiosk sent a `trigger` or a `page` frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum KioskCause {
    /// A visitor touched a `data-act` element or a link.
    Touch,
    /// A page's `data-act-after` timer fired.
    Timer,
    /// The kiosk went home (and may trigger the idle act) after the idle time.
    Idle,
    /// The page's own script called `docent.trigger` or moved to another page.
    Script,
    /// The kiosk's attract loop showed a page or triggered its act.
    Attract,
    /// The schedule showed the closed page or a range's home page.
    Schedule,
}

impl KioskCause {
    /// Whether a visitor did it. A frame from a kiosk older than this field counts as a touch,
    /// as it always did.
    pub fn is_touch(cause: Option<KioskCause>) -> bool {
        cause.is_none_or(|c| c == KioskCause::Touch)
    }
}

/// `element` as the corpus keeps it: trimmed, at most [`ELEMENT_CHARS`] characters, `None`
/// when empty.
pub fn element_description(element: Option<String>) -> Option<String> {
    let element = element?;
    let trimmed = element.trim();
    if trimmed.is_empty() {
        return None;
    }
    if trimmed.chars().count() <= ELEMENT_CHARS {
        return Some(trimmed.to_owned());
    }
    let mut cut: String = trimmed.chars().take(ELEMENT_CHARS - 1).collect();
    cut.push('…');
    Some(cut)
}

/// The fields of a `touch` event ([`super::EventKind::Touch`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct Touch {
    /// The kiosk.
    pub client: u64,
    /// The page touched, as the server's display state had it.
    pub page: Option<String>,
    /// The element, as the kiosk described it (`button#start [data-act=GREETING] "Hello"`).
    pub element: Option<String>,
    /// The act it asked for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub act: Option<String>,
    /// The page a link led to.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub link: Option<String>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn old_kiosks_frames_are_touches_and_timers_are_not() {
        assert!(KioskCause::is_touch(None));
        assert!(KioskCause::is_touch(Some(KioskCause::Touch)));
        assert!(!KioskCause::is_touch(Some(KioskCause::Timer)));
        assert!(!KioskCause::is_touch(Some(KioskCause::Idle)));
        assert!(!KioskCause::is_touch(Some(KioskCause::Script)));
        assert!(!KioskCause::is_touch(Some(KioskCause::Attract)));
        assert!(!KioskCause::is_touch(Some(KioskCause::Schedule)));
    }

    #[test]
    fn descriptions_are_trimmed_and_bounded() {
        assert_eq!(element_description(None), None);
        assert_eq!(element_description(Some("   ".into())), None);
        let short = element_description(Some(" button#start ".into()));
        assert_eq!(short.as_deref(), Some("button#start"));
        let long = element_description(Some("é".repeat(500))).unwrap();
        assert_eq!(long.chars().count(), ELEMENT_CHARS);
        assert!(long.ends_with('…'));
    }
}
