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

use std::collections::{HashMap, VecDeque};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Instant, SystemTime};

use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use tokio::sync::{Notify, watch};
use tokio_util::sync::CancellationToken;

use crate::content::{Bundle, Conversion, ConvertInto};
use crate::events::{EventKind, Hub};
use crate::lifecycle::Lifecycle;
use crate::sync::lock;
pub use cache::default_folder;
pub use docent_protocol::state::{MediaState, MediaView};
pub use probe::check_decodable;
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

    /// Takes the conversions of `bundle` (the live one): new or changed files are queued,
    /// files no longer planned are forgotten (their running conversion stopped).
    pub fn plan(&self, bundle: &Bundle) {
        let mut entries = lock(&self.entries);
        let mut queued = Vec::new();
        entries.retain(|path, entry| {
            let kept = bundle.conversions.iter().any(|c| &c.path == path);
            if !kept {
                entry.cancel.cancel();
            }
            kept
        });
        for conversion in &bundle.conversions {
            let stamp = stamp_of(&conversion.path);
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
                Some(reason) => Status::Failed(reason),
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

    /// What to tell the person starting Docent: files that will not show, and why.
    pub fn startup_warnings(&self) -> Vec<String> {
        let entries = lock(&self.entries);
        let mut failed: Vec<(&str, &str)> = (entries.values())
            .filter_map(|e| match &e.status {
                Status::Failed(reason) => Some((e.conversion.shown.as_str(), reason.as_str())),
                _ => None,
            })
            .collect();
        failed.sort_unstable();
        failed
            .into_iter()
            .map(|(shown, reason)| format!("{shown} will not be shown: {reason}"))
            .collect()
    }

    /// The worker: converts queued files one after another until shutdown.
    async fn work(self: Arc<Self>, shutdown: CancellationToken) {
        loop {
            let next = lock(&self.queue).pop_front();
            let Some(path) = next else {
                tokio::select! {
                    () = shutdown.cancelled() => return,
                    () = self.wake.notified() => continue,
                }
            };
            let job = {
                let entries = lock(&self.entries);
                (entries.get(&path))
                    .filter(|e| e.status == Status::Waiting)
                    .map(|e| (e.conversion.clone(), e.cancel.clone()))
            };
            let Some((conversion, cancel)) = job else {
                continue;
            };
            tokio::select! {
                () = shutdown.cancelled() => return,
                () = cancel.cancelled() => {}
                () = self.convert(&conversion, &cancel) => {}
            }
        }
    }

    /// Converts one file and records the outcome, unless it was cancelled meanwhile.
    async fn convert(&self, conversion: &Conversion, cancel: &CancellationToken) {
        let started = Instant::now();
        let bar = Bar(self.bar(conversion));
        let outcome = self.produce(conversion, cancel, &bar.0).await;
        drop(bar);
        if cancel.is_cancelled() {
            return;
        }
        let shown = &conversion.shown;
        let status = match outcome {
            Ok((file, made)) => {
                let elapsed_ms = u64::try_from(started.elapsed().as_millis()).unwrap_or(u64::MAX);
                let bytes = std::fs::metadata(&file).map_or(0, |m| m.len());
                if made {
                    tracing::info!(file = %shown, elapsed_ms, bytes, "media converted");
                    self.publish(EventKind::MediaConverted {
                        file: shown.clone(),
                        format: conversion.format.to_owned(),
                        elapsed_ms,
                        bytes,
                    });
                } else {
                    tracing::debug!(file = %shown, "media converted before, taken from the cache");
                }
                Status::Ready(file)
            }
            Err(reason) => {
                tracing::warn!("{shown} cannot be shown: {reason}");
                self.publish(EventKind::MediaFailed {
                    file: shown.clone(),
                    reason: reason.clone(),
                });
                Status::Failed(reason)
            }
        };
        self.set(&conversion.path, cancel, status);
    }

    /// The converted file and whether it was made now (else found in the cache).
    async fn produce(
        &self,
        conversion: &Conversion,
        cancel: &CancellationToken,
        bar: &ProgressBar,
    ) -> Result<(PathBuf, bool), String> {
        let (Some(ffmpeg), Some(ffprobe)) = (&self.tools.ffmpeg, &self.tools.ffprobe) else {
            return Err(self
                .tools
                .missing_for(conversion.format)
                .unwrap_or_default());
        };
        let source = conversion.path.clone();
        let key = tokio::task::spawn_blocking(move || cache::content_key(&source))
            .await
            .map_err(|e| format!("reading it failed: {e}"))?
            .map_err(|e| format!("it cannot be read: {e}"))?;
        let heic = conversion.format == "HEIC";
        let probe = if heic || conversion.into == ConvertInto::Picture {
            recipe::Probe::default()
        } else {
            recipe::probe(ffprobe, &conversion.path)
                .await
                .map_err(|said| format!("ffmpeg cannot read it ({said})"))?
        };
        let recipe = recipe::choose(conversion.into, &probe);
        let result = self
            .cache
            .join(cache::cached_name(&key, recipe.name(), recipe.ext()));
        if result.is_file() {
            return Ok((result, false));
        }
        std::fs::create_dir_all(&self.cache).map_err(|e| {
            format!(
                "the media cache {} cannot be made: {e}",
                self.cache.display()
            )
        })?;
        self.set(
            &conversion.path,
            cancel,
            Status::Converting { percent: None },
        );
        let decoded = self.cache.join(format!("{key}.heic.png"));
        let input = if heic {
            let tool = self
                .tools
                .heif_convert
                .as_deref()
                .unwrap_or(Path::new("heif-convert"));
            run::heif_to_png(tool, &conversion.path, &decoded).await?;
            decoded.clone()
        } else {
            conversion.path.clone()
        };
        let partial = cache::partial(&result);
        let args = recipe.ffmpeg_args(&input, &partial);
        let mut shown_percent = None;
        let converted = run::ffmpeg(ffmpeg, &args, probe.duration, |fraction| {
            bar.set_position((fraction * 1000.0) as u64);
            let percent = Some((fraction * 100.0) as u8);
            if percent != shown_percent {
                shown_percent = percent;
                self.set(&conversion.path, cancel, Status::Converting { percent });
            }
        })
        .await;
        if heic {
            let _ = std::fs::remove_file(&decoded);
        }
        if let Err(said) = converted {
            let _ = std::fs::remove_file(&partial);
            return Err(format!("ffmpeg cannot convert it ({said})"));
        }
        std::fs::rename(&partial, &result)
            .map_err(|e| format!("the converted file cannot be kept in the cache: {e}"))?;
        Ok((result, true))
    }

    /// A progress bar on the terminal (drawn only when standard error is one).
    fn bar(&self, conversion: &Conversion) -> ProgressBar {
        let bar = self.bars.add(ProgressBar::new(1000));
        let style = ProgressStyle::with_template(
            "converting {msg} [{bar:30}] {percent:>3} % ({elapsed}, {eta} left)",
        )
        .map(|s| s.progress_chars("=> "));
        if let Ok(style) = style {
            bar.set_style(style);
        }
        bar.set_message(conversion.shown.clone());
        bar
    }

    /// Sets the status of the entry at `path`, if it is still the one `cancel` belongs to.
    fn set(&self, path: &Path, cancel: &CancellationToken, status: Status) {
        let mut entries = lock(&self.entries);
        let Some(entry) = entries.get_mut(path) else {
            return;
        };
        if cancel.is_cancelled() || entry.status == status {
            return;
        }
        entry.status = status;
        let views = views_of(&entries);
        drop(entries);
        self.views.send_replace(views);
    }

    fn publish(&self, kind: EventKind) {
        if let Some(hub) = &self.hub {
            hub.publish(kind);
        }
    }
}

/// A progress bar cleared from the terminal when dropped, also when its conversion is
/// stopped half way.
struct Bar(ProgressBar);

impl Drop for Bar {
    fn drop(&mut self) {
        self.0.finish_and_clear();
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
