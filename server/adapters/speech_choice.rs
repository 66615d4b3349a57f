//! Which speech adapter a server starts with: the bundle's, or espeak-ng when it is installed,
//! and what the person starting Docent is told when it is not what the bundle asked for (a
//! missing voice, no sound device).

use crate::adapters::{SpeechOutput, espeak_available, espeak_can_play, espeak_voices};
use crate::content::config::{AdapterKind, SpeechConfig};

/// Decides the speech adapter and says why when it is not what the bundle asked for.
pub fn speech_adapter(
    config: &SpeechConfig,
    output: &SpeechOutput,
    warnings: &mut Vec<String>,
) -> AdapterKind {
    if let Some(kind) = config.adapter.filter(|&k| k != AdapterKind::Espeak) {
        return kind;
    }
    // The three asks of espeak-ng side by side: one after another they were half of a small
    // bundle's start-up (bench/startup.mjs).
    let (available, installed, can_play) = std::thread::scope(|s| {
        let voices = s.spawn(espeak_voices);
        let playing = (*output == SpeechOutput::Audio).then(|| s.spawn(espeak_can_play));
        let available = espeak_available();
        let installed = voices.join().unwrap_or_default();
        let can_play = playing.is_none_or(|p| p.join().unwrap_or(false));
        (available, installed, can_play)
    });
    let kind = choose_speech(config.adapter, available, warnings);
    if kind != AdapterKind::Espeak {
        return kind;
    }
    if !installed.contains(&config.voice) {
        let voice = &config.voice;
        warnings.push(format!(
            "espeak-ng has no voice {voice:?} (see `espeak-ng --voices`); \
             it will speak with its default voice"
        ));
    }
    // `speech: voice` itself is warned about above; `docent check` names the same languages.
    for (language, voice) in crate::content::unspoken_languages(config, &installed) {
        if voice != config.voice {
            warnings.push(format!(
                "no installed espeak-ng voice speaks the language {language}: it has no voice \
                 {voice:?} (see `espeak-ng --voices`; choose one in speech: voices)"
            ));
        }
    }
    if !can_play {
        if config.adapter.is_none() {
            warnings.push(
                "espeak-ng cannot reach a sound device here, so speech is only logged \
                 (use --speech-wav DIR to record it, or set speech: {adapter: espeak})"
                    .into(),
            );
            return AdapterKind::Log;
        }
        warnings.push(
            "espeak-ng cannot reach a sound device here: every SAY will fail \
             (use --speech-wav DIR to record speech instead)"
                .into(),
        );
    }
    kind
}

/// Picks the speech adapter: the configured one, or espeak when installed; log otherwise.
fn choose_speech(
    configured: Option<AdapterKind>,
    espeak: bool,
    warnings: &mut Vec<String>,
) -> AdapterKind {
    match configured {
        Some(AdapterKind::Espeak) | None if !espeak => {
            warnings.push(
                "espeak-ng is not installed, so speech is only logged (install the Debian package \
                 espeak-ng to hear it)"
                    .into(),
            );
            AdapterKind::Log
        }
        Some(kind) => kind,
        None => AdapterKind::Espeak,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_espeak_falls_back_to_log_with_one_warning() {
        let mut warnings = Vec::new();
        assert_eq!(choose_speech(None, false, &mut warnings), AdapterKind::Log);
        assert_eq!(
            choose_speech(Some(AdapterKind::Espeak), false, &mut warnings),
            AdapterKind::Log
        );
        assert_eq!(warnings.len(), 2);
        assert!(warnings[0].contains("espeak-ng is not installed"));
        let mut none = Vec::new();
        assert_eq!(choose_speech(None, true, &mut none), AdapterKind::Espeak);
        assert_eq!(
            choose_speech(Some(AdapterKind::Ws), false, &mut none),
            AdapterKind::Ws
        );
        assert!(none.is_empty());
    }
}
