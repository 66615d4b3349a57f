//! Media conversion: the files the content check planned (`Bundle::conversions`: formats
//! Chromium cannot show, pictures far larger than any screen) are converted once with ffmpeg
//! in the background, one at a time, kept in the media cache by content ([`cache`]), and
//! served under their own names by `/media/` and `/pages/` ([`Media::lookup`]). Live reload
//! hands every new bundle to [`Media::plan`]: a file that changed is converted again, one
//! that is gone is forgotten. Operators see what is converting or failed (`state.reload.media`
//! and the `media` frame); the terminal shows progress bars; the corpus gets
//! `media.converted` and `media.failed`. The original file is never changed.

mod cache;
mod probe;
mod recipe;
mod run;
mod worker;

use std::collections::{HashMap, VecDeque};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::SystemTime;

use indicatif::MultiProgress;
use tokio::sync::{Notify, watch};
use tokio_util::sync::CancellationToken;

use crate::content::{Bundle, Conversion};
use crate::events::{EventKind, Hub, MediaFailed};
use crate::lifecycle::Lifecycle;
use crate::sync::lock;
pub use cache::default_folder;
pub use docent_protocol::state::{MediaState, MediaView};
pub use probe::check_decodable;
pub use recipe::Recipe;
pub use run::Tools;

/// How a file of the bundle is served.
#[derive(Debug, PartialEq)]
pub enum Served {
    /// As it is: nothing to convert.
    Original,
    /// The converted file in the cache.
    Converted(PathBuf),
    /// Not yet: it is waiting or converting; the reason says how far it is.
    NotYet(String),
    /// Never, until the file is replaced: the reason says why and what to do.
    Failed(String),
}

/// One planned file.
struct Entry {
    conversion: Conversion,
    /// The file's size and modification time when planned: a different one is a new file.
    stamp: Option<(u64, SystemTime)>,
    status: Status,
    /// Cancels the running conversion when the file changes or leaves the bundle.
    cancel: CancellationToken,
}

#[derive(Clone, Debug, PartialEq)]
enum Status {
    Waiting,
    Converting { percent: Option<u8> },
    Ready(PathBuf),
    Failed(String),
}

/// The converter: the media cache, the queue, and what each planned file has become.
pub struct Media {
    cache: PathBuf,
    tools: Tools,
    entries: Mutex<HashMap<PathBuf, Entry>>,
    queue: Mutex<VecDeque<PathBuf>>,
    wake: Notify,
    views: watch::Sender<Vec<MediaView>>,
    hub: Option<Hub>,
    bars: MultiProgress,
}

impl Media {
    /// A converter writing to `cache`, using `tools`, its worker run by `life`; events go to
    /// `hub`.
    pub fn start(cache: PathBuf, tools: Tools, hub: Hub, life: &Lifecycle) -> Arc<Media> {
        cache::sweep(&cache);
        let media = Arc::new(Media::new(cache, tools, Some(hub)));
        let worker = Arc::clone(&media).work(life.shutdown.clone());
        life.spawn(worker);
        media
    }

    /// A converter that converts nothing (no worker): for state built without a server.
    pub fn idle() -> Arc<Media> {
        Arc::new(Media::new(std::env::temp_dir(), Tools::default(), None))
    }

    fn new(cache: PathBuf, tools: Tools, hub: Option<Hub>) -> Media {
        Media {
            cache,
            tools,
            entries: Mutex::default(),
            queue: Mutex::default(),
            wake: Notify::new(),
            views: watch::Sender::new(Vec::new()),
            hub,
            bars: MultiProgress::new(),
        }
    }

    /// The cache folder.
    pub fn cache(&self) -> &Path {
        &self.cache
    }

    /// Takes the conversions of `bundle` (the live one, before it goes live): new or changed
    /// files are queued, files no longer planned are forgotten (their running conversion
    /// stopped). A file the converters missing here cannot convert fails at once, told in the
    /// log and the corpus.
    pub fn plan(&self, bundle: &Bundle) {
        // The files' times are read before the lock: lookups from requests never wait on disk.
        let stamps: Vec<_> = (bundle.conversions.iter())
            .map(|c| stamp_of(&c.path))
            .collect();
        let mut entries = lock(&self.entries);
        let (mut queued, mut failed) = (Vec::new(), Vec::new());
        entries.retain(|path, entry| {
            let kept = bundle.conversions.iter().any(|c| &c.path == path);
            if !kept {
                entry.cancel.cancel();
            }
            kept
        });
        for (conversion, stamp) in bundle.conversions.iter().zip(stamps) {
            if let Some(entry) = entries.get_mut(&conversion.path) {
                // The same file as before: converted, converting, or failed (a failure is not
                // retried until the file changes).
                let same = entry.stamp == stamp && entry.conversion.into == conversion.into;
                if same {
                    entry.conversion = conversion.clone();
                    continue;
                }
                entry.cancel.cancel();
            }
            let status = match self.tools.missing_for(conversion.format) {
                Some(reason) => {
                    failed.push((conversion.shown.clone(), reason.clone()));
                    Status::Failed(reason)
                }
                None => {
                    queued.push(conversion.path.clone());
                    Status::Waiting
                }
            };
            let entry = Entry {
                conversion: conversion.clone(),
                stamp,
                status,
                cancel: CancellationToken::new(),
            };
            entries.insert(conversion.path.clone(), entry);
        }
        let views = views_of(&entries);
        drop(entries);
        if !queued.is_empty() {
            let mut queue = lock(&self.queue);
            queue.retain(|p| !queued.contains(p));
            queue.extend(queued);
            self.wake.notify_one();
        }
        self.views.send_replace(views);
        for (shown, reason) in failed {
            self.failed(&shown, reason);
        }
    }

    /// How the file at `path` (as resolved in the bundle) is served.
    pub fn lookup(&self, path: &Path) -> Served {
        let entries = lock(&self.entries);
        let Some(entry) = entries.get(path) else {
            return Served::Original;
        };
        let shown = &entry.conversion.shown;
        match &entry.status {
            Status::Ready(file) => Served::Converted(file.clone()),
            Status::Failed(reason) => Served::Failed(format!("{shown} cannot be shown: {reason}")),
            Status::Waiting => Served::NotYet(format!(
                "{shown} is waiting to be converted for Chromium ({}); try again in a moment",
                entry.conversion.format
            )),
            Status::Converting { percent } => Served::NotYet(format!(
                "{shown} is still being converted for Chromium{}; try again when it is done",
                percent.map_or(String::new(), |p| format!(" ({p} % done)"))
            )),
        }
    }

    /// The files still converting or failed, for operators.
    pub fn views(&self) -> Vec<MediaView> {
        self.views.borrow().clone()
    }

    /// Follows [`views`](Self::views) as it changes.
    pub fn subscribe(&self) -> watch::Receiver<Vec<MediaView>> {
        self.views.subscribe()
    }

    /// Sets the status of the entry at `path`, if it is still the one `cancel` belongs to;
    /// false when a newer plan replaced or dropped it (then nothing is to be told of it).
    fn set(&self, path: &Path, cancel: &CancellationToken, status: Status) -> bool {
        let mut entries = lock(&self.entries);
        let Some(entry) = entries.get_mut(path) else {
            return false;
        };
        // `plan` cancels under this same lock: a status set here is never a stale one.
        if cancel.is_cancelled() {
            return false;
        }
        if entry.status != status {
            entry.status = status;
            let views = views_of(&entries);
            drop(entries);
            self.views.send_replace(views);
        }
        true
    }

    /// Tells the log and the corpus that `shown` cannot be shown, and why.
    fn failed(&self, shown: &str, reason: String) {
        tracing::warn!("{shown} will not be shown: {reason}");
        self.publish(EventKind::MediaFailed(MediaFailed {
            file: shown.to_owned(),
            reason,
        }));
    }

    fn publish(&self, kind: EventKind) {
        if let Some(hub) = &self.hub {
            hub.publish(kind);
        }
    }
}

/// The size and modification time of `path`, when it can be read.
fn stamp_of(path: &Path) -> Option<(u64, SystemTime)> {
    let meta = std::fs::metadata(path).ok()?;
    Some((meta.len(), meta.modified().ok()?))
}

/// What operators are shown: files not ready, in the order of the bundle.
fn views_of(entries: &HashMap<PathBuf, Entry>) -> Vec<MediaView> {
    let mut views: Vec<(&Conversion, MediaView)> = (entries.values())
        .filter_map(|e| {
            let (state, percent, reason) = match &e.status {
                Status::Ready(_) => return None,
                Status::Waiting => (MediaState::Waiting, None, None),
                Status::Converting { percent } => (MediaState::Converting, *percent, None),
                Status::Failed(reason) => (MediaState::Failed, None, Some(reason.clone())),
            };
            let view = MediaView {
                file: e.conversion.shown.clone(),
                format: e.conversion.format.to_owned(),
                state,
                percent,
                reason,
            };
            Some((&e.conversion, view))
        })
        .collect();
    views.sort_by(|a, b| (&a.0.pos, &a.0.shown).cmp(&(&b.0.pos, &b.0.shown)));
    views.into_iter().map(|(_, view)| view).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bundle projecting `film.mpg` (its content `bytes`), loaded.
    fn bundle_with_film(dir: &Path, bytes: &[u8]) -> Bundle {
        std::fs::create_dir_all(dir.join("media")).expect("media");
        std::fs::write(dir.join("media/film.mpg"), bytes).expect("film");
        std::fs::write(
            dir.join("acts.yaml"),
            "- Label: A\n  Cmds: [PROJECT film.mpg]\n",
        )
        .expect("acts");
        crate::content::load_bundle(dir).bundle.expect("loads")
    }

    /// Converters that are there (never run here: this converter has no worker).
    fn present() -> Tools {
        let tool = Some(PathBuf::from("/usr/bin/true"));
        Tools {
            ffmpeg: tool.clone(),
            ffprobe: tool.clone(),
            heif_convert: tool,
        }
    }

    #[test]
    fn a_planned_file_waits_says_so_and_is_forgotten_when_the_bundle_drops_it() {
        let dir = tempfile::tempdir().expect("temp dir");
        let bundle = bundle_with_film(dir.path(), b"\0\0\x01\xba first");
        let media = Media::new(dir.path().join("cache"), present(), None);
        media.plan(&bundle);
        let path = &bundle.conversions[0].path.clone();
        let Served::NotYet(reason) = media.lookup(path) else {
            panic!("waiting: {:?}", media.lookup(path));
        };
        assert_eq!(
            reason,
            "media/film.mpg is waiting to be converted for Chromium (MPEG-1/2); try again in a \
             moment"
        );
        assert_eq!(media.views()[0].state, MediaState::Waiting);
        assert_eq!(lock(&media.queue).len(), 1);

        // Planned again unchanged: nothing queued twice.
        media.plan(&bundle);
        assert_eq!(lock(&media.queue).len(), 1);
        let cancel = lock(&media.entries)[path].cancel.clone();
        media.set(path, &cancel, Status::Converting { percent: Some(45) });
        let Served::NotYet(reason) = media.lookup(path) else {
            panic!("converting");
        };
        assert!(
            reason.ends_with("(45 % done); try again when it is done"),
            "{reason}"
        );

        // The film changed on disk: the running conversion is stopped, the file queued again.
        std::fs::write(path, b"\0\0\x01\xba second, longer").expect("save");
        media.plan(&bundle);
        assert!(cancel.is_cancelled());
        assert_eq!(media.views()[0].state, MediaState::Waiting);

        // A bundle without it: forgotten, served as it is (nothing to convert).
        let mut bundle = bundle;
        bundle.conversions.clear();
        media.plan(&bundle);
        assert_eq!(media.lookup(path), Served::Original);
        assert!(media.views().is_empty());
    }

    #[test]
    fn without_ffmpeg_a_planned_file_fails_at_once_with_what_to_install() {
        let dir = tempfile::tempdir().expect("temp dir");
        let bundle = bundle_with_film(dir.path(), b"\0\0\x01\xba film");
        let media = Media::new(dir.path().join("cache"), Tools::default(), None);
        media.plan(&bundle);
        let Served::Failed(reason) = media.lookup(&bundle.conversions[0].path) else {
            panic!("failed");
        };
        assert!(reason.contains("sudo apt install ffmpeg"), "{reason}");
        assert!(lock(&media.queue).is_empty(), "nothing to queue");
    }
}
