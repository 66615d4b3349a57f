//! The `captions:` section of `docent.yaml`: where what the robot says is shown as a caption
//! while it is said. The touchscreen shows captions unless the bundle turns them off (a page
//! may still opt out, docs/AUTHORING.md); the projector only when the bundle asks for them.

use crate::acts_file::yaml::Node;
use crate::config::SiteConfig;
use crate::config_file::reader::Reader;
use crate::config_file::section::{Field, Section, Shape};

/// The settings of `captions:`.
pub(crate) const SECTION: Section = Section {
    name: "captions",
    required: &[],
    fields: &[
        Field {
            key: "kiosk",
            description: "Whether the touchscreen shows what the robot says as a caption while \
                          it is said (default `true`).",
            shape: Shape::Bool,
        },
        Field {
            key: "projector",
            description: "Whether the projector shows what the robot says as a caption while \
                          it is said (default `false`).",
            shape: Shape::Bool,
        },
    ],
};

/// Which screens show captions of the robot's speech.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CaptionSettings {
    /// The touchscreen shows captions (default on).
    pub kiosk: bool,
    /// The projector shows captions (default off: a wall is often shared with a film).
    pub projector: bool,
}

impl Default for CaptionSettings {
    fn default() -> Self {
        CaptionSettings {
            kiosk: true,
            projector: false,
        }
    }
}

impl Reader {
    /// Reads `captions:` into `config.captions`.
    pub(super) fn captions(&mut self, node: &Node, config: &mut SiteConfig) {
        for (field, value) in self.entries(node, &SECTION) {
            let key = field.key;
            let what = format!("captions' `{key}` setting (whether that screen shows captions)");
            let Some(on) = self.pick(value, &what, &field.shape, &[true, false]) else {
                continue;
            };
            match key {
                "kiosk" => config.captions.kiosk = on,
                _ => config.captions.projector = on,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::config_file::test_support::{parse, problems};

    #[test]
    fn captions_are_on_the_touchscreen_and_off_the_projector_by_default() {
        let file = parse("home: index.html\n");
        assert!(file.config.captions.kiosk);
        assert!(!file.config.captions.projector);
        let file = parse("captions:\n");
        assert!(file.config.captions.kiosk);
        assert!(file.diagnostics.is_empty());
    }

    #[test]
    fn a_bundle_turns_captions_off_the_touchscreen_and_onto_the_projector() {
        let file = parse("captions: {kiosk: false, projector: true}\n");
        assert!(!file.config.captions.kiosk);
        assert!(file.config.captions.projector);
        assert!(file.diagnostics.is_empty());
    }

    #[test]
    fn a_caption_setting_that_is_not_true_or_false_is_reported_and_its_default_kept() {
        let file = parse("captions:\n  kiosk: sometimes\n");
        assert!(file.config.captions.kiosk, "default kept");
        let found = problems("captions:\n  kiosk: sometimes\n");
        assert_eq!(found.len(), 1, "{found:?}");
        let (code, line, column, message) = &found[0];
        assert_eq!((*code, *line, *column), ("config-bad-value", 2, 10));
        assert!(message.contains("true, false"), "{message}");
    }

    #[test]
    fn an_unknown_caption_setting_is_reported_with_a_suggestion() {
        let found = problems("captions:\n  kisok: true\n");
        let (code, line, column, message) = &found[0];
        assert_eq!((*code, *line, *column), ("config-unknown-key", 2, 3));
        assert!(message.contains("kiosk"), "{message}");
    }
}
