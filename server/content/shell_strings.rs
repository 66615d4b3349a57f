//! The words the kiosk shell itself shows visitors (its "Stop speaking" button, its notices, the
//! outage notice): one table, with every language the shell knows built in, to which a site
//! adds its own languages or words in `docent.yaml` (`kiosk: strings:`). The server hands the
//! shell the table for the bundle's declared languages (`shell_table`, the shell's
//! `data-strings`); the shell picks the words of the page on show's language. A declared
//! language the table lacks a word for is a located warning (`shell-strings-missing`): its
//! visitors would read the default language's words.

use std::collections::BTreeMap;

use crate::DiagnosticCode;
use crate::config::SiteConfig;
use crate::diagnostic::Diagnostic;
use crate::language::Language;
use crate::model::Pos;

/// One thing the kiosk shell says to visitors.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum ShellString {
    /// Shown while the shell waits for its first page.
    Starting,
    /// The button that ends the speech visitors started.
    Stop,
    /// A tap on an act that is already speaking.
    AlreadySpeaking,
    /// A visitor's speech that will not be said (a full queue, the operator took over).
    CannotSay,
    /// Docent is away for more than a second (the outage notice).
    OneMoment,
    /// A language button tapped while Docent is away.
    LanguageOffline,
    /// A language button for a language Docent refused.
    LanguageUnavailable,
}

impl ShellString {
    /// Every string, in the order `kiosk: strings:` documents them.
    pub const ALL: [ShellString; 7] = [
        ShellString::Starting,
        ShellString::Stop,
        ShellString::AlreadySpeaking,
        ShellString::CannotSay,
        ShellString::OneMoment,
        ShellString::LanguageOffline,
        ShellString::LanguageUnavailable,
    ];

    /// The key in `kiosk: strings:` and in the shell's table (`static/shell-text.js`).
    pub fn key(self) -> &'static str {
        match self {
            ShellString::Starting => "starting",
            ShellString::Stop => "stop",
            ShellString::AlreadySpeaking => "already_speaking",
            ShellString::CannotSay => "cannot_say",
            ShellString::OneMoment => "one_moment",
            ShellString::LanguageOffline => "language_offline",
            ShellString::LanguageUnavailable => "language_unavailable",
        }
    }

    /// When the shell shows it, for the schema and the author.
    pub fn shown(self) -> &'static str {
        match self {
            ShellString::Starting => "Shown before the first page.",
            ShellString::Stop => "The button that ends the speech visitors started.",
            ShellString::AlreadySpeaking => "A tap on an act already speaking.",
            ShellString::CannotSay => "A visitor's speech that will not be said.",
            ShellString::OneMoment => "Docent is away for more than a second.",
            ShellString::LanguageOffline => "A language button tapped while Docent is away.",
            ShellString::LanguageUnavailable => "A language button for a language refused.",
        }
    }

    /// The string of `key`, if it is one.
    pub fn from_key(key: &str) -> Option<ShellString> {
        Self::ALL.into_iter().find(|s| s.key() == key)
    }

    /// The built-in words, by primary language tag.
    fn built_in(self) -> &'static [(&'static str, &'static str)] {
        match self {
            ShellString::Starting => &[
                ("en", "Starting…"),
                ("de", "Wird gestartet…"),
                ("fr", "Démarrage…"),
                ("es", "Iniciando…"),
                ("it", "Avvio in corso…"),
                ("nl", "Bezig met starten…"),
            ],
            ShellString::Stop => &[
                ("en", "Stop speaking"),
                ("de", "Nicht mehr sprechen"),
                ("fr", "Arrêter de parler"),
                ("es", "Dejar de hablar"),
                ("it", "Smetti di parlare"),
                ("nl", "Stop met spreken"),
            ],
            ShellString::AlreadySpeaking => &[
                ("en", "Already speaking about this."),
                ("de", "Darüber spreche ich schon."),
                ("fr", "J'en parle déjà."),
                ("es", "Ya estoy hablando de esto."),
                ("it", "Ne sto già parlando."),
                ("nl", "Daar praat ik al over."),
            ],
            ShellString::CannotSay => &[
                ("en", "The robot cannot say this now."),
                ("de", "Das kann der Roboter gerade nicht sagen."),
                ("fr", "Le robot ne peut pas dire cela maintenant."),
                ("es", "El robot no puede decir esto ahora."),
                ("it", "Il robot non può dirlo adesso."),
                ("nl", "De robot kan dit nu niet zeggen."),
            ],
            ShellString::OneMoment => &[
                ("en", "One moment, please: the robot will be right back."),
                (
                    "de",
                    "Einen Moment bitte: Der Roboter ist gleich wieder da.",
                ),
                (
                    "fr",
                    "Un instant, s'il vous plaît : le robot revient tout de suite.",
                ),
                ("es", "Un momento, por favor: el robot vuelve enseguida."),
                ("it", "Un momento, per favore: il robot torna subito."),
                ("nl", "Een ogenblik alstublieft: de robot is zo terug."),
            ],
            ShellString::LanguageOffline => &[
                ("en", "Not connected: the language was not changed."),
                (
                    "de",
                    "Keine Verbindung: Die Sprache wurde nicht gewechselt.",
                ),
                ("fr", "Pas de connexion : la langue n'a pas été changée."),
                ("es", "Sin conexión: no se ha cambiado el idioma."),
                ("it", "Nessuna connessione: la lingua non è stata cambiata."),
                ("nl", "Geen verbinding: de taal is niet gewijzigd."),
            ],
            ShellString::LanguageUnavailable => &[
                ("en", "This language is not available here."),
                ("de", "Diese Sprache gibt es hier nicht."),
                ("fr", "Cette langue n'est pas disponible ici."),
                ("es", "Este idioma no está disponible aquí."),
                ("it", "Questa lingua non è disponibile qui."),
                ("nl", "Deze taal is hier niet beschikbaar."),
            ],
        }
    }

    /// The words for `language`: the site's (`kiosk: strings:`), else the built-in ones for
    /// its tag or its primary language (`de-ch` reads `de`).
    pub fn text_for(self, language: &Language, config: &SiteConfig) -> Option<String> {
        if let Some(own) = config
            .kiosk
            .strings
            .get(language)
            .and_then(|s| s.get(&self))
        {
            return Some(own.clone());
        }
        let tag = language.as_str();
        let primary = tag.split('-').next().unwrap_or(tag);
        let built_in = self.built_in();
        (built_in.iter().find(|(l, _)| *l == tag))
            .or_else(|| built_in.iter().find(|(l, _)| *l == primary))
            .map(|(_, text)| (*text).to_owned())
    }
}

/// A site's own shell words (`kiosk: strings:`): by language, by string.
pub type SiteStrings = BTreeMap<Language, BTreeMap<ShellString, String>>;

/// The shell's table for the bundle's languages: by key, by language tag. A language without
/// its words gets the default language's (then English), so the shell never shows a key; the
/// check has warned about it.
pub fn shell_table(config: &SiteConfig) -> BTreeMap<&'static str, BTreeMap<String, String>> {
    let default = config.languages.default_language();
    let mut table = BTreeMap::new();
    for string in ShellString::ALL {
        let mut texts = BTreeMap::new();
        for language in config.languages.all() {
            let text = (string.text_for(language, config))
                .or_else(|| string.text_for(default, config))
                .or_else(|| string.text_for(&Language::english(), config))
                .unwrap_or_default();
            texts.insert(language.as_str().to_owned(), text);
        }
        table.insert(string.key(), texts);
    }
    table
}

/// Warns, at the language in `languages:`, of each declared language the table lacks words for.
pub(crate) fn check_shell_strings(config: &SiteConfig, out: &mut Vec<Diagnostic>) {
    for language in config.languages.all() {
        let missing: Vec<&str> = (ShellString::ALL.into_iter())
            .filter(|s| s.text_for(language, config).is_none())
            .map(ShellString::key)
            .collect();
        if missing.is_empty() {
            continue;
        }
        let pos = (config.language_places.iter())
            .find(|l| &l.value == language)
            .map_or_else(|| Pos::start_of("docent.yaml"), |l| l.pos.clone());
        let example = missing.first().copied().unwrap_or("stop");
        let message = format!(
            "The kiosk shell has no `{language}` words for: {}. Visitors reading `{language}` \
             see the default language's words there. Add them in `docent.yaml`, e.g. \
             `kiosk: {{strings: {{{language}: {{{example}: \"…\"}}}}}}` (docs/CONFIG.md, \
             \"The kiosk shell's words\").",
            missing.join(", ")
        );
        out.push(Diagnostic::warning(
            DiagnosticCode::ShellStringsMissing,
            &pos,
            message,
        ));
    }
}
