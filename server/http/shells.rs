//! The two browser shells the server renders itself: the touchscreen kiosk at `/` and the
//! projector at `/projector`. Each is an askama template in `pages/`; its struct's fields are
//! everything the page's script needs (handed over as `data-` attributes on `<body>`).

use askama::Template;
use axum::extract::State;
use axum::http::header;
use axum::response::{IntoResponse, Response};

use crate::content::Languages;
use crate::content::config::{AdapterKind, Camera, SiteConfig};
use crate::content::shell_strings::{ShellString, shell_table};
use crate::http::AppError;
use crate::http::missing_page::MissingPage;
use crate::state::AppState;

/// The websocket every shell connects to.
const WS_PATH: &str = "/ws";

/// `pages/kiosk/shell.html`: the touchscreen shell.
#[derive(Template)]
#[template(path = "kiosk/shell.html")]
pub struct KioskShell<'a> {
    /// Websocket path, e.g. `/ws`.
    pub ws_path: &'a str,
    /// Where content pages are served, with a trailing slash: `/pages/`.
    pub pages_path: &'a str,
    /// The bundle's home page, relative to `pages/`.
    pub home: &'a str,
    /// The bundle's languages separated by spaces, the default first (`en de`): pages in
    /// another language are shown from its folder (`pages/de/`).
    pub languages: String,
    /// Each language's folder under `pages/` (`{"en": "", "de": "de/"}`), as the server
    /// resolves it (`Languages::page_folder`), for `static/language.js`.
    pub page_folders: String,
    /// Milliseconds without touch before returning home; 0 disables.
    pub idle_ms: u128,
    /// The act triggered on going idle, if any.
    pub idle_act: Option<&'a str>,
    /// `kiosk: attract:` as JSON for `static/attract.js`; empty when there is none.
    pub attract: String,
    /// Whether the bundle has `schedule:`: the shell then asks `GET /api/schedule/{at}` what
    /// to show by its clock (`static/schedule.js`).
    pub schedule: bool,
    /// Whether the kiosk speaks `SAY` itself (`speech: {adapter: browser}`).
    pub browser_speech: bool,
    /// Voice (a language tag or voice name) for browser speech.
    pub voice: &'a str,
    /// Words per minute for browser speech.
    pub rate: u32,
    /// Whether the kiosk answers the operator console's camera calls (`operator.camera: webrtc`).
    pub webrtc_camera: bool,
    /// The friendly "not available" page (`pages/missing/missing.html`), shown in place of a
    /// page the browser could not load at all; empty: the browser's own error screen.
    pub unavailable_page: &'a str,
    /// Every word the shell shows visitors, by key, by declared language, as JSON for
    /// `static/shell-text.js` (`content::shell_strings`: built in, and `kiosk: strings:`).
    pub strings: String,
    /// The bundle's default language: that of `starting` and `stop`.
    pub default_language: &'a str,
    /// "Starting…" in the default language, until the shell's script runs.
    pub starting: String,
    /// The Stop button's label in the default language, until the shell's script runs.
    pub stop: String,
}

impl<'a> KioskShell<'a> {
    /// The shell for a bundle with these settings, showing `unavailable_page` when a page
    /// cannot be loaded.
    pub fn new(config: &'a SiteConfig, unavailable_page: &'a str) -> Self {
        KioskShell {
            ws_path: WS_PATH,
            pages_path: "/pages/",
            home: &config.home,
            languages: (config.languages.all().iter())
                .map(|language| language.as_str())
                .collect::<Vec<_>>()
                .join(" "),
            page_folders: page_folders(&config.languages),
            idle_ms: config.kiosk.idle.as_millis(),
            idle_act: config.kiosk.idle_act.as_deref(),
            attract: json_or_empty(config.kiosk.attract.as_ref()),
            schedule: config.schedule.is_some(),
            browser_speech: config.speech.adapter == Some(AdapterKind::Browser),
            voice: &config.speech.voice,
            rate: config.speech.rate_wpm,
            webrtc_camera: config.operator.camera == Camera::WebRtc,
            unavailable_page,
            strings: serde_json::to_string(&shell_table(config)).unwrap_or_default(),
            default_language: config.languages.default_language().as_str(),
            starting: default_words(config, ShellString::Starting),
            stop: default_words(config, ShellString::Stop),
        }
    }
}

/// The shell's words for `string` in the bundle's default language.
fn default_words(config: &SiteConfig, string: ShellString) -> String {
    (shell_table(config).get(string.key()))
        .and_then(|texts| texts.get(config.languages.default_language().as_str()))
        .cloned()
        .unwrap_or_default()
}

/// `value` as JSON for a `data-` attribute (askama escapes it), or empty for none: the
/// kiosk's scripts take the parsed form and never parse `docent.yaml` text themselves.
/// `{"en": "", "de": "de/"}`: where each language's pages are shown from.
fn page_folders(languages: &Languages) -> String {
    let folders: serde_json::Map<String, serde_json::Value> = (languages.page_folders())
        .into_iter()
        .map(|(language, folder)| (language.to_string(), folder.into()))
        .collect();
    serde_json::Value::Object(folders).to_string()
}

fn json_or_empty<T: serde::Serialize>(value: Option<&T>) -> String {
    value
        .and_then(|v| serde_json::to_string(v).ok())
        .unwrap_or_default()
}

/// `pages/projector/projector.html`: the projector shell.
#[derive(Template)]
#[template(path = "projector/projector.html")]
pub struct ProjectorShell<'a> {
    /// Websocket path, e.g. `/ws`.
    pub ws_path: &'a str,
    /// Where media files are served, with a trailing slash: `/media/`.
    pub media_path: &'a str,
    /// `black` or `hold`: what stays on screen after a video.
    pub after_video: &'a str,
    /// The soft edge of highlights, a fraction of the projected width.
    pub highlight_edge: f64,
}

impl<'a> ProjectorShell<'a> {
    /// The shell for a bundle with these settings.
    pub fn new(config: &'a SiteConfig) -> Self {
        ProjectorShell {
            ws_path: WS_PATH,
            media_path: "/media/",
            after_video: config.projector.after_video.as_str(),
            highlight_edge: config.projector.highlight_edge,
        }
    }
}

/// `pages/preview/preview.html`: for authors, the act list, the words being spoken, and the
/// kiosk and the projector side by side.
#[derive(Template)]
#[template(path = "preview/preview.html")]
pub struct PreviewPage<'a> {
    /// Websocket path, e.g. `/ws`: the preview fires acts as an operator.
    pub ws_path: &'a str,
    /// False on an `--open` development server: the preview fires acts without signing in.
    pub needs_credential: bool,
    /// Words per minute of speech, for showing texts as long as they take to say.
    pub rate: u32,
    /// The touchscreen's width in CSS pixels.
    pub kiosk_width: u32,
    /// The touchscreen's height.
    pub kiosk_height: u32,
    /// The projector's width in CSS pixels.
    pub projector_width: u32,
    /// The projector's height.
    pub projector_height: u32,
}

impl<'a> PreviewPage<'a> {
    /// The preview at the sizes the examples are made for: a 1280x800 touchscreen, a
    /// 1280x720 projector.
    pub fn new(config: &'a SiteConfig, needs_credential: bool) -> Self {
        PreviewPage {
            ws_path: WS_PATH,
            needs_credential,
            rate: config.speech.rate_wpm,
            kiosk_width: 1280,
            kiosk_height: 800,
            projector_width: 1280,
            projector_height: 720,
        }
    }
}

/// `GET /preview`: acts, speech and both screens in one window (`docent serve --preview`
/// opens it). Open to anyone like the console: firing acts needs the operator's credential.
pub async fn preview(State(state): State<AppState>) -> Response {
    let bundle = state.dispatcher.bundle();
    html(PreviewPage::new(&bundle.config, !state.access.is_open()).render())
}

/// `GET /`: the kiosk shell.
pub async fn kiosk(State(state): State<AppState>) -> Response {
    let bundle = state.dispatcher.bundle();
    let (root, home) = (bundle.root.clone(), bundle.config.home.clone());
    // It reads the home page for its stylesheets: off the threads that carry triggers.
    let unavailable = tokio::task::spawn_blocking(move || MissingPage::new(&root, &home).render())
        .await
        .map_err(|e| askama::Error::Custom(Box::new(e)));
    let unavailable = match unavailable.and_then(|page| page) {
        Ok(page) => page,
        Err(e) => return AppError::internal(e).into_response(),
    };
    html(KioskShell::new(&bundle.config, &unavailable).render())
}

/// `GET /projector`: the projector shell.
pub async fn projector(State(state): State<AppState>) -> Response {
    let bundle = state.dispatcher.bundle();
    html(ProjectorShell::new(&bundle.config).render())
}

/// A rendered page as an HTML answer that is revalidated on every load (a deployed kiosk must
/// pick up a new Docent at once); a rendering failure is an internal error.
pub(super) fn html(rendered: askama::Result<String>) -> Response {
    match rendered {
        Ok(page) => (
            [
                (header::CONTENT_TYPE, "text/html; charset=utf-8"),
                (header::CACHE_CONTROL, "no-cache"),
            ],
            page,
        )
            .into_response(),
        Err(e) => AppError::internal(e).into_response(),
    }
}

#[cfg(test)]
#[path = "shells_words_tests.rs"]
mod words_tests;

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use super::*;
    use crate::content::config::AfterVideo;

    #[test]
    fn the_preview_shows_both_screens_at_their_sizes_and_the_acts() {
        let config = SiteConfig::default();
        let page = PreviewPage::new(&config, true).render().expect("renders");
        assert!(
            page.contains(
                r#"<iframe src="/?preview" title="touchscreen" width="1280" height="800">"#
            ),
            "{page}"
        );
        for id in [
            "act-list",
            "search",
            "speaking",
            "no-voice",
            "signin",
            "link",
            "reload-banner",
        ] {
            assert!(page.contains(&format!(r#"id="{id}""#)), "no #{id}");
        }
        assert!(page.contains(r#"data-credential="required""#), "{page}");
        let page = PreviewPage::new(&config, false).render().expect("renders");
        assert!(page.contains(r#"data-credential="open""#), "{page}");
        assert!(
            page.contains(
                r#"<iframe src="/projector" title="projector" width="1280" height="720">"#
            ),
            "{page}"
        );
        assert!(page.contains(r#"src="/static/preview.js""#), "{page}");
    }

    #[test]
    fn the_kiosk_shell_is_told_each_languages_page_folder() {
        let list = ["en", "de"].map(|t| crate::content::Language::parse(t).expect("tag"));
        let config = SiteConfig {
            languages: Languages::new(list.to_vec()).expect("languages"),
            ..SiteConfig::default()
        };
        let page = KioskShell::new(&config, "").render().expect("renders");
        let folders = r#"data-page-folders="{&#34;de&#34;:&#34;de/&#34;,&#34;en&#34;:&#34;&#34;}""#;
        assert!(page.contains(folders), "{page}");
        assert!(page.contains(r#"data-languages="en de""#), "{page}");
    }

    #[test]
    fn the_kiosk_shell_carries_its_contract() {
        let mut config = SiteConfig {
            home: "start \"page\".html".to_owned(),
            ..SiteConfig::default()
        };
        config.kiosk.idle = Duration::from_secs(90);
        config.kiosk.idle_act = Some("INVITE".to_owned());
        let page = KioskShell::new(&config, "<p>gone</p>")
            .render()
            .expect("renders");
        assert!(page.starts_with("<!doctype html>"), "{page}");
        assert!(
            page.contains(r#"data-unavailable="&#60;p&#62;gone&#60;/p&#62;""#),
            "{page}"
        );
        assert!(page.contains(r#"data-ws="/ws""#), "{page}");
        assert!(page.contains(r#"data-pages="/pages/""#), "{page}");
        assert!(
            page.contains(r#"data-home="start &#34;page&#34;.html""#),
            "{page}"
        );
        assert!(page.contains(r#"data-idle-ms="90000""#), "{page}");
        assert!(page.contains(r#"data-idle-act="INVITE""#), "{page}");
        assert!(page.contains(r#"src="/static/kiosk.js""#), "{page}");
        assert_eq!(page.matches("<iframe").count(), 2);

        config.kiosk.idle_act = None;
        let page = KioskShell::new(&config, "").render().expect("renders");
        assert!(!page.contains("data-idle-act"), "{page}");
    }

    #[test]
    fn the_kiosk_shell_answers_camera_calls_only_with_a_webrtc_camera() {
        let mut config = SiteConfig::default();
        let page = KioskShell::new(&config, "").render().expect("renders");
        assert!(page.contains(r#"data-camera="webrtc""#), "{page}");
        for camera in [
            Camera::None,
            Camera::Url("http://192.168.1.20:8081/stream.mjpg".to_owned()),
        ] {
            config.operator.camera = camera;
            let page = KioskShell::new(&config, "").render().expect("renders");
            assert!(!page.contains("data-camera"), "{page}");
        }
    }

    #[test]
    fn the_projector_shell_carries_its_contract() {
        let mut config = SiteConfig::default();
        let page = ProjectorShell::new(&config).render().expect("renders");
        assert!(page.contains(r#"data-ws="/ws""#), "{page}");
        assert!(page.contains(r#"data-media="/media/""#), "{page}");
        assert!(page.contains(r#"data-after-video="black""#), "{page}");
        assert!(page.contains(r#"data-highlight-edge="0.02""#), "{page}");
        assert!(page.contains(r#"src="/static/projector.js""#), "{page}");
        config.projector.after_video = AfterVideo::Hold;
        config.projector.highlight_edge = 0.0;
        let page = ProjectorShell::new(&config).render().expect("renders");
        assert!(page.contains(r#"data-after-video="hold""#), "{page}");
        assert!(page.contains(r#"data-highlight-edge="0""#), "{page}");
    }
}
