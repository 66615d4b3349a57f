//! The converter's worker: one file at a time, from the queue, until shutdown; each file
//! hashed, asked of ffprobe, looked up in the cache, and converted there when it is not.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};
use tokio_util::sync::CancellationToken;

use crate::content::{Conversion, ConvertInto};
use crate::events::{EventKind, MediaConverted};
use crate::sync::lock;

use super::{Media, Status, cache, recipe, run};

impl Media {
    /// The worker: converts queued files one after another until shutdown.
    pub(super) async fn work(self: Arc<Self>, shutdown: CancellationToken) {
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
        // The status first, then the event: whoever acts on the event finds the file ready.
        // A newer save of the file may have replaced this conversion meanwhile: then nothing
        // is told of it.
        let shown = &conversion.shown;
        match outcome {
            Ok((file, made)) => {
                let elapsed_ms = u64::try_from(started.elapsed().as_millis()).unwrap_or(u64::MAX);
                let bytes = std::fs::metadata(&file).map_or(0, |m| m.len());
                if !self.set(&conversion.path, cancel, Status::Ready(file)) {
                    return;
                }
                if made {
                    tracing::info!(file = %shown, elapsed_ms, bytes, "media converted");
                    self.publish(EventKind::MediaConverted(MediaConverted {
                        file: shown.clone(),
                        format: conversion.format.to_owned(),
                        elapsed_ms,
                        bytes,
                    }));
                } else {
                    tracing::debug!(file = %shown, "media converted before, taken from the cache");
                }
            }
            Err(reason) => {
                if self.set(&conversion.path, cancel, Status::Failed(reason.clone())) {
                    self.failed(shown, reason);
                }
            }
        }
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
            // Taken again: its time is now, so a browser's copy of another version of the
            // file (`If-Modified-Since`) is never taken for this one.
            cache::touch(&result);
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
        // Scratch files go when this ends, however it ends (a failure, a newer save, shutdown).
        let decoded = Scratch(cache::scratch(&self.cache, &key, "heic.png"));
        let partial = Scratch(cache::partial(&result));
        let (decoded, partial) = (&decoded.0, &partial.0);
        let input = if heic {
            let tool = self
                .tools
                .heif_convert
                .as_deref()
                .unwrap_or(Path::new("heif-convert"));
            run::heif_to_png(tool, &conversion.path, decoded).await?;
            decoded.clone()
        } else {
            conversion.path.clone()
        };
        let args = recipe.ffmpeg_args(&input, partial);
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
        if let Err(said) = converted {
            return Err(format!("ffmpeg cannot convert it ({said})"));
        }
        std::fs::rename(partial, &result)
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
}

/// A file of a conversion in progress, removed when it is dropped (after the rename, there is
/// nothing left to remove).
struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
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
