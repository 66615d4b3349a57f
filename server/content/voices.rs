//! The bundle's languages that no installed espeak-ng voice speaks. One rule for the two
//! places that ask: `docent serve`'s start-up warnings and `docent check` (the `no-voice`
//! warning, at the place the voice or the language was written). The installed voices are
//! handed in (the caller runs `espeak-ng --voices`): content loading itself runs nothing.

use crate::DiagnosticCode;
use crate::config::{SiteConfig, SpeechConfig};
use crate::diagnostic::Diagnostic;
use crate::language::Language;
use crate::model::Pos;

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
pub fn no_voice_diagnostics(config: &SiteConfig, installed: &[String]) -> Vec<Diagnostic> {
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
    unspoken_languages(&config.speech, installed)
        .into_iter()
        .map(|(language, voice)| {
            let message = format!(
                "No installed espeak-ng voice speaks {language}: there is no voice `{voice}` \
                 (see `espeak-ng --voices`). Visitors choosing {language} would hear espeak-ng's \
                 default voice. Name an installed voice in `speech: voices:` (e.g. \
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
        let found = no_voice_diagnostics(&config, &installed);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].code.as_str(), "no-voice");
        assert_eq!((found[0].line, found[0].column), (3, 12));
        // Without `voices:`, the language's place in `languages:`.
        let config = parse("languages: [en, xq]\n").config;
        let found = no_voice_diagnostics(&config, &installed);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!((found[0].line, found[0].column), (1, 17));
        assert!(no_voice_diagnostics(&parse("home: a.html\n").config, &installed).is_empty());
    }
}
