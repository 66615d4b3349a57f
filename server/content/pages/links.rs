//! Where a link in a page leads, as the kiosk's browser resolves it: relative to the page's
//! own folder under `/pages/`, or absolute (`/pages/...`, `/media/...`); fragments and query
//! strings play no part. Also splits `srcset` lists and finds CSS `url()`s.

use crate::paths::BundleArea;

/// Where a link leads.
#[derive(Debug, PartialEq, Eq)]
pub(crate) enum Target {
    /// A file of the bundle, to check through the bundle gate.
    Bundle {
        /// `pages/` or `media/`.
        area: BundleArea,
        /// Percent-decoded path inside the area.
        rel: String,
    },
    /// An address on the internet (`http:`, `https:`, `//host`).
    Internet,
    /// A path on the author's own computer (`file:`, `C:\...`).
    OwnComputer,
    /// A path on the Docent server outside the bundle's folders (`/static/...` is the
    /// server's own and fine; anything else is reported).
    Server {
        /// The resolved path.
        path: String,
    },
    /// Nothing to check: `#top`, `data:`, `mailto:`, `javascript:` and the like.
    NotAFile,
}

/// Where `link`, written in the page `page` (its path inside `pages/`), leads.
pub(crate) fn resolve(page: &str, link: &str) -> Target {
    let link = link.trim_matches(|c: char| c.is_ascii_whitespace());
    if link.is_empty() || link.starts_with('#') {
        return Target::NotAFile;
    }
    if link.starts_with("//") || link.starts_with("\\\\") {
        return Target::Internet;
    }
    if let Some(scheme) = scheme(link) {
        return match scheme.as_str() {
            "http" | "https" | "ftp" | "ws" | "wss" => Target::Internet,
            "file" => Target::OwnComputer,
            s if s.len() == 1 => Target::OwnComputer, // `C:\Users\...`
            _ => Target::NotAFile,
        };
    }
    // Browsers read `\` as `/` in web addresses.
    let link = link.replace('\\', "/");
    let end = link.find(['?', '#']).unwrap_or(link.len());
    let path = &link[..end];
    if path.is_empty() {
        return Target::NotAFile; // `?v=2` alone: the page itself.
    }
    let joined = if path.starts_with('/') {
        path.to_owned()
    } else {
        let folder = page.rsplit_once('/').map_or("", |(folder, _)| folder);
        if folder.is_empty() {
            format!("/pages/{path}")
        } else {
            format!("/pages/{folder}/{path}")
        }
    };
    let resolved = without_dot_segments(&joined);
    for area in [BundleArea::Pages, BundleArea::Media] {
        let prefix = format!("/{}/", area.dir_name());
        if let Some(rel) = resolved.strip_prefix(&prefix) {
            let rel = percent_encoding::percent_decode_str(rel)
                .decode_utf8_lossy()
                .into_owned();
            return Target::Bundle { area, rel };
        }
    }
    if resolved.starts_with("/static/") {
        return Target::NotAFile;
    }
    Target::Server { path: resolved }
}

/// The scheme of an absolute URL (`https` in `https://...`), lower case.
fn scheme(link: &str) -> Option<String> {
    let colon = link.find(':')?;
    let scheme = &link[..colon];
    let valid = scheme.starts_with(|c: char| c.is_ascii_alphabetic())
        && scheme
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c));
    valid.then(|| scheme.to_ascii_lowercase())
}

/// `/pages/a/../b/./c` → `/pages/b/c`, as URL resolution does (never above the root).
fn without_dot_segments(path: &str) -> String {
    let mut out: Vec<&str> = Vec::new();
    let segments: Vec<&str> = path.split('/').skip(1).collect();
    for (i, segment) in segments.iter().enumerate() {
        let last = i + 1 == segments.len();
        match *segment {
            "." if last => out.push(""),
            "." => {}
            ".." => {
                out.pop();
                if last {
                    out.push("");
                }
            }
            s => out.push(s),
        }
    }
    format!("/{}", out.join("/"))
}

/// The URLs of a `srcset` list, each with its byte offset in the list (descriptors such as
/// `2x` or `640w` are skipped).
pub(crate) fn srcset_urls(srcset: &str) -> Vec<(&str, usize)> {
    let mut found = Vec::new();
    let mut i = 0;
    let bytes = srcset.as_bytes();
    while i < bytes.len() {
        while i < bytes.len() && (bytes[i].is_ascii_whitespace() || bytes[i] == b',') {
            i += 1;
        }
        let start = i;
        while i < bytes.len() && !bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        let url = srcset[start..i].trim_end_matches(',');
        let ended_by_comma = url.len() < i - start;
        if !url.is_empty() {
            found.push((url, start));
        }
        if !ended_by_comma {
            // Descriptors up to the next comma outside parentheses.
            let mut depth = 0;
            while i < bytes.len() && !(bytes[i] == b',' && depth == 0) {
                match bytes[i] {
                    b'(' => depth += 1,
                    b')' => depth -= 1,
                    _ => {}
                }
                i += 1;
            }
        }
    }
    found
}

/// The URLs in CSS text (`url(...)` and `@import "..."`), each with its byte offset;
/// comments are skipped.
pub(crate) fn css_urls(css: &str) -> Vec<(&str, usize)> {
    let mut found = Vec::new();
    let lower = css.to_ascii_lowercase();
    let mut i = 0;
    while i < css.len() {
        let rest = &lower[i..];
        if rest.starts_with("/*") {
            i = rest.find("*/").map_or(css.len(), |n| i + n + 2);
        } else if rest.starts_with("url(") {
            i += 4;
            if let Some((url, at, end)) = css_value(css, i, true) {
                found.push((url, at));
                i = end;
            }
        } else if rest.starts_with("@import") {
            i += "@import".len();
            if let Some((url, at, end)) = css_value(css, i, false) {
                found.push((url, at));
                i = end;
            }
        } else {
            i += rest.chars().next().map_or(1, char::len_utf8);
        }
    }
    found
}

/// A quoted string, or an unquoted `url(` body when `bare` is allowed, starting at `i`.
fn css_value(css: &str, i: usize, bare: bool) -> Option<(&str, usize, usize)> {
    let body = &css[i..];
    let start = i + (body.len() - body.trim_start().len());
    let body = &css[start..];
    match body.chars().next()? {
        q @ ('"' | '\'') => {
            let len = body[1..].find(q)?;
            Some((&body[1..1 + len], start + 1, start + 2 + len))
        }
        _ if bare => {
            let len = body.find(')')?;
            Some((body[..len].trim_end(), start, start + len))
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bundle(area: BundleArea, rel: &str) -> Target {
        Target::Bundle {
            area,
            rel: rel.to_owned(),
        }
    }

    #[test]
    fn links_resolve_like_a_browser() {
        use BundleArea::{Media, Pages};
        assert_eq!(
            resolve("tour/a.html", "b.html"),
            bundle(Pages, "tour/b.html")
        );
        assert_eq!(
            resolve("tour/a.html", "../img/x.png?v=2#top"),
            bundle(Pages, "img/x.png")
        );
        assert_eq!(
            resolve("a.html", "../media/Film%20One.webm"),
            bundle(Media, "Film One.webm")
        );
        assert_eq!(resolve("a.html", "/media/x.png"), bundle(Media, "x.png"));
        assert_eq!(resolve("a.html", "img\\x.png"), bundle(Pages, "img/x.png"));
        assert_eq!(
            resolve("a.html", "../../x.png"),
            Target::Server {
                path: "/x.png".into()
            }
        );
        assert_eq!(resolve("a.html", "https://example.org"), Target::Internet);
        assert_eq!(
            resolve("a.html", "C:\\Users\\me\\x.png"),
            Target::OwnComputer
        );
        for not_a_file in [
            "#top",
            "",
            "mailto:a@b",
            "tel:1",
            "data:image/png;base64,x",
            "javascript:void(0)",
            "/static/docent.css",
        ] {
            assert_eq!(
                resolve("a.html", not_a_file),
                Target::NotAFile,
                "{not_a_file}"
            );
        }
    }

    #[test]
    fn srcset_candidates_skip_descriptors() {
        assert_eq!(
            srcset_urls("a.png 1x, b.png 2x,c.png,d.png"),
            [("a.png", 0), ("b.png", 10), ("c.png,d.png", 19)]
        );
        assert_eq!(srcset_urls(" x.png 640w"), [("x.png", 1)]);
        assert_eq!(srcset_urls("a.png, b.png"), [("a.png", 0), ("b.png", 7)]);
    }

    #[test]
    fn css_urls_in_any_quoting() {
        let css = "/* url(no.png) */ a { background: URL( 'a.png' ) } b { src: url(b.woff) }\n@import \"c.css\";";
        let found: Vec<&str> = css_urls(css).into_iter().map(|f| f.0).collect();
        assert_eq!(found, ["a.png", "b.woff", "c.css"]);
        assert_eq!(css_urls("x{background:url(a.png)}"), [("a.png", 17)]);
    }
}
