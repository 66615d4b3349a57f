//! Media Chromium cannot show, converted by the real ffmpeg (and libheif for HEIC) when
//! served: films and pictures made here with the same tools, served under their own names as
//! WebM or WebP, kept in the cache across restarts, converted again when the file changes,
//! and, when a file cannot be converted, the reason at its address, in the corpus and in the
//! operator's state. The results are read back with ffprobe.

use std::path::Path;
use std::process::Command;

use docent::events::{EventKind, MediaConverted};
use docent::media::{MediaState, Tools};
use serde_json::Value;

use crate::common;
use common::app::{Answer, TestApp};
use common::{DEADLINE, TempBundle, within};

/// The `docent` binary itself: `check` asking ffmpeg, `serve` saying what it lacks.
mod commands;

/// Runs a media tool to success (ffmpeg, heif-enc), or fails the test with what it said.
fn make(program: &str, args: &[&str]) {
    let output = Command::new(program)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("{program} runs: {e}"));
    assert!(
        output.status.success(),
        "{program} {args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// An MPEG-1 film with MPEG audio, as the paper's `video.mpg`: `seconds` long, a tone of
/// `hz` (so two films differ).
fn mpeg1(path: &Path, seconds: u32, hz: u32) {
    let (seconds, tone) = (seconds.to_string(), format!("sine=frequency={hz}"));
    let path = path.to_str().expect("a UTF-8 path");
    let sources = ["testsrc2=size=176x144:rate=25", &tone];
    let settings = [
        "-t",
        &seconds,
        "-c:v",
        "mpeg1video",
        "-c:a",
        "mp2",
        "-f",
        "mpeg",
        path,
    ];
    ffmpeg_from(&sources, &settings);
}

/// Runs ffmpeg on its own test `sources` (lavfi), with `settings` ending in the output file.
fn ffmpeg_from(sources: &[&str], settings: &[&str]) {
    let mut args = vec!["-v", "error", "-y"];
    for source in sources {
        args.extend(["-f", "lavfi", "-i", source]);
    }
    args.extend(settings);
    make("ffmpeg", &args);
}

/// A QuickTime film cut short, as a copy or a download that stopped half way leaves it: a real
/// film's first 4 KiB (its `ftyp` and the start of its data, none of its index).
fn cut_mov(path: &Path) {
    let whole = path.with_extension("whole.mov");
    let at = whole.to_str().expect("a UTF-8 path");
    let sources = ["testsrc2=size=320x240:rate=25"];
    ffmpeg_from(&sources, &["-t", "1", "-c:v", "mpeg4", at]);
    let bytes = std::fs::read(&whole).expect("read");
    std::fs::write(path, &bytes[..4096]).expect("write");
    std::fs::remove_file(&whole).expect("remove");
}

/// One picture from ffmpeg's test sources (`testsrc2=size=640x480`, `color=c=red:...`) at
/// `path`, in the format its ending names.
fn picture(source: &str, path: &Path) {
    let path = path.to_str().expect("a UTF-8 path");
    ffmpeg_from(&[source], &["-frames:v", "1", path]);
}

/// What ffprobe says of `bytes`: the format name and each stream's codec and size.
fn probe(bytes: &[u8]) -> Value {
    let dir = tempfile::tempdir().expect("temp dir");
    let file = dir.path().join("served");
    std::fs::write(&file, bytes).expect("write");
    let output = Command::new("ffprobe")
        .args(["-v", "error", "-show_entries"])
        .arg("format=format_name:stream=codec_name,codec_type,width,height")
        .args(["-of", "json"])
        .arg(&file)
        .output()
        .expect("ffprobe runs");
    assert!(output.status.success(), "ffprobe reads what was served");
    serde_json::from_slice(&output.stdout).expect("ffprobe's JSON")
}

/// The codecs of the streams ffprobe found.
fn codecs(probed: &Value) -> Vec<&str> {
    (probed["streams"].as_array().expect("streams").iter())
        .filter_map(|s| s["codec_name"].as_str())
        .collect()
}

/// Waits until no planned file is waiting or converting (the worker is done with the plan).
async fn settled(app: &TestApp) -> Vec<docent::media::MediaView> {
    let mut views = app.server().state().media.subscribe();
    let done = views.wait_for(|v| v.iter().all(|m| m.state == MediaState::Failed));
    within(DEADLINE * 4, done)
        .await
        .expect("conversions settle in time")
        .expect("the converter runs")
        .clone()
}

const PROJECTS_THE_FILM: &str = "- Label: RUN_VIDEO_EXHIBIT\n  Text: Let me show you a video.\n  Cmds:\n    - PROJECT Exhibit/video.mpg\n";

/// A bundle projecting `Exhibit/video.mpg`, a real MPEG-1 film of `seconds`; and its path.
fn film_bundle(seconds: u32) -> (TempBundle, std::path::PathBuf) {
    let bundle = TempBundle::new(PROJECTS_THE_FILM);
    let film = bundle.path().join("media/Exhibit/video.mpg");
    std::fs::create_dir_all(film.parent().expect("folder")).expect("mkdir");
    mpeg1(&film, seconds, 440);
    (bundle, film)
}

fn events<'a>(lines: &'a [Value], kind: &str) -> Vec<&'a Value> {
    lines.iter().filter(|l| l["type"] == kind).collect()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_papers_mpeg1_film_is_served_as_webm_under_its_name_and_kept_across_restarts() {
    let (bundle, film) = film_bundle(2);
    let original = std::fs::read(&film).expect("read");
    let cache = tempfile::tempdir().expect("cache");
    let with_cache = |o: &mut docent::serve::ServeOptions| o.media_cache = cache.path().to_owned();

    let app = TestApp::start_with(bundle.path(), with_cache).await;
    assert!(settled(&app).await.is_empty(), "nothing failed");
    let served: Answer = app.get_with("/media/Exhibit/video.mpg", &[]).await;
    assert_eq!(served.status, 200);
    assert_eq!(served.header("content-type"), "video/webm");
    let probed = probe(&served.body);
    assert!(
        probed["format"]["format_name"]
            .as_str()
            .expect("name")
            .contains("webm")
    );
    assert_eq!(codecs(&probed), ["vp9", "opus"]);
    let first = app.stop().await;
    let converted = events(&first, "media.converted");
    assert_eq!(converted.len(), 1, "{converted:?}");
    assert_eq!(converted[0]["file"], "media/Exhibit/video.mpg");
    assert_eq!(converted[0]["format"], "MPEG-1/2");
    assert_eq!(converted[0]["bytes"], served.body.len() as u64);
    assert_eq!(
        std::fs::read(&film).expect("read"),
        original,
        "the original is unchanged"
    );

    // A restart finds the film in the cache: served at once, nothing converted again.
    let app = TestApp::start_with(bundle.path(), with_cache).await;
    assert!(settled(&app).await.is_empty());
    let again = app.get_with("/media/Exhibit/video.mpg", &[]).await;
    assert_eq!(again.body, served.body, "the same converted film");
    let second = app.stop().await;
    assert!(
        events(&second, "media.converted").is_empty(),
        "taken from the cache"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn heic_and_tiff_photos_and_an_oversized_scan_become_webp_that_fits_the_screen() {
    let bundle = TempBundle::new(
        "- Label: PHOTOS\n  Cmds:\n    - PROJECT photo.heic\n    - PROJECT scan.tif\n    - PROJECT wide.png\n",
    );
    let media = bundle.path().join("media");
    let at = |name: &str| media.join(name).to_str().expect("UTF-8").to_owned();
    let png = at("source.png");
    picture("testsrc2=size=640x480", Path::new(&png));
    make("heif-enc", &["-q", "80", &png, "-o", &at("photo.heic")]);
    std::fs::remove_file(&png).expect("remove");
    picture("testsrc2=size=400x300", Path::new(&at("scan.tif")));
    picture("color=c=red:size=5000x300", Path::new(&at("wide.png")));

    let app = TestApp::start(bundle.path()).await;
    assert!(settled(&app).await.is_empty(), "nothing failed");
    let mut sizes = Vec::new();
    for name in ["photo.heic", "scan.tif", "wide.png"] {
        let served = app.get_with(&format!("/media/{name}"), &[]).await;
        assert_eq!(served.status, 200, "{name}");
        assert_eq!(served.header("content-type"), "image/webp", "{name}");
        let probed = probe(&served.body);
        let stream = &probed["streams"][0];
        assert_eq!(stream["codec_name"], "webp", "{name}");
        sizes.push((stream["width"].as_u64(), stream["height"].as_u64()));
    }
    assert_eq!(
        sizes,
        [
            (Some(640), Some(480)),
            (Some(400), Some(300)),
            (Some(3840), Some(230)),
        ],
        "pictures keep their size unless far larger than a screen"
    );
    let lines = app.stop().await;
    assert_eq!(events(&lines, "media.converted").len(), 3);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_film_ffmpeg_cannot_read_fails_at_its_address_with_the_reason_and_is_logged() {
    let bundle = TempBundle::new(PROJECTS_THE_FILM.replace("video.mpg", "cut.mov").as_str());
    std::fs::create_dir_all(bundle.path().join("media/Exhibit")).expect("mkdir");
    cut_mov(&bundle.path().join("media/Exhibit/cut.mov"));
    let app = TestApp::start(bundle.path()).await;
    let failed = settled(&app).await;
    assert_eq!(failed.len(), 1, "{failed:?}");
    assert_eq!(failed[0].file, "media/Exhibit/cut.mov");
    let reason = failed[0].reason.clone().expect("a reason");
    assert!(reason.starts_with("ffmpeg cannot read it ("), "{reason}");

    let answer = app.get_with("/media/Exhibit/cut.mov", &[]).await;
    assert_eq!(answer.status, 422);
    let body = answer.json();
    assert_eq!(body["code"], "media-unconvertible");
    assert_eq!(
        body["error"],
        format!("media/Exhibit/cut.mov cannot be shown: {reason}")
    );
    // The operator's state lists it too (what the console's banner shows).
    let state = app.server().state().state_view();
    assert_eq!(state.reload.media, failed);
    let lines = app.stop().await;
    let logged = events(&lines, "media.failed");
    assert_eq!(logged.len(), 1);
    assert_eq!(logged[0]["reason"], reason.as_str());
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn without_ffmpeg_the_film_fails_with_what_to_do_in_the_corpus_and_at_its_address() {
    let (bundle, _) = film_bundle(1);
    let app = TestApp::start_with(bundle.path(), |o| o.media_tools = Tools::default()).await;
    let answer = app.get_with("/media/Exhibit/video.mpg", &[]).await;
    assert_eq!(answer.status, 422);
    assert!(
        answer.json()["error"]
            .as_str()
            .is_some_and(|e| e.contains("ffmpeg is not installed")),
        "{}",
        answer.json()
    );
    let lines = app.stop().await;
    let failed = events(&lines, "media.failed");
    assert_eq!(failed.len(), 1, "{failed:?}");
    assert_eq!(failed[0]["file"], "media/Exhibit/video.mpg");
    let reason = failed[0]["reason"].as_str().expect("a reason");
    assert!(reason.contains("sudo apt install ffmpeg"), "{reason}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_film_replaced_while_serving_is_converted_again_and_its_new_content_served() {
    let (bundle, film) = film_bundle(1);
    let app = TestApp::start(bundle.path()).await;
    assert!(settled(&app).await.is_empty());
    let before = app.get_with("/media/Exhibit/video.mpg", &[]).await.body;

    // The author exports a longer film under the same name; live reload takes the new bundle.
    // The first film's `media.converted` may still be told after it is served: the one
    // awaited is the new film's, longer, so of another size.
    let mut events_seen = app.server().state().hub.subscribe();
    app.server().watch(docent::reload::ReloadOptions::default());
    let replacement = bundle.path().join("new.mpg");
    mpeg1(&replacement, 2, 880);
    std::fs::rename(&replacement, &film).expect("replace the film");
    let first_size = before.len() as u64;
    let converted = async {
        loop {
            let event = events_seen.recv().await.expect("the hub runs");
            if let EventKind::MediaConverted(MediaConverted { bytes, .. }) = event.kind
                && bytes != first_size
            {
                return;
            }
        }
    };
    within(DEADLINE * 4, converted)
        .await
        .expect("the changed film is converted again");
    let after = app.get_with("/media/Exhibit/video.mpg", &[]).await;
    assert_eq!(after.status, 200);
    assert_ne!(after.body, before, "the new film is served");
    let lines = app.stop().await;
    assert_eq!(events(&lines, "media.converted").len(), 2);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_kiosk_reloads_the_pages_that_show_a_picture_once_it_is_converted() {
    // Two pages show the scan; a third does not. A new scan is saved while a kiosk is
    // connected: live reload names the file, and once it is converted the kiosk is told
    // the two pages, so one showing it fetches the picture that was missing meanwhile.
    let scan_page = |title: &str| {
        format!("<!doctype html><title>{title}</title><img src=\"images/scan.tif\" alt=\"scan\">")
    };
    let bundle = TempBundle::new("- Label: A\n  Text: Hi\n")
        .with_file("pages/index.html", &scan_page("home"))
        .with_file("pages/room.html", &scan_page("room"))
        .with_file("pages/other.html", "<!doctype html><title>other</title>");
    let tif = |name: &str, size: &str| {
        picture(&format!("testsrc2=size={size}"), &bundle.path().join(name));
    };
    std::fs::create_dir_all(bundle.path().join("pages/images")).expect("mkdir");
    tif("pages/images/scan.tif", "200x100");
    let watch = |server: &docent::serve::Server| {
        server.watch(docent::reload::ReloadOptions::default());
    };
    let converter = std::sync::Arc::new(std::sync::Mutex::new(None));
    let keep = std::sync::Arc::clone(&converter);
    let prepare = |server: &docent::serve::Server| {
        *keep.lock().expect("lock") = Some(std::sync::Arc::clone(&server.state().media));
        watch(server);
    };
    let server = common::TestServer::start_prepared(bundle.path(), |_| {}, prepare).await;
    // The first scan is converted before the kiosk comes: its `changed` is not the one awaited.
    let media = converter
        .lock()
        .expect("lock")
        .take()
        .expect("the converter");
    let mut views = media.subscribe();
    within(DEADLINE, views.wait_for(Vec::is_empty))
        .await
        .expect("the first scan is converted")
        .expect("the converter runs");
    let mut kiosk = server
        .client(serde_json::json!({"type": "hello", "role": "kiosk"}))
        .await;
    tif("new-scan.tif", "300x150");
    std::fs::rename(
        bundle.path().join("new-scan.tif"),
        bundle.path().join("pages/images/scan.tif"),
    )
    .expect("save the new scan");
    // Live reload names the saved file first; the pages follow once it is converted (a
    // `changed` for the first scan, told late, comes before both and is passed over).
    let saved = serde_json::json!(["images/scan.tif"]);
    kiosk
        .recv_where(|f| f["type"] == "changed" && f["pages"] == saved)
        .await;
    let ready = kiosk
        .recv_where(|f| f["type"] == "changed" && f["pages"] != saved)
        .await;
    assert_eq!(
        ready["pages"],
        serde_json::json!(["index.html", "room.html"])
    );
    assert_eq!(ready["shell"], false);
    let served = reqwest::get(server.url("/pages/images/scan.tif"))
        .await
        .expect("an answer")
        .bytes()
        .await
        .expect("a body");
    let stream = &probe(&served)["streams"][0];
    assert_eq!(
        (
            stream["codec_name"].as_str(),
            stream["width"].as_u64(),
            stream["height"].as_u64()
        ),
        (Some("webp"), Some(300), Some(150)),
        "the new scan, converted"
    );
    server.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_film_still_converting_is_answered_503_with_how_far_it_is() {
    // An ffmpeg that takes its time (the real ffprobe says what the film holds): the film
    // stays converting while it is asked for, and the answer says so.
    let (bundle, _) = film_bundle(1);
    let slow = tempfile::tempdir().expect("a folder for the slow ffmpeg");
    let ffmpeg = slow.path().join("ffmpeg");
    std::fs::write(&ffmpeg, "#!/bin/sh\nexec sleep 60\n").expect("write");
    let mut mode = std::fs::metadata(&ffmpeg).expect("meta").permissions();
    std::os::unix::fs::PermissionsExt::set_mode(&mut mode, 0o755);
    std::fs::set_permissions(&ffmpeg, mode).expect("chmod");
    let tools = Tools {
        ffmpeg: Some(ffmpeg),
        ..Tools::find()
    };
    let app = TestApp::start_with(bundle.path(), |o| o.media_tools = tools).await;
    let mut views = app.server().state().media.subscribe();
    let converting = views.wait_for(|v| v.iter().any(|m| m.state == MediaState::Converting));
    within(DEADLINE, converting)
        .await
        .expect("it starts converting")
        .expect("the converter runs");
    let answer = app.get_with("/media/Exhibit/video.mpg", &[]).await;
    assert_eq!(answer.status, 503);
    assert_eq!(answer.header("retry-after"), "5");
    assert_eq!(answer.json()["code"], "media-converting");
    assert_eq!(
        answer.json()["error"],
        "media/Exhibit/video.mpg is still being converted for Chromium; try again when it is done"
    );
    // Shutdown does not wait for the conversion (ffmpeg is started with `kill_on_drop`).
    app.stop().await;
}
