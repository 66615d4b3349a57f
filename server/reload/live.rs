//! The reload loop: waits for the watcher, checks the bundle on a blocking thread (loading
//! reads every file; the async threads keep serving triggers meanwhile), then either puts the
//! new bundle live or refuses it. Changes that arrive during a check are coalesced into the
//! next one, so one check runs at a time and the last save always wins.

use std::collections::BTreeSet;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use tokio::sync::mpsc;

use crate::content::config::SiteConfig;
use crate::content::{Bundle, Diagnostic, LoadReport, corpus_fingerprint, load_bundle};
use crate::events::{BundleRefused, BundleReloaded, BundleWatchFailed, ClientRole, EventKind};
use crate::reload::settings::{kiosk_shell_changed, not_applied};
use crate::reload::watch::{BundleWatcher, Seen};
use crate::reload::{FOLDER_RECHECK, ReloadOptions};
use crate::state::AppState;
use crate::ws::protocol::changed_frame;

/// The loop's state.
pub(super) struct Reloader {
    state: AppState,
    options: ReloadOptions,
    root: PathBuf,
    /// The configuration the adapters and credentials were set up from.
    started: SiteConfig,
    /// Files changed since the last bundle went live.
    pending: BTreeSet<String>,
    /// When the first of `pending` was seen.
    since: Option<Instant>,
    watcher: Option<BundleWatcher>,
    tx: mpsc::UnboundedSender<Seen>,
    rx: mpsc::UnboundedReceiver<Seen>,
}

impl Reloader {
    pub(super) fn new(state: AppState, options: ReloadOptions) -> Self {
        let bundle = state.dispatcher.bundle();
        let (tx, rx) = mpsc::unbounded_channel();
        Reloader {
            root: bundle.root.clone(),
            started: bundle.config.clone(),
            state,
            options,
            pending: BTreeSet::new(),
            since: None,
            watcher: None,
            tx,
            rx,
        }
    }

    pub(super) async fn run(mut self) {
        self.start_watcher();
        let shutdown = self.state.life.shutdown.clone();
        let mut recheck = tokio::time::interval(FOLDER_RECHECK);
        loop {
            tokio::select! {
                () = shutdown.cancelled() => break,
                seen = self.rx.recv() => match seen {
                    Some(seen) => self.seen(seen).await,
                    None => break,
                },
                _ = recheck.tick() => self.recheck().await,
            }
        }
    }

    /// Once a second: a folder renamed away may give the watcher no event, so look for it; a
    /// folder that is back (or a watcher that failed to start) is watched and checked again.
    async fn recheck(&mut self) {
        let present = self.root.is_dir();
        if self.watcher.is_some() && !present {
            self.folder_missing();
        } else if self.watcher.is_none() && present && self.start_watcher() {
            self.pending.insert(".".to_owned());
            self.since.get_or_insert_with(Instant::now);
            self.reload().await;
        }
    }

    /// Starts the watcher; on failure says so and leaves it for the next recheck.
    fn start_watcher(&mut self) -> bool {
        match BundleWatcher::start(&self.root, self.options.debounce, self.tx.clone()) {
            Ok(watcher) => {
                tracing::info!(bundle = %self.root.display(), "watching the bundle for changes");
                self.watcher = Some(watcher);
                true
            }
            Err(e) if !self.root.is_dir() => {
                drop(e);
                self.folder_missing();
                false
            }
            Err(e) => {
                self.watch_failed(format!(
                    "Docent cannot watch {} for changes ({e}); saved files are not checked \
                     until it can, or until Docent is restarted.",
                    self.root.display()
                ));
                false
            }
        }
    }

    async fn seen(&mut self, seen: Seen) {
        match seen {
            Seen::Failed(errors) => self.watch_failed(format!(
                "Watching {} for changes failed ({}); saved files may not be checked until \
                 Docent is restarted.",
                self.root.display(),
                errors.join("; ")
            )),
            Seen::Changed(files) => {
                self.since.get_or_insert_with(Instant::now);
                self.pending.extend(files);
                // Whatever else is already queued belongs to the same check.
                while let Ok(more) = self.rx.try_recv() {
                    if let Seen::Changed(files) = more {
                        self.pending.extend(files);
                    }
                }
                self.reload().await;
            }
        }
    }

    /// Checks the bundle and puts it live or refuses it.
    async fn reload(&mut self) {
        if !self.root.is_dir() {
            return self.folder_missing();
        }
        let started = Instant::now();
        let root = self.root.clone();
        let loaded = tokio::task::spawn_blocking(move || loaded_with_hash(&root));
        let (report, bundle_hash) = match loaded.await {
            Ok(loaded) => loaded,
            Err(e) => {
                return self.watch_failed(format!("checking the saved bundle failed: {e}"));
            }
        };
        let checked_ms = millis(started);
        let changed: Vec<String> = self.pending.iter().cloned().collect();
        match report.bundle {
            Some(bundle) => self.go_live(bundle, bundle_hash, &report.diagnostics, changed),
            None if !self.root.is_dir() => self.folder_missing(),
            None => self.refuse(report.diagnostics, changed, checked_ms),
        }
    }

    fn go_live(
        &mut self,
        mut bundle: Bundle,
        bundle_hash: Option<String>,
        diagnostics: &[Diagnostic],
        changed: Vec<String>,
    ) {
        bundle.fingerprint = bundle_hash.as_deref().map(Arc::from);
        if let Some(speech) = self.options.speech_override {
            bundle.config.speech.adapter = Some(speech);
        }
        let not_applied = not_applied(&self.started, &bundle.config);
        let (acts, contexts, page_acts) = (
            bundle.acts.len(),
            bundle.contexts.len(),
            bundle.page_acts.len(),
        );
        // The media first: the new bundle never serves a file it converts as it is.
        self.state.media.plan(&bundle);
        let old = self.state.dispatcher.replace_bundle(Arc::new(bundle));
        let new = self.state.dispatcher.bundle();
        let elapsed_ms = self.since.take().map_or(0, millis);
        self.pending.clear();
        tracing::info!(acts, elapsed_ms, files = ?changed, "the saved bundle is live");
        for sentence in &not_applied {
            tracing::warn!("a changed setting is not in effect yet: {sentence}");
        }
        self.state.reload.went_live(not_applied.clone());
        self.state
            .hub
            .publish(EventKind::BundleReloaded(BundleReloaded {
                bundle_hash,
                acts,
                contexts,
                page_acts,
                warnings: diagnostics.iter().filter(|d| d.is_warning()).count(),
                changed: changed.clone(),
                elapsed_ms,
                not_applied,
            }));
        let pages: Vec<&str> = (changed.iter())
            .filter_map(|f| f.strip_prefix("pages/"))
            .collect();
        let shell = kiosk_shell_changed(&old.config, &new.config);
        if !pages.is_empty() || shell {
            (self.state).send_to_role(ClientRole::Kiosk, &changed_frame(&pages, shell));
        }
    }

    fn refuse(&mut self, diagnostics: Vec<Diagnostic>, changed: Vec<String>, elapsed_ms: u64) {
        let errors = diagnostics.iter().filter(|d| d.is_error()).count();
        tracing::warn!(
            "the saved bundle has {errors} error(s) and was refused; the last good bundle \
             keeps running until they are fixed:"
        );
        for d in &diagnostics {
            tracing::warn!("{d}");
        }
        self.state.reload.refused(diagnostics.clone());
        self.state
            .hub
            .publish(EventKind::BundleRefused(BundleRefused {
                diagnostics,
                changed,
                elapsed_ms,
            }));
    }

    /// The folder is gone: stop watching it and look for it again every second.
    fn folder_missing(&mut self) {
        let was_watching = self.watcher.take().is_some();
        let known = self.state.reload.view().trouble.is_some();
        if !was_watching && known {
            return;
        }
        let message = format!(
            "The bundle folder {} is gone (deleted, renamed or moved). The last good bundle \
             keeps running; put the folder back under that name, or restart Docent with its \
             new place.",
            self.root.display()
        );
        tracing::error!("{message}");
        self.state.reload.trouble(message.clone());
        self.state
            .hub
            .publish(EventKind::BundleWatchFailed(BundleWatchFailed {
                code: "folder-missing".into(),
                message,
            }));
    }

    fn watch_failed(&mut self, message: String) {
        if self.state.reload.view().trouble.as_deref() == Some(message.as_str()) {
            return; // said already (a watcher that keeps failing to start)
        }
        tracing::error!("{message}");
        self.state.reload.trouble(message.clone());
        self.state
            .hub
            .publish(EventKind::BundleWatchFailed(BundleWatchFailed {
                code: "watcher-error".into(),
                message,
            }));
    }
}

fn millis(since: Instant) -> u64 {
    u64::try_from(since.elapsed().as_millis()).unwrap_or(u64::MAX)
}

/// The bundle at `root` and, for one that loaded, the fingerprint of the files it was loaded
/// from (`act.triggered`'s `bundle_hash`): taken before and after the load, which is done
/// again when a save fell between them; `None` when the files kept changing.
fn loaded_with_hash(root: &std::path::Path) -> (LoadReport, Option<String>) {
    let mut tries = 0;
    loop {
        let before = corpus_fingerprint(root);
        let report = load_bundle(root);
        if report.bundle.is_none() {
            return (report, None);
        }
        let after = corpus_fingerprint(root);
        if before == after {
            return (report, after);
        }
        tries += 1;
        if tries == 3 {
            return (report, None);
        }
    }
}
