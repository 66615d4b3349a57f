//! The bundle of the speech-channel tests (`channel_policies`, `flood`).

use super::TempBundle;

/// A text that speaks far longer than any test waits.
pub const LONG_TEXT: &str = "This sentence goes on and on, far longer than any test would wait for it, one two three four five six seven eight nine ten eleven twelve thirteen fourteen fifteen sixteen seventeen eighteen nineteen twenty twenty-one twenty-two twenty-three twenty-four twenty-five twenty-six twenty-seven twenty-eight twenty-nine thirty and more words until the end.";

/// Acts that speak long (LONG, READ), greet (HELLO) and show the map page (MAP), with a
/// home page offering READ, HELLO and MAP, on the log speech adapter.
pub fn bundle() -> TempBundle {
    let acts = format!(
        "- Label: LONG\n  Text: [\"{LONG_TEXT}\"]\n- Label: READ\n  Text: [\"{LONG_TEXT} Read.\"]\n\
         - Label: HELLO\n  Text: [Hello]\n- Label: MAP\n  Cmds: [DISPLAY_PAGE map.html]\n"
    );
    TempBundle::new(&acts)
        .with_file("docent.yaml", "speech: {adapter: log, rate: 120}\n")
        .with_file(
            "pages/index.html",
            "<!doctype html><title>home</title><button data-act=\"READ\">Read</button>\
             <button data-act=\"HELLO\">Hi</button><a href=\"map.html\">Map</a>\
             <button data-act=\"MAP\">Map</button>",
        )
        .with_file("pages/map.html", "<!doctype html><title>map</title>")
}
