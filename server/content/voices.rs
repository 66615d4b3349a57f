//! The bundle's languages that no installed espeak-ng voice speaks. One rule for the two
//! places that ask: `docent serve`'s start-up warnings and `docent check` (the `no-voice`
//! warning, at the place the voice or the language was written). The installed voices are
//! handed in (the caller runs `espeak-ng --voices`): content loading itself runs nothing.
//! The check applies whenever espeak-ng would speak ([`espeak_speaks`]): with `speech:
//! {adapter: espeak}` written, and also with no adapter written, the default on a computer
//! where espeak-ng is installed.

use crate::DiagnosticCode;
use crate::config::{AdapterKind, SiteConfig, SpeechConfig};
use crate::diagnostic::Diagnostic;
use crate::language::Language;
use crate::model::Pos;

/// Why espeak-ng speaks a bundle on this computer: the message says so, since without an
/// adapter written the answer depends on the machine.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EspeakChoice {
    /// `speech: {adapter: espeak}` is written.
    Written,
    /// No `speech: adapter` is written and espeak-ng is installed: `docent serve`'s default.
    Default,
}

/// Whether espeak-ng speaks the bundle here, and why: the same rule `docent serve` follows to
/// choose its speech adapter (espeak-ng when written or when nothing is written, but only if it
/// is installed; otherwise speech is only logged). `None` for any other adapter.
pub fn espeak_speaks(speech: &SpeechConfig, espeak_installed: bool) -> Option<EspeakChoice> {
    match speech.adapter {
        _ if !espeak_installed => None,
        Some(AdapterKind::Espeak) => Some(EspeakChoice::Written),
        None => Some(EspeakChoice::Default),
        Some(_) => None,
    }
}

/// Each language whose espeak-ng voice (`speech: voices:`, or its default) is not among
/// `installed`, with that voice.
pub fn unspoken_languages<'c>(
    speech: &'c SpeechConfig,
    installed: &[String],
) -> Vec<(&'c Language, &'c str)> {
    (speech.voices.iter())
        .filter(|(_, voice)| !installed.contains(voice))
        .map(|(language, voice)| (language, voice.as_str()))
        .collect()
}

/// A `no-voice` warning for each language no installed voice speaks, at its entry in `speech:
/// voices:`, else at its place in `languages:`, else at the top of `docent.yaml` (a bundle of
/// one language whose voice is `speech: voice` or the language's own name).
pub fn no_voice_diagnostics(
    config: &SiteConfig,
    installed: &[String],
    choice: EspeakChoice,
) -> Vec<Diagnostic> {
    let place = |language: &Language| {
        (config.voice_places.iter())
            .chain(&config.language_places)
            .find(|written| written.value == *language)
            .map_or_else(
                || Pos {
                    file: "docent.yaml".into(),
                    line: 1,
                    column: 1,
                },
                |written| written.pos.clone(),
            )
    };
    let why = match choice {
        EspeakChoice::Written => "",
        EspeakChoice::Default => {
            " (espeak-ng speaks here because `speech: adapter` is not written and espeak-ng is \
             installed on this computer)"
        }
    };
    unspoken_languages(&config.speech, installed)
        .into_iter()
        .map(|(language, voice)| {
            let message = format!(
                "No installed espeak-ng voice speaks {language}: there is no voice `{voice}` \
                 (see `espeak-ng --voices`). Visitors choosing {language} would hear espeak-ng's \
                 default voice{why}. Name an installed voice in `speech: voices:` (e.g. \
                 `{language}: {language}`), or install the voice."
            );
            Diagnostic::warning(DiagnosticCode::NoVoice, &place(language), message)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config_file::test_support::parse;

    #[test]
    fn a_voice_not_installed_is_reported_where_it_was_written() {
        let config = parse("languages: [en, de]\nspeech:\n  voices: {de: zz}\n").config;
        let installed = ["en".to_owned(), "de".to_owned()];
        let written = EspeakChoice::Written;
        let found = no_voice_diagnostics(&config, &installed, written);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].code.as_str(), "no-voice");
        assert_eq!((found[0].line, found[0].column), (3, 12));
        // Without `voices:`, the language's place in `languages:`.
        let config = parse("languages: [en, xq]\n").config;
        let found = no_voice_diagnostics(&config, &installed, written);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!((found[0].line, found[0].column), (1, 17));
        let plain = parse("home: a.html\n").config;
        assert!(no_voice_diagnostics(&plain, &installed, written).is_empty());
    }

    #[test]
    fn espeak_speaks_when_written_or_by_default_where_installed() {
        let speech = |text: &str| parse(text).config.speech;
        let unwritten = speech("speech: { voice: en }\n");
        assert_eq!(espeak_speaks(&unwritten, true), Some(EspeakChoice::Default));
        assert_eq!(espeak_speaks(&unwritten, false), None);
        let written = speech("speech: { adapter: espeak }\n");
        assert_eq!(espeak_speaks(&written, true), Some(EspeakChoice::Written));
        assert_eq!(espeak_speaks(&written, false), None);
        let browser = speech("speech: { adapter: browser }\n");
        assert_eq!(espeak_speaks(&browser, true), None);
    }

    #[test]
    fn a_voice_unknown_to_espeak_is_told_without_the_adapter_written() {
        let text = "languages: [en, de]\nspeech:\n  voice: en\n  voices: {de: deutsch}\n";
        let config = parse(text).config;
        let installed = ["en".to_owned(), "de".to_owned()];
        let choice = espeak_speaks(&config.speech, true).expect("espeak-ng by default");
        let found = no_voice_diagnostics(&config, &installed, choice);
        let located: Vec<_> = (found.iter())
            .map(|d| (d.code.as_str(), &*d.file, d.line, d.column))
            .collect();
        assert_eq!(located, [("no-voice", "docent.yaml", 4, 12)]);
        let message = &found[0].message;
        assert!(message.contains("`deutsch`"), "{message}");
        assert!(
            message.contains("`speech: adapter` is not written"),
            "{message}"
        );
    }
}
