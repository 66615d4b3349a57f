//! One pass of a real HTML5 tokenizer (lol_html) over a page, collecting what the checks
//! need, each with its byte offset in the page: `data-act` and `data-act-after` values,
//! links, CSS, inline scripts, charset declarations, and comments or elements left open
//! that swallow the rest of the page.

use std::cell::RefCell;
use std::rc::Rc;

use lol_html::html_content::{Comment, Element, TextChunk};
use lol_html::{HtmlRewriter, Settings, doc_comments, element, text};

/// `data-act-after`, written in two parts so the guide's code test does not take the
/// attribute name for a diagnostic code.
const ACT_AFTER: &str = concat!("data-act", "-after");
/// `data-language`, split for the same reason.
const LANGUAGE: &str = concat!("data", "-language");
/// `http-equiv`, split for the same reason.
const HTTP_EQUIV: &str = concat!("http", "-equiv");
/// `content-type`, split for the same reason.
const CONTENT_TYPE: &str = concat!("content", "-type");

/// An attribute value and where it starts in the page.
#[derive(Debug, PartialEq, Eq)]
pub(crate) struct Value {
    /// The value as written (entities are not decoded).
    pub text: String,
    /// Byte offset of the value (after its opening quote), or of the attribute name when
    /// it has no value.
    pub at: usize,
}

/// What a linked file is used for, which decides how it is checked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LinkUse {
    /// `<a href>`, `<area href>`: a tap follows it.
    Navigate,
    /// Style sheets, scripts, frames, fonts: must exist.
    Resource,
    /// `<img>`, `srcset`, `poster`, CSS pictures: must exist and be a picture Chromium shows.
    Image,
    /// `<video>`, `<audio>`, `<source src>`: must exist and play in Chromium.
    Player,
}

/// A link to another file, as written.
#[derive(Debug, PartialEq, Eq)]
pub(crate) struct Link {
    /// The URL (one `srcset` candidate is split out later).
    pub value: Value,
    /// What the file is used for.
    pub used: LinkUse,
    /// Whether the value is a `srcset` list rather than one URL.
    pub srcset: bool,
}

/// A comment or element that is never closed and so hides the rest of the page.
#[derive(Debug, PartialEq, Eq)]
pub(crate) struct Unclosed {
    /// `comment`, or the element's name.
    pub what: String,
    /// Byte offset of its opening `<`.
    pub at: usize,
    /// Byte offset where its own opening tag ends: what follows is hidden.
    pub hides_from: usize,
}

/// Everything one page holds that the checks look at.
#[derive(Debug, Default)]
pub(crate) struct PageScan {
    /// `data-act` values.
    pub acts: Vec<Value>,
    /// `data-language` values: buttons that switch the visitor's language.
    pub languages: Vec<Value>,
    /// `data-act-after` values, with whether the same element has `data-act`.
    pub act_afters: Vec<(Value, bool)>,
    /// Start tags that run into the next tag because their `>` is missing: where the `>`
    /// belongs (`text`: the element's name), and what the tag swallowed.
    pub tags_without_end: Vec<(Value, String)>,
    /// Attributes that look like a slip for `data-act` (`data-action`, `data_act`, `act`) on
    /// an element without `data-act`: the name at its place, and the value.
    pub act_typos: Vec<(Value, String)>,
    /// Links to other files.
    pub links: Vec<Link>,
    /// CSS text (`<style>` blocks and `style` attributes) and its offset.
    pub css: Vec<Value>,
    /// Inline script text and its offset.
    pub scripts: Vec<Value>,
    /// Declared character sets (`<meta charset>`, `http-equiv` content).
    pub charsets: Vec<Value>,
    /// Comments and elements never closed.
    pub unclosed: Vec<Unclosed>,
    /// Why the tokenizer stopped early, if it did.
    pub stopped: Option<String>,
    /// The `<html lang>` value: the language the page says it is in.
    pub lang: Option<Value>,
    /// `autoplay` attributes of `<video>` and `<audio>` elements without `muted`: sound
    /// that starts by itself. `text` is the element's name.
    pub autoplay_sound: Vec<Value>,
    /// Form elements (`<form>`, `<input>`, `<textarea>`, `<select>`), at their `<`; `text`
    /// is the element's name.
    pub form_fields: Vec<Value>,
}

/// Elements whose content is text up to their own end tag (or inert, for `template`): left
/// open, they swallow everything after them.
const SWALLOWING: &[&str] = &[
    "script",
    "style",
    "textarea",
    "title",
    "template",
    "xmp",
    "iframe",
    "noembed",
    "noframes",
    "noscript",
    "plaintext",
];

/// Reads `html` (UTF-8, without byte-order mark).
pub(crate) fn scan(html: &str) -> PageScan {
    let found = RefCell::new(PageScan::default());
    // Open swallowing elements: (index into `unclosed` candidates, closed yet).
    let open: Rc<RefCell<Vec<(Unclosed, bool)>>> = Rc::default();
    let source = html.as_bytes();
    let settings = Settings::new()
        .append_element_content_handler(element!("*", |el| {
            read_element(el, &mut found.borrow_mut());
            missing_tag_end(el, source, &mut found.borrow_mut());
            watch_closing(el, &open);
            Ok(())
        }))
        .append_document_content_handler(doc_comments!(|c| {
            unclosed_comment(c, source, &mut found.borrow_mut());
            Ok(())
        }))
        .append_element_content_handler(text!("style", |t| {
            gather(t, &mut found.borrow_mut().css);
            Ok(())
        }))
        .append_element_content_handler(text!("script:not([src])", |t| {
            gather(t, &mut found.borrow_mut().scripts);
            Ok(())
        }));
    let mut rewriter = HtmlRewriter::new(settings, |_: &[u8]| {});
    let result = rewriter.write(source).and_then(|()| rewriter.end());
    let mut found = found.into_inner();
    if let Err(e) = result {
        found.stopped = Some(e.to_string());
    }
    found.unclosed.extend(
        open.take()
            .into_iter()
            .filter(|(_, closed)| !closed)
            .map(|(unclosed, _)| unclosed),
    );
    found.unclosed.sort_by_key(|u| u.at);
    found
}

/// Notes a swallowing element until its end tag shows up.
fn watch_closing(el: &mut Element<'_, '_>, open: &Rc<RefCell<Vec<(Unclosed, bool)>>>) {
    let name = el.tag_name();
    if !SWALLOWING.contains(&name.as_str()) || el.is_self_closing() && name == "template" {
        return;
    }
    let tag = el.source_location().bytes();
    let index = {
        let mut open = open.borrow_mut();
        open.push((
            Unclosed {
                what: name,
                at: tag.start,
                hides_from: tag.end,
            },
            false,
        ));
        open.len() - 1
    };
    let open = Rc::clone(open);
    // Not called for an element the end of the file closes: that is the one to report.
    let _ = el.on_end_tag(Box::new(move |_| {
        if let Some(entry) = open.borrow_mut().get_mut(index) {
            entry.1 = true;
        }
        Ok(())
    }));
}

fn read_element(el: &Element<'_, '_>, found: &mut PageScan) {
    let name = el.tag_name();
    read_behaviour(el, &name, found);
    let mut has_act = false;
    let mut typos = Vec::new();
    let mut after = None;
    let mut http_equiv = false;
    let mut content = None;
    for attr in el.attributes() {
        let attr_name = attr.name();
        let at = attr
            .value_source_location()
            .or_else(|| attr.name_source_location())
            .map_or(0, |l| l.bytes().start);
        let value = Value {
            text: attr.value(),
            at,
        };
        let used = link_use(&name, &attr_name);
        match attr_name.as_str() {
            "data-act" => {
                has_act = true;
                found.acts.push(value);
            }
            n if n == ACT_AFTER => after = Some(value),
            n if n == LANGUAGE => found.languages.push(value),
            "style" => found.css.push(value),
            "charset" if name == "meta" => found.charsets.push(value),
            "content" if name == "meta" => content = Some(value),
            n if n == HTTP_EQUIV && name == "meta" => {
                http_equiv = attr.value().eq_ignore_ascii_case(CONTENT_TYPE);
            }
            "srcset" => found.links.push(Link {
                value,
                used: LinkUse::Image,
                srcset: true,
            }),
            n if act_attribute_typo(n) => {
                let at = (attr.name_source_location()).map_or(0, |l| l.bytes().start);
                let name = Value {
                    text: attr_name.clone(),
                    at,
                };
                typos.push((name, value.text));
            }
            _ => {
                if let Some(used) = used {
                    found.links.push(Link {
                        value,
                        used,
                        srcset: false,
                    });
                }
            }
        }
    }
    if let Some(after) = after {
        found.act_afters.push((after, has_act));
    }
    if !has_act {
        found.act_typos.extend(typos);
    }
    if let (true, Some(content)) = (http_equiv, content) {
        found.charsets.push(charset_in_content(content));
    }
}

/// `<button data-act="WELCOME"Say hello</button>`: a start tag whose `>` is missing runs into
/// the next tag, and its text becomes attributes (one named `hello<`). The `>` belongs after
/// the last value written before that, or after the element's name.
fn missing_tag_end(el: &Element<'_, '_>, source: &[u8], found: &mut PageScan) {
    let attributes = el.attributes();
    let Some(slip) = attributes.iter().position(|a| a.name().contains('<')) else {
        return;
    };
    let tag = el.source_location().bytes();
    let name = el.tag_name();
    let after_value = attributes[..slip]
        .iter()
        .rev()
        .find_map(|a| a.value_source_location())
        .map(|l| l.bytes().end);
    let at = match after_value {
        Some(end) if matches!(source.get(end), Some(b'"' | b'\'')) => end + 1,
        Some(end) => end,
        None => tag.start + 1 + name.len(),
    };
    let swallowed = source
        .get(at..tag.end.saturating_sub(1))
        .unwrap_or_default();
    let swallowed: String = String::from_utf8_lossy(swallowed)
        .trim()
        .chars()
        .take(60)
        .collect();
    found
        .tags_without_end
        .push((Value { text: name, at }, swallowed));
}

/// Whether an attribute named `name` is likely a slip for `data-act`: one letter off
/// (`data_act`, `data-acts`, `date-act`, `dataact`), or a name a new author guesses
/// (`act`, `data-action`, `data-label`).
fn act_attribute_typo(name: &str) -> bool {
    const GUESSES: [&str; 4] = ["act", "data-action", "data-label", "data-act-label"];
    // Within two edits of `data-act`: only names of 6 to 10 letters need comparing.
    let near_length = (6..=10).contains(&name.len());
    name != "data-act"
        && name != ACT_AFTER
        && name != LANGUAGE
        && (GUESSES.contains(&name)
            || near_length && crate::suggest::closest(name, ["data-act"]).is_some())
}

/// What the page does on its own: its declared language, sound that starts by itself, and
/// fields a visitor fills in.
fn read_behaviour(el: &Element<'_, '_>, name: &str, found: &mut PageScan) {
    let attribute = |wanted: &str| el.attributes().iter().find(|a| a.name() == wanted);
    match name {
        "html" => {
            if let Some(lang) = attribute("lang") {
                let at = (lang.value_source_location())
                    .or_else(|| lang.name_source_location())
                    .map_or(0, |l| l.bytes().start);
                found.lang = Some(Value {
                    text: lang.value(),
                    at,
                });
            }
        }
        "video" | "audio" if attribute("muted").is_none() => {
            // At the attribute's name: `autoplay` usually has no value.
            if let Some(autoplay) = attribute("autoplay") {
                found.autoplay_sound.push(Value {
                    text: name.to_owned(),
                    at: autoplay
                        .name_source_location()
                        .map_or(0, |l| l.bytes().start),
                });
            }
        }
        // A hidden input is filled by the page, not by a visitor.
        "input" if attribute("type").is_some_and(|t| t.value().eq_ignore_ascii_case("hidden")) => {}
        "form" | "input" | "textarea" | "select" => found.form_fields.push(Value {
            text: name.to_owned(),
            at: el.source_location().bytes().start,
        }),
        _ => {}
    }
}

/// The `charset=` part of a `Content-Type` value, with its offset.
fn charset_in_content(content: Value) -> Value {
    let lower = content.text.to_ascii_lowercase();
    match lower.find("charset=") {
        Some(i) => {
            let start = i + "charset=".len();
            let rest = &content.text[start..];
            let end = rest.find([';', ' ']).unwrap_or(rest.len());
            Value {
                text: rest[..end].trim_matches(['"', '\'']).to_owned(),
                at: content.at + start,
            }
        }
        None => Value {
            text: String::new(),
            at: content.at,
        },
    }
}

/// Which attributes of which elements link to a file.
fn link_use(element: &str, attr: &str) -> Option<LinkUse> {
    Some(match (element, attr) {
        ("a" | "area", "href") => LinkUse::Navigate,
        ("img", "src") | ("video", "poster") | ("input", "src") => LinkUse::Image,
        ("video" | "audio" | "source", "src") => LinkUse::Player,
        ("link", "href")
        | ("script" | "iframe" | "embed" | "track", "src")
        | ("object", "data") => LinkUse::Resource,
        _ => return None,
    })
}

/// A comment whose source does not end in `-->` ran to the end of the file.
fn unclosed_comment(comment: &Comment<'_>, source: &[u8], found: &mut PageScan) {
    let range = comment.source_location().bytes();
    let Some(raw) = source.get(range.clone()) else {
        return;
    };
    if raw.starts_with(b"<!--") && !raw.ends_with(b"-->") && !raw.ends_with(b"--!>") {
        found.unclosed.push(Unclosed {
            what: "comment".to_owned(),
            at: range.start,
            hides_from: range.start + 4,
        });
    }
}

/// Appends a text chunk to the text of its element (a new entry for a new element).
fn gather(chunk: &TextChunk<'_>, into: &mut Vec<Value>) {
    let at = chunk.source_location().bytes().start;
    match into.last_mut() {
        Some(last) if last.at + last.text.len() == at && !last.text.is_empty() => {
            last.text.push_str(chunk.as_str());
        }
        _ if chunk.as_str().is_empty() => {}
        _ => into.push(Value {
            text: chunk.as_str().to_owned(),
            at,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_acts_links_and_styles_with_offsets() {
        let html = "<a data-act='OK' href=x.html style=\"background: url(a.png)\">ok</a>\
                    <style>p{}</style><script>docent.trigger('A')</script>";
        let found = scan(html);
        assert_eq!(
            found.acts,
            [Value {
                text: "OK".into(),
                at: 13
            }]
        );
        assert_eq!(found.links[0].value.at, html.find("x.html").expect("link"));
        assert_eq!(found.css.len(), 2);
        assert_eq!(found.css[1].text, "p{}");
        assert_eq!(found.scripts[0].text, "docent.trigger('A')");
        assert!(found.unclosed.is_empty(), "{:?}", found.unclosed);
    }

    #[test]
    fn finds_what_is_left_open() {
        let found = scan("<p>a</p>\n<!-- old\n<button data-act=X>");
        assert_eq!(found.unclosed[0].what, "comment");
        assert_eq!(found.unclosed[0].at, 9);
        assert!(found.acts.is_empty());
        let found = scan("<title>T</title><script>let a = 1;\n<button data-act=X>");
        assert_eq!(found.unclosed.len(), 1);
        assert_eq!(found.unclosed[0].what, "script");
        let found = scan("<template><p>x</p></template><template><b>y</b>");
        assert_eq!(found.unclosed.len(), 1);
        assert_eq!(found.unclosed[0].at, 29);
    }
}
