//! The `kiosk:` and `projector:` sections of `docent.yaml`: how the touchscreen and projector
//! shells behave (idle return home, idle act, what follows a video). Whether the idle act
//! exists is checked later, with the acts (`load.rs`).

use crate::content::acts_file::yaml::Node;
use crate::content::config::{AfterVideo, SiteConfig};
use crate::content::duration::parse_duration;
use crate::content::model::Located;

use super::Reader;

const IDLE_USAGE: &str = "`idle` is how long the touchscreen waits without a touch before it \
                          returns to the home page: a length of time with its unit, e.g. \
                          `idle: 2m` or `idle: 90s`; `idle: 0s` turns it off.";
const IDLE_ACT_USAGE: &str = "`idle_act` is the label of the act to trigger when the \
                              touchscreen goes idle, e.g. `idle_act: INVITE`.";

impl Reader {
    /// Reads `kiosk:` into `config.kiosk`; returns the idle act with its place.
    pub(super) fn kiosk(
        &mut self,
        node: &Node,
        config: &mut SiteConfig,
    ) -> Option<Located<String>> {
        let mut idle_act = None;
        for (key, value) in self.entries(node, &["idle", "idle_act"], "kiosk") {
            if key == "idle" {
                if let Some(idle) = self.setting(value, IDLE_USAGE, parse_duration) {
                    config.kiosk.idle = idle;
                }
                continue;
            }
            let label = |t: &str| (!t.chars().any(char::is_whitespace)).then(|| t.to_owned());
            if let Some(act) = self.setting(value, IDLE_ACT_USAGE, label) {
                config.kiosk.idle_act = Some(act.clone());
                idle_act = Some(Located {
                    value: act,
                    pos: value.pos.clone(),
                });
            }
        }
        idle_act
    }

    /// Reads `projector:` into `config.projector`.
    pub(super) fn projector(&mut self, node: &Node, config: &mut SiteConfig) {
        for (_, value) in self.entries(node, &["after_video"], "projector") {
            let options = [("black", AfterVideo::Black), ("hold", AfterVideo::Hold)];
            if let Some(after) = self.choice(value, "projector's `after_video`", &options) {
                config.projector.after_video = after;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;
    use std::time::Duration;

    use crate::content::config::AfterVideo;
    use crate::content::config_file::{ConfigFile, parse_config};

    fn parse(text: &str) -> ConfigFile {
        parse_config(&Arc::from("docent.yaml"), text.as_bytes())
    }

    #[test]
    fn kiosk_and_projector_settings_are_read() {
        let file =
            parse("kiosk:\n  idle: 90s\n  idle_act: INVITE\nprojector:\n  after_video: hold\n");
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        assert_eq!(file.config.kiosk.idle, Duration::from_secs(90));
        assert_eq!(file.config.kiosk.idle_act.as_deref(), Some("INVITE"));
        let act = file.idle_act.expect("idle act located");
        assert_eq!(
            (act.value.as_str(), act.pos.line, act.pos.column),
            ("INVITE", 3, 13)
        );
        assert_eq!(file.config.projector.after_video, AfterVideo::Hold);
    }

    #[test]
    fn defaults_are_two_minutes_no_act_and_black() {
        let file = parse("kiosk:\nprojector:\n");
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        assert_eq!(file.config.kiosk.idle, Duration::from_secs(120));
        assert_eq!(file.config.kiosk.idle_act, None);
        assert_eq!(file.config.projector.after_video, AfterVideo::Black);
        assert_eq!(
            parse("kiosk: { idle: 0s }\n").config.kiosk.idle,
            Duration::ZERO
        );
    }

    #[test]
    fn bad_values_are_located_and_defaults_kept() {
        let file = parse(
            "kiosk:\n  idle: 120\n  idle_act: two words\n  idel: 1m\nprojector:\n  after_video: blak\n",
        );
        let located: Vec<_> = file
            .diagnostics
            .iter()
            .map(|d| (d.code, d.line, d.column))
            .collect();
        assert_eq!(
            located,
            [
                ("config-unknown-key", 4, 3),
                ("config-bad-value", 2, 9),
                ("config-bad-value", 3, 13),
                ("config-bad-value", 6, 16),
            ]
        );
        assert!(file.diagnostics[0].message.contains("Did you mean `idle`?"));
        assert!(
            file.diagnostics[3]
                .message
                .contains("Did you mean `black`?")
        );
        assert_eq!(file.config.kiosk.idle, Duration::from_secs(120));
        assert_eq!(file.config.projector.after_video, AfterVideo::Black);
        assert!(file.idle_act.is_none());
    }
}
