//! Visitor sessions as the operator marks them: a session starts and ends by hand, and the
//! group and situation marks made meanwhile carry its number into the corpus.

use std::sync::Mutex;

use crate::sync::lock;

/// The visitor groups an operator can note.
pub const VISITOR_GROUPS: [&str; 3] = ["single", "group", "children"];

/// The current visitor session.
#[derive(Debug, Default)]
pub struct Visits {
    inner: Mutex<Inner>,
}

#[derive(Debug, Default)]
struct Inner {
    last: u64,
    current: Option<u64>,
}

impl Visits {
    /// Starts a new session; returns the one it ended (if one was running) and the new one.
    pub fn start(&self) -> (Option<u64>, u64) {
        let mut inner = lock(&self.inner);
        inner.last += 1;
        let session = inner.last;
        (inner.current.replace(session), session)
    }

    /// Ends the running session, if any, and returns it.
    pub fn end(&self) -> Option<u64> {
        lock(&self.inner).current.take()
    }

    /// The running session.
    pub fn current(&self) -> Option<u64> {
        lock(&self.inner).current
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn starting_a_session_ends_the_running_one() {
        let visits = Visits::default();
        assert_eq!(visits.current(), None);
        assert_eq!(visits.start(), (None, 1));
        assert_eq!(visits.start(), (Some(1), 2));
        assert_eq!(visits.current(), Some(2));
        assert_eq!(visits.end(), Some(2));
        assert_eq!(visits.end(), None);
        assert_eq!(visits.start(), (None, 3));
    }
}
