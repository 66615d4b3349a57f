//! `data-act-after` delays, read once by the server. A page's timer element
//! (`<div data-act="NEXT" data-act-after="20s">`) is served with the delay the checker
//! accepted added as `data-act-after-ms="20000"`; the page script only reads that number, so
//! the rule for writing delays exists once, in `content::act_delay`, and `docent check` and the
//! running page cannot disagree. A delay the rule cannot read gets no `-ms` attribute: the
//! page script warns, and `docent check` has reported it (`bad-act-delay`).

use lol_html::{HtmlRewriter, Settings, element};

use crate::content::act_delay;

/// The attribute the page script reads.
const MS_ATTRIBUTE: &str = "data-act-after-ms";

/// `page` with each readable `data-act-after` delay added in milliseconds; the page as it is
/// when it has none (most pages) or when it cannot be rewritten.
pub(crate) fn with_act_timers(page: Vec<u8>) -> Vec<u8> {
    if !page
        .windows(b"data-act-after".len())
        .any(|w| w.eq_ignore_ascii_case(b"data-act-after"))
    {
        return page;
    }
    let mut out = Vec::with_capacity(page.len() + 64);
    let handler = element!("[data-act-after]", |el| {
        let delay = el
            .get_attribute("data-act-after")
            .and_then(|d| act_delay(&d));
        el.remove_attribute(MS_ATTRIBUTE);
        if let Some(delay) = delay {
            el.set_attribute(MS_ATTRIBUTE, &delay.as_millis().to_string())?;
        }
        Ok(())
    });
    let settings = Settings::new().append_element_content_handler(handler);
    let mut rewriter = HtmlRewriter::new(settings, |chunk: &[u8]| out.extend_from_slice(chunk));
    if rewriter.write(&page).is_err() || rewriter.end().is_err() {
        return page;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rewritten(page: &str) -> String {
        String::from_utf8(with_act_timers(page.as_bytes().to_vec())).expect("utf-8")
    }

    #[test]
    fn readable_delays_are_added_in_milliseconds_and_others_are_not() {
        assert_eq!(
            rewritten(r#"<div data-act="A" data-act-after="1.5s"></div>"#),
            r#"<div data-act="A" data-act-after="1.5s" data-act-after-ms="1500"></div>"#
        );
        assert_eq!(
            rewritten(r#"<div data-act="A" data-act-after="5 sec" data-act-after-ms="9"></div>"#),
            r#"<div data-act="A" data-act-after="5 sec"></div>"#
        );
        assert_eq!(rewritten("<p>no timers</p>"), "<p>no timers</p>");
    }
}
