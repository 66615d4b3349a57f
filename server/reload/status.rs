//! What live reload has to tell the operators right now: the problems of a refused save, a
//! bundle folder that cannot be watched, settings that are not yet in effect. Connected consoles
//! learn of changes from the `bundle.*` events; a console joining later reads the same thing
//! from the `reload` field of its `welcome` state, so the banner never depends on when it joined.
//! It also keeps when the running bundle went live, which `/report` gives while a save is
//! refused ("the running bundle is the last good one from 14:05").

use std::sync::Mutex;
use std::time::SystemTime;

use crate::content::Diagnostic;
use crate::sync::lock;
pub use docent_protocol::state::ReloadView;

/// The shared live-reload status. Cheap to read; changed only by the reload loop.
#[derive(Debug)]
pub struct ReloadStatus {
    view: Mutex<ReloadView>,
    /// When the running bundle went live: start-up, then each good save.
    live_since: Mutex<SystemTime>,
}

impl Default for ReloadStatus {
    /// Made with the server, whose first bundle goes live then.
    fn default() -> Self {
        ReloadStatus {
            view: Mutex::default(),
            live_since: Mutex::new(SystemTime::now()),
        }
    }
}

impl ReloadStatus {
    /// When the running bundle went live.
    pub fn live_since(&self) -> SystemTime {
        *lock(&self.live_since)
    }

    /// A copy of the current status.
    pub fn view(&self) -> ReloadView {
        lock(&self.view).clone()
    }

    /// A good bundle went live: refusals and troubles are over.
    pub fn went_live(&self, not_applied: Vec<String>) {
        *lock(&self.live_since) = SystemTime::now();
        *lock(&self.view) = ReloadView {
            not_applied,
            ..ReloadView::default()
        };
    }

    /// A save was refused with these problems.
    pub fn refused(&self, diagnostics: Vec<Diagnostic>) {
        let mut view = lock(&self.view);
        view.refused = Some(diagnostics);
        view.trouble = None;
    }

    /// The folder cannot be watched or read.
    pub fn trouble(&self, message: String) {
        lock(&self.view).trouble = Some(message);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::content::Pos;

    #[test]
    fn a_good_save_clears_a_refusal_and_a_trouble() {
        let status = ReloadStatus::default();
        let problem = Diagnostic::error(
            crate::content::DiagnosticCode::UnknownVerb,
            &Pos::new("acts.yaml", 3, 5),
            "x",
        );
        status.refused(vec![problem.clone()]);
        status.trouble("gone".into());
        assert_eq!(status.view().refused, Some(vec![problem]));
        assert_eq!(status.view().trouble.as_deref(), Some("gone"));
        let before = status.live_since();
        status.went_live(vec!["restart".into()]);
        assert!(
            status.live_since() >= before,
            "the good save is the running bundle now"
        );
        assert_eq!(
            status.view(),
            ReloadView {
                refused: None,
                trouble: None,
                not_applied: vec!["restart".into()],
                media: Vec::new(),
            }
        );
    }
}
