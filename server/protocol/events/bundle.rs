//! What the corpus says about the bundle being served: a saved bundle gone live or refused,
//! its folder no longer watched (`bundle.*`), and its media converted for Chromium, or not
//! (`media.*`).

use std::borrow::Cow;

use serde::{Deserialize, Serialize};

/// The fields of a `bundle.reloaded` event ([`super::EventKind::BundleReloaded`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct BundleReloaded {
    /// The new bundle's content, `sha256:…`, as in `server.started`.
    pub bundle_hash: Option<String>,
    /// Acts in the new bundle.
    pub acts: usize,
    /// Contexts in the new bundle.
    pub contexts: usize,
    /// Acts the new bundle's pages offer to a touchscreen.
    pub page_acts: usize,
    /// Warnings the check found (errors would have refused it; notes are not counted).
    pub warnings: usize,
    /// Files changed since the last bundle went live, relative to the bundle folder.
    pub changed: Vec<String>,
    /// Milliseconds from the first change seen to the new bundle being live.
    pub elapsed_ms: u64,
    /// Settings changed in `docent.yaml` that take effect only after a restart (or a
    /// reload of a screen), each as a sentence for the operator; empty when none.
    pub not_applied: Vec<String>,
}

/// The fields of a `bundle.refused` event ([`super::EventKind::BundleRefused`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct BundleRefused {
    /// Every problem found, errors, warnings and notes, as `docent check --format json`
    /// gives them.
    /// Not read back (read as empty).
    #[serde(skip_deserializing)]
    pub diagnostics: Vec<docent_content::Diagnostic>,
    /// Files changed since the last bundle went live, relative to the bundle folder.
    pub changed: Vec<String>,
    /// Milliseconds the check took.
    pub elapsed_ms: u64,
}

/// The fields of a `bundle.watch-failed` event ([`super::EventKind::BundleWatchFailed`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct BundleWatchFailed {
    /// `folder-missing` or `watcher-error`.
    pub code: Cow<'static, str>,
    /// What happened and what to do, in plain words.
    pub message: String,
}

/// The fields of a `media.converted` event ([`super::EventKind::MediaConverted`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct MediaConverted {
    /// The file from the bundle folder (`media/Exhibit/video.mpg`).
    pub file: String,
    /// Its format (`MPEG-1/2`, `HEIC`).
    pub format: String,
    /// Milliseconds the conversion took.
    pub elapsed_ms: u64,
    /// The converted file's size in bytes.
    pub bytes: u64,
}

/// The fields of a `media.failed` event ([`super::EventKind::MediaFailed`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct MediaFailed {
    /// The file from the bundle folder.
    pub file: String,
    /// Why, in words, with what to do.
    pub reason: String,
}
