//! Which `docent.yaml` settings a reload cannot put into effect. The adapters, their routing and
//! the credentials are set up once, at start-up (`Devices::start`, `decide_access`); the kiosk
//! shell reads its settings when it loads (the server tells kiosks to reload it), the projector
//! shell when it loads. Rather than ignore such a change silently, the reload goes live and the
//! operator is told, in a sentence per setting, what it takes for the change to count.

use crate::content::config::SiteConfig;

/// Sentences naming every setting that differs between the configuration Docent started with
/// and `new`, and what makes it take effect; empty when everything in `new` is live.
pub fn not_applied(started: &SiteConfig, new: &SiteConfig) -> Vec<String> {
    let restart = |what: &str| format!("restart Docent for the {what} to take effect");
    let mut out = Vec::new();
    if started.speech != new.speech {
        out.push(restart("speech settings (speech: adapter, voice, rate)"));
    }
    if started.drive != new.drive {
        out.push(restart("drive settings (drive:)"));
    }
    if started.rosbridge != new.rosbridge {
        out.push(restart("link to the robot (rosbridge:)"));
    }
    if started.display != new.display {
        out.push(restart("display adapter (display: adapter)"));
    }
    if started.adapter_timeout != new.adapter_timeout {
        out.push(restart("adapter time-out (adapter_timeout:)"));
    }
    let routes = |c: &SiteConfig| -> Vec<(String, &'static str)> {
        (c.verbs.iter())
            .map(|(name, verb)| (name.clone(), verb.adapter.as_str()))
            .collect()
    };
    if routes(started) != routes(new) {
        out.push(restart(
            "site verbs and where they go (verbs: names and adapters)",
        ));
    }
    if started.access != new.access {
        out.push(restart("credentials (access:)"));
    }
    if started.server.trusted_proxies != new.server.trusted_proxies {
        out.push(restart("trusted proxies (server: trusted_proxies)"));
    }
    if started.server.limits != new.server.limits {
        out.push(restart(
            "server limits (server: connections, timeouts, messages, queues)",
        ));
    }
    if started.projector != new.projector {
        out.push(
            "reload the projector screen (or restart Docent) for the projector settings \
             (projector:) to take effect"
                .to_owned(),
        );
    }
    out
}

/// Whether the kiosk shell itself (not only its page) must reload for `new` to show: its
/// settings are written into the shell when it loads (the languages too: its page folders and
/// its words for visitors, `data-strings`, are the declared languages').
pub fn kiosk_shell_changed(old: &SiteConfig, new: &SiteConfig) -> bool {
    old.home != new.home
        || old.kiosk != new.kiosk
        || old.languages != new.languages
        || old.operator.camera != new.operator.camera
        || old.speech != new.speech
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_unchanged_configuration_needs_nothing() {
        let config = SiteConfig::default();
        assert!(not_applied(&config, &config.clone()).is_empty());
        assert!(!kiosk_shell_changed(&config, &config.clone()));
        let german = crate::content::Language::parse("de").expect("a tag");
        let mut two = config.clone();
        two.languages =
            crate::content::Languages::new(vec![crate::content::Language::english(), german])
                .expect("languages");
        assert!(
            kiosk_shell_changed(&config, &two),
            "a new language brings the shell its words"
        );
    }

    #[test]
    fn a_new_voice_needs_a_restart_and_a_new_idle_time_reloads_the_kiosk() {
        let started = SiteConfig::default();
        let mut new = started.clone();
        new.speech.voice = "de".into();
        let said = not_applied(&started, &new);
        assert_eq!(said.len(), 1);
        assert!(said[0].starts_with("restart Docent for the speech settings"));
        let mut idle = started.clone();
        idle.kiosk.idle = std::time::Duration::from_secs(5);
        assert!(not_applied(&started, &idle).is_empty());
        assert!(kiosk_shell_changed(&started, &idle));
    }

    #[test]
    fn changed_server_limits_need_a_restart_apart_from_the_proxies() {
        let started = SiteConfig::default();
        let mut new = started.clone();
        new.server.limits.per_address = 512;
        let said = not_applied(&started, &new);
        assert_eq!(
            said,
            [
                "restart Docent for the server limits (server: connections, timeouts, messages, \
              queues) to take effect"
            ]
        );
        new.server.trusted_proxies = vec![std::net::Ipv4Addr::LOCALHOST.into()];
        assert_eq!(not_applied(&started, &new).len(), 2);
    }

    #[test]
    fn a_changed_setting_changed_back_is_live_again() {
        let started = SiteConfig::default();
        let mut new = started.clone();
        new.adapter_timeout = std::time::Duration::from_secs(1);
        assert_eq!(not_applied(&started, &new).len(), 1);
        new.adapter_timeout = started.adapter_timeout;
        assert!(not_applied(&started, &new).is_empty());
    }
}
