//! SVG drawings shown as pictures (the projector, `<img>`, CSS): a browser runs no script in
//! a picture, so a drawing a script makes stays blank (`svg-script`).

use std::io::Read;
use std::path::Path;

use crate::DiagnosticCode;
use crate::diagnostic::Diagnostic;
use crate::model::Pos;

use super::MediaSniffs;

/// How much of an SVG is read to look for a script (drawings are rarely larger).
const SVG_READ_BYTES: u64 = 4 << 20;

/// The first script in an SVG's text, as found (`<script>`, `onload=`), if any.
fn svg_script(text: &str) -> Option<String> {
    let lower = text.to_ascii_lowercase();
    if lower.contains("<script") {
        return Some("`<script>`".to_owned());
    }
    // An event handler attribute: white space, `on`, letters, `=`.
    let bytes = lower.as_bytes();
    (1..bytes.len().saturating_sub(2))
        .filter(|&i| bytes[i - 1].is_ascii_whitespace() && bytes[i..].starts_with(b"on"))
        .find_map(|at| {
            let end = (at + 2..bytes.len())
                .find(|&i| !bytes[i].is_ascii_lowercase())
                .unwrap_or(bytes.len());
            (end > at + 2 && bytes.get(end) == Some(&b'='))
                .then(|| format!("`{}=`", &lower[at..end]))
        })
}

impl MediaSniffs {
    /// Warns, once per file, when an SVG shown as a picture has a script: it never runs there.
    /// The file is read once; each use is noted, and the first in the bundle's order told.
    pub(super) fn scripted_svg(&self, path: &Path, shown: &str, pos: &Pos) {
        let script = (self.scripts.borrow_mut().entry(path.to_owned()))
            .or_insert_with(|| {
                let mut text = Vec::new();
                let file = std::fs::File::open(path).ok()?;
                file.take(SVG_READ_BYTES).read_to_end(&mut text).ok()?;
                svg_script(&String::from_utf8_lossy(&text))
            })
            .clone();
        let Some(script) = script else {
            return;
        };
        let message = format!(
            "`{shown}` has a script ({script}), but the projector and a page's pictures show an \
             SVG as a picture, and a browser runs no script in a picture: what the script would \
             draw or animate stays blank. Open the drawing in its program and export it as a \
             plain SVG or PNG, or put the animation into the page itself."
        );
        let told = Diagnostic::warning(DiagnosticCode::SvgScript, pos, message);
        self.once.borrow_mut().push((path.to_owned(), told));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scripts_in_an_svg_are_found_and_words_are_not() {
        let svg = "<svg>\n<rect\n  onload=\"draw()\"/></svg>";
        assert_eq!(svg_script(svg).as_deref(), Some("`onload=`"));
        assert_eq!(
            svg_script("<svg><SCRIPT>x()</SCRIPT></svg>").as_deref(),
            Some("`<script>`")
        );
        assert_eq!(svg_script("<svg><text>Go on = stay</text></svg>"), None);
        assert_eq!(svg_script("<svg><text>based on the map</text></svg>"), None);
    }
}
