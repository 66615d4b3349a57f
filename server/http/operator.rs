//! The operator console (Wizard of Oz): the page at `/operator` (an askama template whose
//! script, `static/operator/main.js`, signs in and does the rest over the websocket) and its
//! settings at `GET /api/operator` (map, camera, situations, visitor groups from `docent.yaml`
//! `operator:`), which need the operator's or dialog manager's credential.

use askama::Template;
use axum::Json;
use axum::extract::State;
use axum::response::Response;
use percent_encoding::{AsciiSet, NON_ALPHANUMERIC, utf8_percent_encode};
use serde_json::{Value, json};

use crate::content::config::{Camera, SiteConfig};
use crate::http::auth::Authorized;
use crate::http::shells::html;
use crate::http::static_files;
use crate::state::AppState;

/// The camera script, when this build embeds it (`static/operator/camera.js`).
const CAMERA_SCRIPT: &str = "operator/camera.js";

/// `pages/operator/console.html`: the console.
#[derive(Template)]
#[template(path = "operator/console.html")]
pub struct OperatorConsole<'a> {
    /// Websocket path, e.g. `/ws`.
    pub ws_path: &'a str,
    /// False on an `--open` development server: the console connects without asking.
    pub needs_credential: bool,
    /// Whether the camera script is served (the console loads it only then).
    pub camera_script: bool,
}

impl OperatorConsole<'_> {
    /// The console of a server that does (or, `--open`, does not) ask for a credential.
    pub fn new(needs_credential: bool) -> Self {
        OperatorConsole {
            ws_path: "/ws",
            needs_credential,
            camera_script: static_files::lookup(CAMERA_SCRIPT).is_some(),
        }
    }
}

/// `GET /operator`: the console page. Open to anyone: it holds no secret and does nothing
/// until its operator signs in.
pub async fn console(State(state): State<AppState>) -> Response {
    html(OperatorConsole::new(!state.access.is_open()).render())
}

/// `GET /api/operator` (bearer): the console's settings.
pub async fn settings(_: Authorized, State(state): State<AppState>) -> Json<Value> {
    Json(settings_json(&state.dispatcher.bundle().config))
}

/// The console's settings as `GET /api/operator` answers them.
pub fn settings_json(config: &SiteConfig) -> Value {
    let operator = &config.operator;
    let map = operator.map.as_deref().map(|path| {
        let bounds = config.drive.bounds.map(
            |b| json!({ "min_x": b.min_x, "min_y": b.min_y, "max_x": b.max_x, "max_y": b.max_y }),
        );
        json!({ "url": url_path(path), "bounds": bounds })
    });
    let camera = match &operator.camera {
        Camera::WebRtc => json!({ "kind": "webrtc" }),
        Camera::None => json!({ "kind": "none" }),
        Camera::Url(url) => json!({ "kind": "url", "url": url }),
    };
    json!({
        "map": map,
        "camera": camera,
        "situations": operator.situations,
        "visitor_groups": operator.visitor_groups,
    })
}

/// Bytes kept as they are in a URL path segment: RFC 3986's unreserved characters.
const SEGMENT: &AsciiSet = &NON_ALPHANUMERIC
    .remove(b'-')
    .remove(b'.')
    .remove(b'_')
    .remove(b'~');

/// A bundle-relative path (`pages/images/map.png`) as the URL path it is served at, each
/// segment percent-encoded.
pub(super) fn url_path(path: &str) -> String {
    let mut url = String::with_capacity(path.len() + 1);
    for segment in path.split('/') {
        url.push('/');
        url.extend(utf8_percent_encode(segment, SEGMENT));
    }
    url
}

#[cfg(test)]
mod tests {
    use std::collections::{BTreeMap, BTreeSet};

    use super::*;
    use crate::content::config::{Bounds, OperatorConfig};

    #[test]
    fn the_console_page_carries_its_contract() {
        let page = OperatorConsole::new(true).render().expect("renders");
        assert!(page.starts_with("<!doctype html>"), "{page}");
        assert!(page.contains(r#"data-ws="/ws""#), "{page}");
        assert!(page.contains(r#"data-credential="required""#), "{page}");
        assert!(page.contains(r#"src="/static/operator/main.js""#), "{page}");
        assert!(page.contains(r#"href="/static/operator.css""#), "{page}");
        assert!(page.contains(r#"<dialog id="signin""#), "{page}");
        assert!(page.contains(r#"type="password""#), "{page}");
        // The sign-in form never sends the credential anywhere by itself (no GET to a URL).
        assert!(page.contains(r#"method="dialog""#), "{page}");
        for id in [
            "search",
            "act-list",
            "preview",
            "stop",
            "history",
            "proposals",
            "queue",
        ] {
            assert!(page.contains(&format!(r#"id="{id}""#)), "no #{id}");
        }
        let camera = static_files::lookup(CAMERA_SCRIPT).is_some();
        assert_eq!(
            page.contains(r#"data-camera-script="/static/operator/camera.js""#),
            camera
        );

        let page = OperatorConsole::new(false).render().expect("renders");
        assert!(page.contains(r#"data-credential="open""#), "{page}");
    }

    #[test]
    fn every_console_script_is_served() {
        // Every module reachable from main.js (and from the camera script, when served) through
        // static imports, not only main.js's own: one missing from the table is a 404 in the
        // browser, and the console does not start.
        let mut queue = vec!["operator/main.js".to_owned()];
        if static_files::lookup(CAMERA_SCRIPT).is_some() {
            queue.push(CAMERA_SCRIPT.to_owned());
        }
        let mut served = BTreeSet::new();
        while let Some(name) = queue.pop() {
            if served.contains(&name) {
                continue;
            }
            let (_, body) = static_files::lookup(&name)
                .unwrap_or_else(|| panic!("{name} is imported but not served"));
            served.insert(name);
            for line in body.lines().map(str::trim_start) {
                // `import ... from "./x.js"`, or the last line of a multi-line import.
                if !(line.starts_with("import ") || line.starts_with("} from ")) {
                    continue;
                }
                if let Some(module) = line.split('"').nth(1) {
                    queue.push(format!("operator/{}", module.trim_start_matches("./")));
                }
            }
        }
        // search.js is imported by actlist.js only: the walk went past main.js's own imports.
        assert!(served.contains("operator/search.js"), "{served:?}");
    }

    #[test]
    fn settings_give_the_map_with_its_bounds_and_the_camera() {
        let mut config = SiteConfig::default();
        assert_eq!(
            settings_json(&config),
            json!({"map": null, "camera": {"kind": "webrtc"}, "situations": [], "visitor_groups": {}})
        );
        config.drive.bounds = Some(Bounds {
            min_x: 0.0,
            min_y: -1.0,
            max_x: 20.0,
            max_y: 12.5,
        });
        config.operator = OperatorConfig {
            map: Some("pages/images/hall map.png".to_owned()),
            camera: Camera::Url("http://cam.local/stream.mjpg".to_owned()),
            situations: vec!["question".to_owned(), "laughter".to_owned()],
            visitor_groups: BTreeMap::from([("children".to_owned(), "TextChild".to_owned())]),
        };
        assert_eq!(
            settings_json(&config),
            json!({
                "map": {"url": "/pages/images/hall%20map.png",
                        "bounds": {"min_x": 0.0, "min_y": -1.0, "max_x": 20.0, "max_y": 12.5}},
                "camera": {"kind": "url", "url": "http://cam.local/stream.mjpg"},
                "situations": ["question", "laughter"],
                "visitor_groups": {"children": "TextChild"},
            })
        );
        config.operator.camera = Camera::None;
        assert_eq!(settings_json(&config)["camera"], json!({"kind": "none"}));
    }

    #[test]
    fn url_paths_are_percent_encoded_per_segment() {
        assert_eq!(url_path("pages/images/map.png"), "/pages/images/map.png");
        assert_eq!(
            url_path("media/Plan ü#1.png"),
            "/media/Plan%20%C3%BC%231.png"
        );
    }
}
