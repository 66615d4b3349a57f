//! The two-language bundle settings the language checks' fixtures share: English and German,
//! a home page with its button to German and the German home page, so that only the problem a
//! test is about is reported.

/// `docent.yaml` of a bundle in English (the default) and German, with a `TextChild` context.
pub const TWO: (&str, &str) = (
    "docent.yaml",
    "languages: [en, de]\ncontexts: [TextChild]\n",
);
/// The home page with its button to German, so that only the problem under test is reported.
pub const HOME: (&str, &str) = (
    "pages/index.html",
    "<!doctype html><title>Start</title><button data-language=\"de\">Deutsch</button>",
);
/// The German home page, so that only the problem under test is reported.
pub const GERMAN_HOME: (&str, &str) =
    ("pages/de/index.html", "<!doctype html><title>Start</title>");
