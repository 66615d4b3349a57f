//! Benchmark of media conversion: how long Docent takes to make the paper's Fig. 4 film and a
//! two-minute 1080p QuickTime film playable, and how much the media cache holds, side by side
//! with the floor: ffmpeg alone doing the same conversion. Then the same bundle started again
//! on the same cache (a restart): the time until every film is served. Run with
//! `cargo run --release --example media-bench -- [--seconds 120] [--runs 1]`.
//!
//! Films: `fig4.mpg` is `dialogs/paper-fig4/media/Exhibit/video.mpg` (MPEG-1, 640x360, 4 s);
//! `phone.mov` is H.264 + AAC in QuickTime, as a phone films (only re-packed); `camera.mov` is
//! MPEG-4 part 2 + PCM sound in QuickTime, as older cameras film (converted to VP9 + Opus).
//! The two `.mov` are made here with ffmpeg (testsrc2, 1920x1080, 30 fps).

use std::path::Path;
use std::process::Command;
use std::sync::Arc;
use std::time::{Duration, Instant};

use docent::content::load_bundle;
use docent::events::Hub;
use docent::lifecycle::Lifecycle;
use docent::media::{Media, Recipe, Tools};

fn main() -> std::io::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let arg = |name: &str, default: u64| {
        (args.iter().position(|a| a == name))
            .and_then(|i| args.get(i + 1))
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let seconds = arg("--seconds", 120);
    let root = std::env::temp_dir().join(format!("docent-media-bench-{}", std::process::id()));
    let media = root.join("films");
    std::fs::create_dir_all(&media)?;
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::copy(
        repo.join("dialogs/paper-fig4/media/Exhibit/video.mpg"),
        media.join("fig4.mpg"),
    )?;
    let secs = seconds.to_string();
    let source = [
        "-f",
        "lavfi",
        "-i",
        "testsrc2=size=1920x1080:rate=30",
        "-f",
        "lavfi",
        "-i",
    ];
    let made = Instant::now();
    ffmpeg(
        &[
            &source[..],
            &["sine=frequency=440:sample_rate=48000", "-t", &secs],
        ]
        .concat(),
        &[
            "-c:v", "libx264", "-preset", "veryfast", "-crf", "20", "-pix_fmt", "yuv420p", "-c:a",
            "aac",
        ],
        &media.join("phone.mov"),
    );
    ffmpeg(
        &[
            &source[..],
            &["sine=frequency=440:sample_rate=48000", "-t", &secs],
        ]
        .concat(),
        &["-c:v", "mpeg4", "-q:v", "4", "-c:a", "pcm_s16le"],
        &media.join("camera.mov"),
    );
    eprintln!("made the films in {:.1} s", made.elapsed().as_secs_f64());

    println!(
        "| film | size | Docent converts | ffmpeg alone (floor) | cached result | restart: served after |"
    );
    println!("| --- | --- | --- | --- | --- | --- |");
    for film in ["fig4.mpg", "phone.mov", "camera.mov"] {
        let bundle = root.join(format!("only-{film}"));
        std::fs::create_dir_all(bundle.join("media"))?;
        std::fs::copy(media.join(film), bundle.join("media").join(film))?;
        std::fs::write(
            bundle.join("acts.yaml"),
            format!("- Label: FILM\n  Cmds:\n    - PROJECT {film}\n"),
        )?;
        let cache = root.join(format!("cache-{film}"));
        let first = convert(&bundle, &cache);
        let cached = folder_size(&cache);
        let again = convert(&bundle, &cache);
        let floor = floor(&media.join(film), &root.join(format!("floor-{film}")));
        let size = std::fs::metadata(media.join(film))?.len();
        println!(
            "| {film} | {:.1} MB | {:.2} s | {:.2} s | {:.1} MB | {:.3} s |",
            mb(size),
            first.as_secs_f64(),
            floor.as_secs_f64(),
            mb(cached),
            again.as_secs_f64()
        );
    }
    std::fs::remove_dir_all(&root)?;
    Ok(())
}

/// The time from starting a converter on `bundle` with `cache` until every film is ready.
fn convert(bundle: &Path, cache: &Path) -> Duration {
    let runtime = tokio::runtime::Runtime::new().expect("a runtime");
    runtime.block_on(async {
        let report = load_bundle(bundle);
        let bundle = report.bundle.expect("the bench bundle loads");
        let (hub, _feed) = Hub::new();
        let life = Lifecycle::new();
        let started = Instant::now();
        let media: Arc<Media> = Media::start(cache.to_owned(), Tools::find(), hub, &life);
        media.plan(&bundle);
        let mut views = media.subscribe();
        let ready = views
            .wait_for(Vec::is_empty)
            .await
            .map(|_| started.elapsed());
        let failed = media.views();
        assert!(failed.is_empty(), "conversions failed: {failed:?}");
        life.shutdown.cancel();
        ready.expect("the converter runs")
    })
}

/// ffmpeg alone, with the command Docent runs for this film ([`Recipe::ffmpeg_args`]).
fn floor(film: &Path, out: &Path) -> Duration {
    let name = film
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or_default();
    let recipe = if name == "phone.mov" {
        Recipe::RepackMp4
    } else {
        Recipe::Vp9
    };
    let started = Instant::now();
    let status = Command::new("ffmpeg")
        .args(recipe.ffmpeg_args(film, out))
        .stdout(std::process::Stdio::null())
        .status()
        .expect("ffmpeg runs");
    assert!(status.success(), "ffmpeg failed on {}", film.display());
    started.elapsed()
}

fn ffmpeg(input: &[&str], settings: &[&str], out: &Path) {
    let status = Command::new("ffmpeg")
        .args(["-nostdin", "-v", "error", "-y"])
        .args(input)
        .args(settings)
        .arg(out)
        .status()
        .expect("ffmpeg runs");
    assert!(status.success(), "ffmpeg failed on {}", out.display());
}

fn folder_size(dir: &Path) -> u64 {
    (std::fs::read_dir(dir).into_iter().flatten().flatten())
        .filter_map(|e| e.metadata().ok())
        .map(|m| m.len())
        .sum()
}

fn mb(bytes: u64) -> f64 {
    bytes as f64 / 1_000_000.0
}
