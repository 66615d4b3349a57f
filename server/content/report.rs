//! The content report behind `/report`: every act (its variants, commands, place, group and
//! key), every page (the acts it offers through `data-act`, the acts that display it), every
//! media file (the acts that project it, the pages that name it) and the live bundle's
//! warnings. Built from the loaded [`Bundle`] plus one read of its pages, through the bundle's
//! path gate; a serialization boundary of its own (`GET /api/report`), never the internal
//! structs.

use std::collections::BTreeMap;
use std::path::Path;

use serde::Serialize;

use crate::diagnostic::Diagnostic;
use crate::model::{Bundle, Verb};
use crate::paths::{BundleArea, list_files, resolve_in_bundle};

/// Pages larger than this are not searched for media names (as `pages.rs` does for acts).
const MAX_PAGE_BYTES: u64 = 8 * 1024 * 1024;

/// What `GET /api/report` answers.
#[derive(Debug, Serialize)]
pub struct ContentReport {
    /// The bundle folder's name.
    pub bundle: String,
    /// The home page, relative to `pages/`.
    pub home: String,
    /// Every act in loaded order.
    pub acts: Vec<ActReport>,
    /// Every file under `pages/`, sorted.
    pub pages: Vec<PageReport>,
    /// Every file under `media/`, sorted.
    pub media: Vec<MediaReport>,
    /// The live bundle's warnings and notes (a live bundle has no errors).
    pub problems: Vec<Diagnostic>,
}

/// One act as the report shows it.
#[derive(Debug, Serialize)]
pub struct ActReport {
    /// The label.
    pub label: String,
    /// The acts file, relative to the bundle.
    pub file: String,
    /// Line of the label.
    pub line: u32,
    /// The console group (written or the file's name).
    pub group: String,
    /// The console shortcut letter, if any.
    pub key: Option<char>,
    /// Text variants in written order.
    pub variants: Vec<VariantReport>,
    /// Commands in written order, as written (`VERB argument`).
    pub commands: Vec<String>,
    /// Pages (relative to `pages/`) with a `data-act` naming this act.
    pub offered_on: Vec<String>,
}

/// One text variant.
#[derive(Debug, Serialize)]
pub struct VariantReport {
    /// `Text`, `TextChild`, ...
    pub name: String,
    /// The alternatives.
    pub texts: Vec<String>,
}

/// One page.
#[derive(Debug, Serialize)]
pub struct PageReport {
    /// Path relative to `pages/`.
    pub path: String,
    /// Acts the page offers (`data-act`), with the line, in page order.
    pub offers: Vec<Offer>,
    /// Acts whose `DISPLAY_PAGE` shows this page.
    pub displayed_by: Vec<String>,
}

/// A `data-act` on a page.
#[derive(Debug, Serialize)]
pub struct Offer {
    /// The label named.
    pub label: String,
    /// Line in the page file.
    pub line: u32,
    /// Whether the bundle has an act of that label.
    pub known: bool,
}

/// One media file.
#[derive(Debug, Serialize)]
pub struct MediaReport {
    /// Path relative to `media/`.
    pub path: String,
    /// Acts whose `PROJECT` shows it.
    pub projected_by: Vec<String>,
    /// Pages (relative to `pages/`) that name it (`media/<path>` in their HTML).
    pub used_on: Vec<String>,
}

/// Builds the report of `bundle`, reading its pages (blocking: call off the async runtime).
pub fn content_report(bundle: &Bundle) -> ContentReport {
    let root = bundle.root.as_path();
    let mut offers: BTreeMap<String, Vec<Offer>> = BTreeMap::new();
    let mut offered_on: BTreeMap<&str, Vec<String>> = BTreeMap::new();
    for found in bundle.page_offers.iter().cloned() {
        let page = found.pos.file.trim_start_matches("pages/").to_owned();
        if let Some(act) = bundle.act(&found.value) {
            let pages = offered_on.entry(act.label.as_str()).or_default();
            if !pages.contains(&page) {
                pages.push(page.clone());
            }
        }
        offers.entry(page).or_default().push(Offer {
            known: bundle.act(&found.value).is_some(),
            label: found.value,
            line: found.pos.line,
        });
    }
    let mut displayed_by: BTreeMap<&str, Vec<String>> = BTreeMap::new();
    let mut projected_by: BTreeMap<&str, Vec<String>> = BTreeMap::new();
    for act in &bundle.acts {
        for command in &act.commands {
            let users = match command.value.verb {
                Verb::DisplayPage => &mut displayed_by,
                Verb::Project => &mut projected_by,
                _ => continue,
            };
            if let Some(file) = command.value.arg.as_deref() {
                let labels = users.entry(file).or_default();
                if !labels.contains(&act.label) {
                    labels.push(act.label.clone());
                }
            }
        }
    }
    let page_files = list_files(root, BundleArea::Pages);
    let media_users = media_named_in_pages(root, &page_files);
    let acts = bundle
        .acts
        .iter()
        .map(|act| ActReport {
            label: act.label.clone(),
            file: act.pos.file.to_string(),
            line: act.pos.line,
            group: act.group_name().to_owned(),
            key: act.key,
            variants: act
                .variants
                .iter()
                .map(|v| VariantReport {
                    name: v.name.clone(),
                    texts: v.alternatives.iter().map(|a| a.value.clone()).collect(),
                })
                .collect(),
            commands: act
                .commands
                .iter()
                .map(|c| match &c.value.arg {
                    Some(arg) => format!("{} {arg}", c.value.verb),
                    None => c.value.verb.to_string(),
                })
                .collect(),
            offered_on: offered_on.remove(act.label.as_str()).unwrap_or_default(),
        })
        .collect();
    let pages = page_files
        .into_iter()
        .map(|path| PageReport {
            offers: offers.remove(&path).unwrap_or_default(),
            displayed_by: displayed_by.remove(path.as_str()).unwrap_or_default(),
            path,
        })
        .collect();
    let media = list_files(root, BundleArea::Media)
        .into_iter()
        .map(|path| MediaReport {
            projected_by: projected_by.remove(path.as_str()).unwrap_or_default(),
            used_on: media_users.get(&path).cloned().unwrap_or_default(),
            path,
        })
        .collect();
    ContentReport {
        bundle: root
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default(),
        home: bundle.config.home.clone(),
        acts,
        pages,
        media,
        problems: bundle.diagnostics.clone(),
    }
}

/// Media path (relative to `media/`) → the pages whose HTML names `media/<path>`.
fn media_named_in_pages(root: &Path, pages: &[String]) -> BTreeMap<String, Vec<String>> {
    let mut users: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for page in pages {
        let lower = page.to_ascii_lowercase();
        if !(lower.ends_with(".html") || lower.ends_with(".htm") || lower.ends_with(".css")) {
            continue;
        }
        // Through the gate: a page linked from outside the bundle is never read.
        let Ok(path) = resolve_in_bundle(root, BundleArea::Pages, page) else {
            continue;
        };
        if std::fs::metadata(&path).map_or(true, |m| m.len() > MAX_PAGE_BYTES) {
            continue;
        }
        let Ok(bytes) = std::fs::read(&path) else {
            continue;
        };
        for name in media_names(&String::from_utf8_lossy(&bytes)) {
            let pages = users.entry(name).or_default();
            if !pages.contains(page) {
                pages.push(page.clone());
            }
        }
    }
    users
}

/// Every `media/<path>` written in `text`, the path ending at a quote, bracket, space, `?`
/// or `#`.
fn media_names(text: &str) -> Vec<String> {
    text.match_indices("media/")
        .map(|(at, _)| {
            let rest = &text[at + "media/".len()..];
            let end = rest
                .find(|c: char| c.is_whitespace() || "\"'()<>?#`".contains(c))
                .unwrap_or(rest.len());
            rest[..end].replace("%20", " ")
        })
        .filter(|name| !name.is_empty())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn media_names_end_at_quotes_brackets_and_queries() {
        let html = r#"<img src="../media/a%20b.png"><video src='/media/clip.webm?x=1'>
            <div style="background: url(media/sub/bg.jpg)"></div> multimedia/ <a href="media/x%20y.pdf#p2">"#;
        assert_eq!(
            media_names(html),
            ["a b.png", "clip.webm", "sub/bg.jpg", "x y.pdf"]
        );
    }
}
