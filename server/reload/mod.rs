//! Live reload: while `docent serve` runs, saving any file of the bundle checks it again. A
//! bundle without errors replaces the live one at once (the dispatcher's `ArcSwap`); acts
//! already running finish with the commands they resolved. A bundle with errors is refused and
//! the last good one keeps running; the problems go to the log, the corpus (`bundle.refused`)
//! and the operator consoles' banner until a good save is live.
//!
//! Map:
//! - `watch`: the debounced file watcher, sending what changed to the loop.
//! - `live`: the reload loop: check off the async threads, swap or refuse, tell everyone.
//! - `settings`: what in `docent.yaml` a reload cannot put into effect (adapters, credentials).
//! - `status`: what the operators' banner shows now, also sent in `welcome`.

mod live;
mod settings;
mod status;
mod watch;

use std::time::Duration;

pub use status::{ReloadStatus, ReloadView};

use crate::content::config::AdapterKind;
use crate::state::AppState;

/// How long the folder must be quiet before a batch of changes is checked: long enough that an
/// editor's write, rename and mode change are one reload, short enough that a save is live
/// within a second.
pub const DEFAULT_DEBOUNCE: Duration = Duration::from_millis(150);

/// How often a bundle folder that went missing is looked for again.
pub const FOLDER_RECHECK: Duration = Duration::from_secs(1);

/// How live reload runs.
#[derive(Clone, Debug)]
pub struct ReloadOptions {
    /// The quiet period that makes a burst of writes one reload.
    pub debounce: Duration,
    /// The speech adapter every reloaded bundle is given, as the first one was
    /// (`docent serve --preview` speaks in the browser whatever the bundle says).
    pub speech_override: Option<AdapterKind>,
}

impl Default for ReloadOptions {
    fn default() -> Self {
        ReloadOptions {
            debounce: DEFAULT_DEBOUNCE,
            speech_override: None,
        }
    }
}

/// Starts watching the live bundle's folder; the loop is a tracked task that ends with the
/// server. Must be called within the tokio runtime.
pub fn watch(state: &AppState, options: ReloadOptions) {
    let reloader = live::Reloader::new(state.clone(), options);
    state.life.tracker.spawn(reloader.run());
}
