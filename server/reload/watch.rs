//! Watching a bundle folder: `notify` through `notify-debouncer-full`, whose quiet period turns
//! an editor's burst of writes, renames and mode changes into one batch. Batches arrive on a
//! tokio channel as [`Seen`] values: the changed files, relative to the bundle folder, or the
//! watcher's errors. Reads (including Docent's own, while reloading) and hidden or back-up
//! files (`.acts.yaml.swp`, `acts.yaml~`) are not changes.

use std::path::Path;
use std::time::Duration;

use notify_debouncer_full::notify::{EventKind, RecommendedWatcher, RecursiveMode};
use notify_debouncer_full::{DebounceEventResult, Debouncer, RecommendedCache, new_debouncer};
use tokio::sync::mpsc;

use crate::content::is_litter;

/// What the watcher saw.
#[derive(Debug)]
pub enum Seen {
    /// Files created, written, renamed, removed or re-permissioned, relative to the folder
    /// (`/`-separated; `.` for the folder itself).
    Changed(Vec<String>),
    /// The watcher failed; each entry says how.
    Failed(Vec<String>),
}

/// A running watcher; dropping it stops watching.
pub struct BundleWatcher {
    _debouncer: Debouncer<RecommendedWatcher, RecommendedCache>,
}

impl BundleWatcher {
    /// Watches `root` and everything below it, sending what it sees to `to`.
    pub fn start(
        root: &Path,
        debounce: Duration,
        to: mpsc::UnboundedSender<Seen>,
    ) -> Result<Self, String> {
        let base = root.to_owned();
        let handler = move |result: DebounceEventResult| {
            let seen = match result {
                Ok(events) => {
                    let mut changed: Vec<String> = (events.iter())
                        .filter(|e| !matches!(e.event.kind, EventKind::Access(_)))
                        .flat_map(|e| e.event.paths.iter())
                        .filter_map(|path| relative(&base, path))
                        .collect();
                    changed.sort();
                    changed.dedup();
                    if changed.is_empty() {
                        return;
                    }
                    Seen::Changed(changed)
                }
                Err(errors) => Seen::Failed(errors.iter().map(ToString::to_string).collect()),
            };
            // A closed channel means the reload loop ended: nothing is left to tell.
            let _ = to.send(seen);
        };
        let mut debouncer = new_debouncer(debounce, None, handler).map_err(|e| e.to_string())?;
        debouncer
            .watch(root, RecursiveMode::Recursive)
            .map_err(|e| e.to_string())?;
        Ok(BundleWatcher {
            _debouncer: debouncer,
        })
    }
}

/// `path` relative to `root`, `/`-separated; `None` outside it, for hidden files and for what
/// computers and editors leave (`Thumbs.db`, `desktop.ini`, `.bak`: [`is_litter`]).
fn relative(root: &Path, path: &Path) -> Option<String> {
    let rel = path.strip_prefix(root).ok()?;
    let mut parts = Vec::new();
    for part in rel.components() {
        let part = part.as_os_str().to_string_lossy();
        if part.starts_with('.') || is_litter(&part) {
            return None;
        }
        parts.push(part.into_owned());
    }
    if parts.is_empty() {
        return Some(".".to_owned());
    }
    Some(parts.join("/"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hidden_and_backup_files_are_not_changes() {
        let root = Path::new("/b");
        let rel = |p: &str| relative(root, Path::new(p));
        assert_eq!(rel("/b/acts.yaml").as_deref(), Some("acts.yaml"));
        assert_eq!(rel("/b/pages/a b.html").as_deref(), Some("pages/a b.html"));
        assert_eq!(rel("/b").as_deref(), Some("."));
        assert_eq!(rel("/b/.acts.yaml.swp"), None);
        assert_eq!(rel("/b/pages/.git/x"), None);
        assert_eq!(rel("/b/acts.yaml~"), None);
        assert_eq!(rel("/b/pages/Thumbs.db"), None);
        assert_eq!(rel("/b/media/desktop.ini"), None);
        assert_eq!(rel("/b/acts.yaml.bak"), None);
        assert_eq!(rel("/elsewhere/acts.yaml"), None);
    }
}
