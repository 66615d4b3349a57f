//! Checking the touchscreen pages: every `pages/**/*.html` (and `.htm`) is read with a real
//! HTML5 tokenizer (lol_html, see `scan`), and `.css` and `.js` files under `pages/` are
//! read for the links and act triggers they hold.
//!
//! What a visitor would meet is reported: content hidden by something left open, broken
//! `data-act` quoting, links to missing files, pictures and videos Chromium cannot show,
//! pages not in UTF-8, unreadable `data-act-after` delays; and what fights the robot or the
//! kiosk (`behaviour`): a `lang` other than the page's folder's, sound that starts by itself,
//! a form on an attract page; and a start tag without its `>` (`tag_end`). Labels (`data-act` values and
//! `docent.trigger` literals) are returned for `load` to check against the acts.

mod behaviour;
mod languages;
mod links;
mod scan;
mod script;
mod tag_end;
mod text;

use std::collections::BTreeSet;
use std::sync::Arc;

use crate::DiagnosticCode;
use crate::commands::CommandChecker;
use crate::diagnostic::Diagnostic;
use crate::language::Language;
use crate::media::ShownBy;
use crate::model::Located;
use crate::paths::{BundleArea, list_files};
use links::{Target, css_urls, resolve, srcset_urls};
use scan::{LinkUse, PageScan, Unclosed, Value};
use text::SourceText;

pub(crate) use languages::check_reachable_languages;
pub use script::act_delay;

/// Files larger than this are not read; no real touchscreen page comes near it.
const MAX_PAGE_BYTES: u64 = 8 * 1024 * 1024;

/// The act labels the bundle's pages use.
#[derive(Debug, Default)]
pub(crate) struct PageLabels {
    /// `data-act` values (well quoted), in file order, at the value.
    pub offered: Vec<Located<String>>,
    /// `docent.trigger("LABEL")` literals in page scripts, at the label.
    pub triggered: Vec<Located<String>>,
    /// The languages each page offers through `data-language` buttons: (page inside
    /// `pages/`, language), in file order.
    pub languages: Vec<(String, Language)>,
}

/// Checks every page, style sheet and script under `pages/`; returns the labels they use.
pub(crate) fn check_pages(checker: &CommandChecker<'_>, out: &mut Vec<Diagnostic>) -> PageLabels {
    let mut labels = PageLabels::default();
    let mut html_pages = Vec::new();
    let files = list_files(checker.root(), BundleArea::Pages);
    let stray = languages::StrayFolders::find(checker, &files);
    let attract = behaviour::attract_pages(checker.config());
    for rel in files {
        let lower = rel.to_ascii_lowercase();
        let kind = match lower.rsplit_once('.').map(|(_, ext)| ext) {
            Some("html" | "htm") => FileKind::Page,
            Some("css") => FileKind::Style,
            Some("js" | "mjs") => FileKind::Script,
            _ => continue,
        };
        // Through the gate: a file symlinked from outside the bundle is never read.
        let Ok(path) = checker.resolve(BundleArea::Pages, &rel) else {
            continue;
        };
        if std::fs::metadata(&path).map_or(true, |m| m.len() > MAX_PAGE_BYTES) {
            continue;
        }
        let Ok(bytes) = std::fs::read(&path) else {
            continue;
        };
        let file: Arc<str> = Arc::from(format!("pages/{rel}"));
        let page = PageFile {
            checker,
            rel: &rel,
            stray: &stray,
            attract: &attract,
        };
        match kind {
            FileKind::Page => {
                html_pages.push(rel.clone());
                let Some(source) = SourceText::decode(file, &bytes, out) else {
                    continue;
                };
                page.check_html(&source, &mut labels, out);
            }
            FileKind::Style | FileKind::Script => {
                let source = SourceText::new(file, String::from_utf8_lossy(&bytes).into_owned());
                if kind == FileKind::Style {
                    page.check_css(&source, &source.text, 0, out);
                } else {
                    page.find_triggers(&source, &source.text, 0, &mut labels);
                }
            }
        }
    }
    stray.report(checker, &html_pages, out);
    languages::check_translated_pages(checker, &html_pages, &stray, out);
    labels
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum FileKind {
    Page,
    Style,
    Script,
}

/// One file under `pages/` being checked.
struct PageFile<'c, 'r> {
    checker: &'c CommandChecker<'c>,
    /// Its path inside `pages/`: relative links start from its folder.
    rel: &'r str,
    /// Folders named like a language the bundle does not list (reported once, elsewhere).
    stray: &'r languages::StrayFolders,
    /// The pages the attract loops show, inside `pages/`.
    attract: &'r BTreeSet<String>,
}

impl PageFile<'_, '_> {
    fn check_html(&self, source: &SourceText, labels: &mut PageLabels, out: &mut Vec<Diagnostic>) {
        let found: PageScan = scan::scan(&source.text);
        if let Some(first) = found.unclosed.first() {
            report_unclosed(source, first, out);
        }
        if found.stopped.is_some() {
            let message = "Docent could not follow this page's markup to the end (an element \
                           where HTML does not allow it, such as a `<style>` or `<title>` inside \
                           a `<select>`, can do this), so the rest of the page was not checked. \
                           Move that element out, or check the page in the preview.";
            out.push(Diagnostic::warning(
                DiagnosticCode::PageNotChecked,
                &source.pos(0),
                message,
            ));
        }
        for act in &found.acts {
            match broken_quoting(&act.text) {
                Some(message) => out.push(Diagnostic::error(
                    DiagnosticCode::ActQuoting,
                    &source.pos(act.at),
                    message,
                )),
                None => labels.offered.push(Located {
                    value: act.text.clone(),
                    pos: source.pos(act.at),
                }),
            }
        }
        for value in &found.languages {
            let pos = source.pos(value.at);
            if let Some(language) =
                languages::offered_language(self.checker, &value.text, &pos, out)
            {
                labels.languages.push((self.rel.to_owned(), language.value));
            }
        }
        for (after, has_act) in &found.act_afters {
            check_act_after(source, after, *has_act, out);
        }
        for (name, value) in &found.act_typos {
            behaviour::check_act_typo(source, name, value, out);
        }
        for (tag, swallowed) in &found.tags_without_end {
            tag_end::report(source, tag, swallowed, out);
        }
        check_charset(source, &found.charsets, out);
        behaviour::check_lang(
            source,
            &found,
            self.checker.config(),
            self.stray,
            self.rel,
            out,
        );
        behaviour::check_autoplay(source, &found, out);
        // A translation of an attract page is shown in the loop too.
        let shown_as = (self.checker.languages().page_fallback(self.rel)).unwrap_or(self.rel);
        if self.attract.contains(self.rel) || self.attract.contains(shown_as) {
            behaviour::check_attract_form(source, &found, out);
        }
        for link in &found.links {
            if link.srcset {
                for (url, offset) in srcset_urls(&link.value.text) {
                    self.check_link(source, url, link.value.at + offset, link.used, out);
                }
            } else {
                self.check_link(source, &link.value.text, link.value.at, link.used, out);
            }
        }
        for css in &found.css {
            self.check_css(source, &css.text, css.at, out);
        }
        for js in &found.scripts {
            self.find_triggers(source, &js.text, js.at, labels);
        }
    }

    fn check_css(&self, source: &SourceText, css: &str, at: usize, out: &mut Vec<Diagnostic>) {
        for (url, offset) in css_urls(css) {
            let lower = url.to_ascii_lowercase();
            let used = if lower.ends_with(".css")
                || [".woff", ".woff2", ".ttf", ".otf", ".eot"]
                    .iter()
                    .any(|font| lower.split(['?', '#']).next().unwrap_or("").ends_with(font))
            {
                LinkUse::Resource
            } else {
                LinkUse::Image
            };
            self.check_link(source, url, at + offset, used, out);
        }
    }

    fn find_triggers(&self, source: &SourceText, js: &str, at: usize, labels: &mut PageLabels) {
        for (label, offset) in script::trigger_literals(js) {
            labels.triggered.push(Located {
                value: label,
                pos: source.pos(at + offset),
            });
        }
    }

    fn check_link(
        &self,
        source: &SourceText,
        url: &str,
        at: usize,
        used: LinkUse,
        out: &mut Vec<Diagnostic>,
    ) {
        let pos = source.pos(at);
        match resolve(self.rel, url) {
            Target::Bundle { area, rel } => {
                // `tour.html` in `pages/de/`: the kiosk shows `pages/tour.html` when there is
                // no German one (the page-translation check warns about that once per page).
                let fallback = (self.checker.languages().page_fallback(&rel))
                    .or_else(|| self.stray.page_fallback(&rel));
                let rel = match fallback {
                    Some(fallback)
                        if area == BundleArea::Pages
                            && self.checker.path_problem(area, &rel).is_some() =>
                    {
                        fallback.to_owned()
                    }
                    _ => rel,
                };
                if let Some((_, problem)) = self.checker.path_problem(area, &rel) {
                    let message = format!("This link leads nowhere. {problem}");
                    out.push(Diagnostic::error(DiagnosticCode::BrokenLink, &pos, message));
                    return;
                }
                let by = match used {
                    LinkUse::Image => ShownBy::PageImage,
                    LinkUse::Player => ShownBy::PagePlayer,
                    LinkUse::Navigate | LinkUse::Resource => return,
                };
                if let Ok(path) = self.checker.resolve(area, &rel) {
                    let shown = format!("{}/{rel}", area.dir_name());
                    self.checker.media().check(&path, &shown, by, &pos, out);
                }
            }
            Target::Internet if used == LinkUse::Navigate => {
                let message = format!(
                    "The kiosk does not open addresses outside the bundle, so tapping this \
                     link (`{url}`) does nothing. Copy what it shows into a page under pages/ \
                     and link there, or remove the link."
                );
                out.push(Diagnostic::warning(
                    DiagnosticCode::ExternalLink,
                    &pos,
                    message,
                ));
            }
            Target::Internet => {
                let message = format!(
                    "`{url}` is on the internet, which the touchscreen may not reach. Copy the \
                     file into pages/ and link to it relative to this page."
                );
                out.push(Diagnostic::warning(
                    DiagnosticCode::ExternalLink,
                    &pos,
                    message,
                ));
            }
            Target::OwnComputer => {
                let message = format!(
                    "`{url}` is a file on your own computer, which the touchscreen cannot \
                     reach. Copy the file into pages/ and link to it relative to this page, \
                     e.g. `images/photo.jpg`."
                );
                out.push(Diagnostic::error(DiagnosticCode::BrokenLink, &pos, message));
            }
            Target::Server { path } => {
                let message = format!(
                    "This link leads to `{path}` on the Docent server, outside the bundle's \
                     pages/ and media/ folders, so it finds nothing (too many `../`?). Link \
                     to a file inside pages/, relative to this page, or to `/media/...`."
                );
                out.push(Diagnostic::error(DiagnosticCode::BrokenLink, &pos, message));
            }
            Target::NotAFile => {}
        }
    }
}

/// The message for a `data-act` value whose quotes went wrong, if they did.
fn broken_quoting(value: &str) -> Option<String> {
    const CURLY: &[char] = &['“', '”', '„', '‘', '’', '‚', '«', '»', '″'];
    const BREAKS: &[char] = &['"', '\'', '<', '>', '\n', '\r', '='];
    let label: String = value
        .trim_matches(|c: char| CURLY.contains(&c) || BREAKS.contains(&c) || c.is_whitespace())
        .chars()
        .take_while(|c| !CURLY.contains(c) && !BREAKS.contains(c) && !c.is_whitespace())
        .collect();
    if value.contains(CURLY) {
        return Some(format!(
            "This `data-act` value is in curly quotes (“ ”), as a word processor types them; \
             HTML needs straight quotes, so the label would be `{value}`. Write \
             `data-act=\"{label}\"`."
        ));
    }
    if !value.contains(BREAKS) {
        return None;
    }
    let shown: String = value.chars().take(40).collect();
    let shown = shown.replace(['\n', '\r'], " ");
    let more = if value.chars().count() > 40 {
        "…"
    } else {
        ""
    };
    Some(format!(
        "The quotes around this `data-act` value do not match, so the browser reads the label \
         as `{shown}{more}` (and may swallow what follows). Write `data-act=\"{label}\"`, with \
         a straight quote on each side."
    ))
}

fn check_act_after(source: &SourceText, after: &Value, has_act: bool, out: &mut Vec<Diagnostic>) {
    let pos = source.pos(after.at);
    if !has_act {
        let message = "`data-act-after` only works on an element that also has `data-act`, \
                       which names the act to trigger: add `data-act=\"LABEL\"` to this \
                       element.";
        out.push(Diagnostic::error(
            DiagnosticCode::ActAfterWithoutAct,
            &pos,
            message,
        ));
    } else if act_delay(&after.text).is_none() {
        let message = format!(
            "`{}` is not a delay the page script can read, so the act would never be \
             triggered. Write a number and a unit, without anything else: `500ms`, `20s`, \
             `1.5s` or `1m`.",
            after.text
        );
        out.push(Diagnostic::error(
            DiagnosticCode::BadActDelay,
            &pos,
            message,
        ));
    }
}

/// Pages are UTF-8: a page declaring another character set shows letters wrongly, and one
/// declaring none leaves the browser guessing.
fn check_charset(source: &SourceText, charsets: &[Value], out: &mut Vec<Diagnostic>) {
    for charset in charsets {
        let name = charset.text.trim();
        if name.is_empty()
            || name.eq_ignore_ascii_case("utf-8")
            || name.eq_ignore_ascii_case("utf8")
        {
            continue;
        }
        let message = format!(
            "This page says its character set is `{name}`, but Docent pages are UTF-8: \
             letters such as ä, é or ß would show wrongly. Write `<meta charset=\"utf-8\">` \
             instead (and keep saving the file as UTF-8)."
        );
        out.push(Diagnostic::error(
            DiagnosticCode::PageCharset,
            &source.pos(charset.at),
            message,
        ));
    }
    if charsets.iter().all(|c| c.text.trim().is_empty()) && !source.text.is_ascii() {
        let message = "This page has letters beyond plain English but does not say it is \
                       UTF-8, so the browser may guess and show `Ã¶` instead of `ö`. Add \
                       `<meta charset=\"utf-8\">` at the start of `<head>`.";
        out.push(Diagnostic::warning(
            DiagnosticCode::PageCharset,
            &source.pos(0),
            message,
        ));
    }
}

fn report_unclosed(source: &SourceText, unclosed: &Unclosed, out: &mut Vec<Diagnostic>) {
    let hidden = source.text.get(unclosed.hides_from..).unwrap_or_default();
    let buttons = hidden.matches("data-act=").count();
    let first = source.pos(unclosed.hides_from).line;
    let last = source.pos(source.text.len()).line;
    let lines = if first == last {
        format!("line {first}")
    } else {
        format!("lines {first} to {last}")
    };
    let including = match buttons {
        0 => String::new(),
        1 => ", including a `data-act` button".to_owned(),
        n => format!(", including {n} `data-act` buttons"),
    };
    let message = if unclosed.what == "comment" {
        format!(
            "This comment (`<!--`) is never closed with `-->`, so everything after it to the \
             end of the file ({lines}{including}) is hidden from visitors. Close the comment \
             with `-->` where it should end."
        )
    } else {
        let name = &unclosed.what;
        format!(
            "This `<{name}>` is never closed with `</{name}>`, so everything after it to the \
             end of the file ({lines}{including}) is taken as its content and never shown. \
             Add `</{name}>` where it should end."
        )
    };
    out.push(Diagnostic::error(
        DiagnosticCode::PageHiddenContent,
        &source.pos(unclosed.at),
        message,
    ));
}
