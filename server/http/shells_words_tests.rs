//! The kiosk shell's words for visitors: every declared language in its table, the default
//! language's words in the page before the script runs, and none written in its scripts.

use crate::content::config::SiteConfig;
use crate::content::shell_strings::{ShellString, shell_table};
use crate::content::{Language, Languages};
use crate::http::shells::KioskShell;

use askama::Template;

#[test]
fn the_kiosk_shell_gets_its_words_in_every_declared_language() {
    let list = ["de", "en"].map(|t| Language::parse(t).expect("tag"));
    let config = SiteConfig {
        languages: Languages::new(list.to_vec()).expect("languages"),
        ..SiteConfig::default()
    };
    let page = KioskShell::new(&config, "").render().expect("renders");
    // Until the script runs: the default language's words, never English on a German kiosk.
    assert!(
        page.contains(r#"type="button" lang="de" hidden>Nicht mehr sprechen</button>"#),
        "{page}"
    );
    assert!(!page.contains(">Stop speaking</button>"), "{page}");
    let table = shell_table(&config);
    for string in ShellString::ALL {
        let texts = &table[string.key()];
        assert_eq!(
            texts.keys().collect::<Vec<_>>(),
            ["de", "en"],
            "{}",
            string.key()
        );
        assert!(texts.values().all(|t| !t.is_empty()), "{}", string.key());
    }
    assert!(
        page.contains("data-strings=\"{&#34;already_speaking&#34;:"),
        "{page}"
    );
}

/// Every word a visitor reads comes from the table: no shell script writes one itself (a
/// literal starting with a capitalised word and going on with another, outside comments,
/// the browser's log and protocol messages, is taken for one).
#[test]
fn no_shell_script_writes_words_for_visitors() {
    let scripts = [
        "kiosk.js",
        "speech-state.js",
        "speech.js",
        "caption.js",
        "attract.js",
        "overlay.js",
        "outage.js",
        "language.js",
        "shell-text.js",
        "schedule.js",
        "docent-page.js",
        "socket.js",
        "client-name.js",
        "recorder.js",
        "camera-kiosk.js",
    ];
    let mut found = Vec::new();
    for name in scripts {
        let (_, source) = crate::http::static_files::lookup(name).expect(name);
        for (n, line) in source.lines().enumerate() {
            let code = line.trim_start();
            if ["//", "*", "/*"].iter().any(|c| code.starts_with(c)) || line.contains("console.") {
                continue;
            }
            for literal in visitor_literals(line) {
                found.push(format!("{name}:{}: {literal}", n + 1));
            }
        }
    }
    assert!(
        found.is_empty(),
        "words for visitors outside the shell's table: {found:#?}"
    );
}

/// The quoted texts of `line` that read like words for people: `"Stop speaking"`, not
/// `"docent-stop-speech"`, and not a protocol frame's `message: "..."`.
fn visitor_literals(line: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut rest = line;
    while let Some(start) = rest.find(['"', '`']) {
        let quote = rest[start..].chars().next().unwrap_or('"');
        let after = &rest[start + 1..];
        let Some(end) = after.find(quote) else { break };
        let literal = &after[..end];
        let before = rest[..start].trim_end();
        let mut words = literal.split(' ');
        let first = words.next().unwrap_or_default();
        let capitalised = first.chars().next().is_some_and(char::is_uppercase)
            && first.chars().skip(1).all(char::is_lowercase)
            && first.len() > 1;
        let more = words
            .next()
            .is_some_and(|w| w.starts_with(char::is_lowercase));
        if capitalised && more && !before.ends_with("message:") {
            out.push(literal);
        }
        rest = &after[end + 1..];
    }
    out
}
