//! The visitor's answer to a page that is not there. A touchscreen must never show raw JSON:
//! a page asked for by a browser (an HTML name under `/pages/`, or `Accept: text/html`) that
//! does not exist answers 404 with a friendly page in the bundle's style (the stylesheets its
//! home page links, over a plain style of our own) that says so and offers one big button back
//! to the home page. API clients (`Accept: application/json`) keep the JSON error.
//!
//! Each such answer is reported, so that the author learns of the broken link: a `page.missing`
//! event (the corpus) and a warning in the server log, at most [`REPORT_BURST`] at once and
//! [`REPORTS_PER_SECOND`] after that, so a stranger asking for nonsense cannot flood the log.

use std::path::Path;
use std::sync::Mutex;
use std::time::Instant;

use askama::Template;
use axum::http::{HeaderMap, StatusCode, header};
use axum::response::{IntoResponse, Response};
use lol_html::{RewriteStrSettings, element, rewrite_str};

use crate::access::TokenBucket;
use crate::content::{BundleArea, resolve_in_bundle};
use crate::events::EventKind;
use crate::http::operator::url_path;
use crate::state::AppState;
use crate::sync::lock;

/// Missing-page reports logged at once.
pub const REPORT_BURST: f64 = 20.0;
/// Missing-page reports per second kept up after a burst.
pub const REPORTS_PER_SECOND: f64 = 2.0;
/// Longest path or referrer written to the log; longer ones are cut (they are nonsense).
const MAX_LOGGED_CHARS: usize = 300;
/// Home pages larger than this are not read for their stylesheets.
const MAX_HOME_BYTES: u64 = 1024 * 1024;
/// At most this many of the home page's stylesheets are linked.
const MAX_STYLESHEETS: usize = 8;

/// The allowance of `page.missing` reports of one server.
#[derive(Debug)]
pub struct MissingPageReports(Mutex<TokenBucket>);

impl Default for MissingPageReports {
    fn default() -> Self {
        let bucket = TokenBucket::new(REPORT_BURST, REPORTS_PER_SECOND, Instant::now());
        MissingPageReports(Mutex::new(bucket))
    }
}

impl MissingPageReports {
    /// Whether one more report may be logged now.
    fn allow(&self) -> bool {
        lock(&self.0).take(Instant::now()).is_ok()
    }
}

/// `pages/missing/missing.html`: the friendly page.
#[derive(Template)]
#[template(path = "missing/missing.html")]
pub struct MissingPage {
    /// The home page's URL path; also the base of the stylesheet links.
    pub home_url: String,
    /// The home page's local stylesheets, as its `<link rel="stylesheet">` write them.
    pub stylesheets: Vec<String>,
}

impl MissingPage {
    /// The page for a bundle whose home page, relative to `pages/`, is `home`.
    pub fn new(root: &Path, home: &str) -> Self {
        MissingPage {
            home_url: url_path(&format!("pages/{home}")),
            stylesheets: home_stylesheets(root, home),
        }
    }
}

/// Whether a request for `rel` under `/pages/` comes from a browser showing a page: it asks
/// for HTML, is a navigation, or names an HTML file without asking for JSON.
pub fn wants_page(headers: &HeaderMap, rel: &str) -> bool {
    let text = |name: &str| {
        headers
            .get(name)
            .and_then(|v| v.to_str().ok())
            .unwrap_or("")
    };
    let accept = text(header::ACCEPT.as_str()).to_ascii_lowercase();
    if accept.contains("text/html") {
        return true;
    }
    if accept.contains("application/json") {
        return false;
    }
    let dest = text("sec-fetch-dest");
    let lower = rel.to_ascii_lowercase();
    matches!(dest, "document" | "iframe" | "frame")
        || lower.ends_with(".html")
        || lower.ends_with(".htm")
}

/// The 404 answer for `rel` (relative to `pages/`), reported as `page.missing`.
pub async fn answer(state: &AppState, rel: &str, headers: &HeaderMap) -> Response {
    let from = headers
        .get(header::REFERER)
        .and_then(|v| v.to_str().ok())
        .map(referrer_page);
    report(state, rel, from);
    let bundle = state.dispatcher.bundle();
    let (root, home) = (bundle.root.clone(), bundle.config.home.clone());
    // Reading the home page is file I/O: off the threads that carry triggers.
    let page = tokio::task::spawn_blocking(move || MissingPage::new(&root, &home).render()).await;
    match page {
        Ok(Ok(html)) => {
            let html = crate::http::files::with_page_script(html.as_bytes());
            let headers = [
                (header::CONTENT_TYPE, "text/html; charset=utf-8"),
                (header::CACHE_CONTROL, "no-cache"),
            ];
            (StatusCode::NOT_FOUND, headers, html).into_response()
        }
        Ok(Err(e)) => crate::http::AppError::internal(e).into_response(),
        Err(e) => crate::http::AppError::internal(e).into_response(),
    }
}

/// Logs a missing page in the corpus and the server log, within the allowance.
fn report(state: &AppState, rel: &str, from: Option<String>) {
    if !state.missing_pages.allow() {
        tracing::debug!(page = rel, "missing page not reported: too many at once");
        return;
    }
    let page = shorten(rel);
    match &from {
        Some(from) => tracing::warn!(
            "a visitor asked for the page {page:?}, which is not in the bundle (linked from {from:?})"
        ),
        None => tracing::warn!("a visitor asked for the page {page:?}, which is not in the bundle"),
    }
    state.hub.publish(EventKind::PageMissing { page, from });
}

/// Where a link came from: the page under `pages/` for a page of this server, else the
/// referrer's path (`/`: the kiosk shell itself, a `DISPLAY_PAGE` or a return home).
fn referrer_page(referer: &str) -> String {
    // `scheme://host[:port]/path?query#fragment` → `/path`.
    let after_scheme = referer.split_once("://").map_or(referer, |(_, rest)| rest);
    let path = after_scheme
        .find('/')
        .map_or("/", |at| &after_scheme[at..])
        .split(['?', '#'])
        .next()
        .unwrap_or("/");
    let path = percent_decode(path);
    let page = path.strip_prefix("/pages/").unwrap_or(&path);
    shorten(page)
}

/// `%XX` sequences decoded (as UTF-8, lossily); anything else kept.
fn percent_decode(text: &str) -> String {
    percent_encoding::percent_decode_str(text)
        .decode_utf8_lossy()
        .into_owned()
}

fn shorten(text: &str) -> String {
    match text.char_indices().nth(MAX_LOGGED_CHARS) {
        Some((at, _)) => format!("{}…", &text[..at]),
        None => text.to_owned(),
    }
}

/// The local stylesheets the home page links (`<link rel="stylesheet" href>`), read with an
/// HTML parser; none when the home page cannot be read. Links to other sites are left out: a
/// kiosk is often offline, and the page must show at once.
fn home_stylesheets(root: &Path, home: &str) -> Vec<String> {
    let Ok(file) = resolve_in_bundle(root, BundleArea::Pages, home) else {
        return Vec::new();
    };
    if std::fs::metadata(&file).map_or(true, |m| m.len() > MAX_HOME_BYTES) {
        return Vec::new();
    }
    let Ok(bytes) = std::fs::read(&file) else {
        return Vec::new();
    };
    stylesheets_of(&String::from_utf8_lossy(&bytes))
}

/// The local stylesheet links of one HTML page, in order.
fn stylesheets_of(html: &str) -> Vec<String> {
    let mut found = Vec::new();
    let handler = element!("link[rel][href]", |el| {
        let is_stylesheet = el.get_attribute("rel").is_some_and(|rel| {
            rel.split_ascii_whitespace()
                .any(|r| r.eq_ignore_ascii_case("stylesheet"))
        });
        let href = el.get_attribute("href").unwrap_or_default();
        let href = href.trim();
        let external = href.starts_with("//") || has_scheme(href);
        if is_stylesheet && !href.is_empty() && !external && found.len() < MAX_STYLESHEETS {
            found.push(href.to_owned());
        }
        Ok(())
    });
    let settings = RewriteStrSettings::new().append_element_content_handler(handler);
    // A page lol_html cannot read gives no stylesheets: the page's own style still applies.
    if rewrite_str(html, settings).is_err() {
        return Vec::new();
    }
    found
}

/// Whether `href` starts with a URL scheme (`https:`, `data:`), i.e. is not a path.
fn has_scheme(href: &str) -> bool {
    let Some((scheme, _)) = href.split_once(':') else {
        return false;
    };
    let mut chars = scheme.chars();
    chars.next().is_some_and(|c| c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
}

#[cfg(test)]
mod tests {
    use axum::http::HeaderValue;

    use super::*;

    fn headers(pairs: &[(&'static str, &'static str)]) -> HeaderMap {
        let mut map = HeaderMap::new();
        for (name, value) in pairs {
            map.insert(*name, HeaderValue::from_static(value));
        }
        map
    }

    #[test]
    fn browsers_get_the_page_and_api_clients_json() {
        let html = "text/html,application/xhtml+xml,application/xml;q=0.9,*/*;q=0.8";
        assert!(wants_page(&headers(&[("accept", html)]), "x.png"));
        assert!(wants_page(&headers(&[]), "room/Map.HTM"));
        assert!(wants_page(&headers(&[("accept", "*/*")]), "a.html"));
        assert!(wants_page(&headers(&[("sec-fetch-dest", "iframe")]), "x"));
        assert!(!wants_page(
            &headers(&[("accept", "application/json")]),
            "a.html"
        ));
        assert!(!wants_page(&headers(&[("accept", "*/*")]), "img/a.png"));
    }

    #[test]
    fn the_referrer_names_the_page_it_came_from() {
        assert_eq!(
            referrer_page("http://10.0.0.2:8080/pages/rooms/caf%C3%A9.html?x=1#top"),
            "rooms/café.html"
        );
        assert_eq!(referrer_page("http://127.0.0.1:8080/"), "/");
        assert_eq!(referrer_page("http://host"), "/");
        assert_eq!(
            referrer_page(&format!("http://h/{}", "a".repeat(400)))
                .chars()
                .count(),
            301
        );
    }

    #[test]
    fn only_the_home_pages_local_stylesheets_are_linked() {
        let html = r#"<!doctype html><head>
            <link rel="stylesheet" href="css/site.css">
            <LINK REL="Alternate StyleSheet" HREF="/pages/alt.css">
            <link rel="icon" href="icon.png">
            <link rel="stylesheet" href="https://fonts.example.com/x.css">
            <link rel="stylesheet" href="//cdn.example.com/y.css">
            <!-- <link rel="stylesheet" href="commented.css"> -->
            <link rel="stylesheet" href="">
            </head>"#;
        assert_eq!(stylesheets_of(html), ["css/site.css", "/pages/alt.css"]);
    }

    #[test]
    fn the_page_says_it_plainly_and_leads_home() {
        let page = MissingPage {
            home_url: url_path("pages/start page.html"),
            stylesheets: vec!["css/site.css".to_owned()],
        };
        let html = page.render().expect("renders");
        assert!(html.contains("This page is not available."), "{html}");
        assert!(
            html.contains(r#"<base href="/pages/start%20page.html">"#),
            "{html}"
        );
        assert!(
            html.contains(r#"<link rel="stylesheet" href="css/site.css">"#),
            "{html}"
        );
        assert!(
            html.contains(r#"<a class="docent-home" href="/pages/start%20page.html""#),
            "{html}"
        );
        assert!(
            !html.contains("data-act"),
            "the way home triggers nothing: {html}"
        );
    }
}
