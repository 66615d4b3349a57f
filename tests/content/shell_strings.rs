//! The kiosk shell's own words (`content::shell_strings`, `kiosk: strings:`): a declared
//! language without them is a located warning, a site's words fill it, an unknown key is
//! told with its suggestion, and the table the shell gets has every declared language.

use crate::common;

use common::check::{bundle, check, loaded, only};
use docent_content::Severity;
use docent_content::shell_strings::{ShellString, shell_table};

const ACTS: (&str, &str) = (
    "acts.yaml",
    "- Label: HELLO\n  Text: [Hello]\n  Text@sv: [Hej]\n",
);
const HOME: (&str, &str) = (
    "pages/index.html",
    "<!doctype html><html lang=\"en\"><title>Hall</title><button data-act=\"HELLO\">Hi</button>\
     <button data-language=\"sv\">Svenska</button></html>",
);

const SWEDISH: &str = "languages: [en, sv]\nkiosk:\n  strings:\n    sv:\n      starting: Startar…\n      \
                       stop: Sluta tala\n      already_speaking: Jag pratar redan om det här.\n      \
                       cannot_say: Roboten kan inte säga det nu.\n      one_moment: Ett ögonblick.\n      \
                       language_offline: \"Ingen anslutning: språket byttes inte.\"\n      \
                       language_unavailable: Det här språket finns inte här.\n";

#[test]
fn a_declared_language_without_shell_words_is_a_warning_at_the_language() {
    let dir = bundle(&[("docent.yaml", "languages: [en, sv]\n"), ACTS, HOME]);
    let report = check(dir.path());
    let missing = only(&report, "shell-strings-missing");
    assert_eq!(missing.len(), 1, "{:#?}", report.diagnostics);
    let warning = missing[0];
    assert_eq!(warning.severity, Severity::Warning);
    assert_eq!(
        (warning.file.as_str(), warning.line, warning.column),
        ("docent.yaml", 1, 17)
    );
    for string in ShellString::ALL {
        assert!(
            warning.message.contains(string.key()),
            "{}",
            warning.message
        );
    }
    assert!(
        warning.message.contains("kiosk: {strings: {sv:"),
        "{}",
        warning.message
    );
}

#[test]
fn a_sites_words_give_the_shell_a_language_it_lacks() {
    let dir = bundle(&[("docent.yaml", SWEDISH), ACTS, HOME]);
    let report = check(dir.path());
    assert_eq!(
        only(&report, "shell-strings-missing").len(),
        0,
        "{:#?}",
        report.diagnostics
    );
    let bundle = loaded(report);
    let table = shell_table(&bundle.config);
    assert_eq!(table["stop"]["sv"], "Sluta tala");
    assert_eq!(table["stop"]["en"], "Stop speaking");
    assert_eq!(
        table["language_offline"]["sv"],
        "Ingen anslutning: språket byttes inte."
    );
}

#[test]
fn a_regional_tag_reads_its_languages_built_in_words() {
    let acts = (
        "acts.yaml",
        "- Label: HELLO\n  Text: [Hello]\n  Text@de-ch: [Grüezi]\n",
    );
    let dir = bundle(&[("docent.yaml", "languages: [en, de-ch]\n"), acts]);
    let report = check(dir.path());
    assert_eq!(
        only(&report, "shell-strings-missing").len(),
        0,
        "{:#?}",
        report.diagnostics
    );
    let table = shell_table(&loaded(report).config);
    assert_eq!(
        table["cannot_say"]["de-ch"],
        "Das kann der Roboter gerade nicht sagen."
    );
}

#[test]
fn an_unknown_shell_word_is_told_with_its_suggestion() {
    let config = "languages: [en, de]\nkiosk:\n  strings:\n    de: {stopp: Halt}\n";
    let dir = bundle(&[("docent.yaml", config), ACTS]);
    let report = check(dir.path());
    let unknown = only(&report, "config-unknown-key");
    assert_eq!(unknown.len(), 1, "{:#?}", report.diagnostics);
    assert_eq!((unknown[0].line, unknown[0].column), (4, 10));
    assert!(
        unknown[0].message.contains("`stop`"),
        "{}",
        unknown[0].message
    );
}
