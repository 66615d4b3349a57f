//! The `operator:` section of `docent.yaml`: what the operator console shows (the map, the
//! camera) and offers (situations to mark, visitor groups). Whether the map file exists and
//! which contexts the visitor groups may name are checked later, with the whole bundle
//! (`content/operator_check.rs`).

use crate::acts_file::yaml::{Kind, Node};
use crate::config::Camera;
use crate::model::Located;
use crate::suggest::did_you_mean;

use serde_json::{Value, json};

use super::section::{Field, Section, Shape};
use super::{ConfigFile, Reader};
use crate::schema::{VARIANT_KEY_PATTERN, any_case, words};

/// The settings of `operator:`.
pub(crate) const SECTION: Section = Section {
    name: "operator",
    required: &[],
    fields: &[
        Field {
            key: "map",
            description: "A picture of the area the robot drives in, spanning `drive: bounds`, \
                          written from the bundle folder, e.g. `pages/images/map.png`",
            shape: Shape::Custom(map_schema),
        },
        Field {
            key: "camera",
            description: "The camera the operator sees: `webrtc` (the touchscreen's own \
                          camera, the default), `none`, or the address of an MJPEG stream \
                          starting with http:// or https://.",
            shape: Shape::Custom(camera_schema),
        },
        Field {
            key: "situations",
            description: "1 to 9 short names the operator marks during a session with \
                          Alt+Shift+1 to 9, e.g. `[question, laughter, leaving]`.",
            shape: Shape::Custom(situations_schema),
        },
        Field {
            key: "visitor_groups",
            description: "Which context each visitor group button of the console switches to.",
            shape: Shape::Nested(&VISITOR_GROUPS),
        },
    ],
};

/// Visitor groups the console offers, in the order it shows them, each naming the context
/// its button switches to.
pub(crate) const VISITOR_GROUPS: Section = Section {
    name: "visitor_groups",
    required: &[],
    fields: &[
        Field {
            key: "single",
            description: "The context the console switches to for the `single` visitor group: \
                          `Text` or a text variant key, e.g. `TextChild`.",
            shape: Shape::Pattern(VARIANT_KEY_PATTERN),
        },
        Field {
            key: "group",
            description: "The context the console switches to for the `group` visitor group: \
                          `Text` or a text variant key, e.g. `TextChild`.",
            shape: Shape::Pattern(VARIANT_KEY_PATTERN),
        },
        Field {
            key: "children",
            description: "The context the console switches to for the `children` visitor \
                          group: `Text` or a text variant key, e.g. `TextChild`.",
            shape: Shape::Pattern(VARIANT_KEY_PATTERN),
        },
    ],
};
/// Picture formats Chromium shows in an `<img>`.
pub(crate) const MAP_FORMATS: &[&str] = &["png", "jpg", "jpeg", "gif", "webp", "svg"];
/// Situations are marked with Alt+Shift+1 to 9.
const MAX_SITUATIONS: usize = 9;

const MAP_USAGE: &str = "`map` is a picture of the area the robot drives in, spanning \
                         `drive: bounds`, written from the bundle folder: \
                         `map: pages/images/map.png` (under pages/ or media/).";
const CAMERA_USAGE: &str = "`camera` is `webrtc` (the kiosk's own camera, the default), \
                            `none`, or the address of an MJPEG stream starting with http:// \
                            or https://.";
const SITUATIONS_USAGE: &str = "`situations` lists 1 to 9 short names the operator marks \
                                during a session with Alt+Shift+1 to 9, e.g. \
                                `situations: [question, laughter, leaving]`.";
const GROUP_CONTEXT_USAGE: &str = "A visitor group switches to a context: `Text` or the name \
                                   of a text variant key, e.g. `children: TextChild`.";

impl Reader {
    /// Reads `operator:` into `out.config.operator`, keeping the places the bundle checks need.
    pub(super) fn operator(&mut self, node: &Node, out: &mut ConfigFile) {
        for (field, value) in self.entries(node, &SECTION) {
            let operator = &mut out.config.operator;
            match field.key {
                "map" => {
                    if let Some(map) = self.map(value) {
                        operator.map = Some(map.clone());
                        out.map = Some(Located {
                            value: map,
                            pos: value.pos.clone(),
                        });
                    }
                }
                "camera" => operator.camera = self.camera(value).unwrap_or_default(),
                "situations" => operator.situations = self.situations(value),
                _ => out.visitor_groups = self.visitor_groups(value),
            }
        }
    }

    fn map(&mut self, node: &Node) -> Option<String> {
        let text = node.as_text().map(str::trim).unwrap_or_default();
        if text.is_empty() {
            self.bad(node, MAP_USAGE);
            return None;
        }
        let in_area = ["pages/", "media/"]
            .iter()
            .any(|area| text.strip_prefix(area).is_some_and(|rest| !rest.is_empty()));
        if !in_area {
            let message = format!(
                "{MAP_USAGE} Start the path with `pages/` or `media/`, e.g. `pages/{}`.",
                text.trim_start_matches('/')
            );
            self.bad(node, &message);
            return None;
        }
        let format = text
            .rsplit_once('.')
            .map(|(_, ext)| ext.to_ascii_lowercase())
            .filter(|ext| MAP_FORMATS.contains(&ext.as_str()));
        if format.is_none() {
            let message = format!(
                "The map must be a picture the console's browser shows: a {} file.",
                MAP_FORMATS.join(", ")
            );
            self.bad(node, &message);
            return None;
        }
        Some(text.to_owned())
    }

    fn camera(&mut self, node: &Node) -> Option<Camera> {
        let text = node.as_text().map(str::trim).unwrap_or_default();
        match text {
            "webrtc" => return Some(Camera::WebRtc),
            "none" => return Some(Camera::None),
            _ => {}
        }
        if let Some(url) = stream_url(text) {
            return Some(Camera::Url(url.to_owned()));
        }
        let lower = text.to_ascii_lowercase();
        let message = if lower.starts_with("http://") || lower.starts_with("https://") {
            format!(
                "{CAMERA_USAGE} This address needs a host name after `//` and no spaces, \
                 quotes or angle brackets (write them as %20, %22, %3C, %3E)."
            )
        } else {
            format!("{CAMERA_USAGE}{}", did_you_mean(text, ["webrtc", "none"]))
        };
        self.bad(node, &message);
        None
    }

    fn situations(&mut self, node: &Node) -> Vec<String> {
        let items: Vec<&Node> = match &node.kind {
            Kind::Seq(items) if items.is_empty() => {
                self.bad(node, SITUATIONS_USAGE);
                return Vec::new();
            }
            Kind::Seq(items) => items.iter().collect(),
            Kind::Null => return Vec::new(),
            _ => vec![node],
        };
        let mut situations: Vec<String> = Vec::new();
        for (index, item) in items.into_iter().enumerate() {
            if index == MAX_SITUATIONS {
                let message = format!(
                    "There are at most {MAX_SITUATIONS} situations, one for each of \
                     Alt+Shift+1 to 9. Remove this one and those after it."
                );
                self.bad(item, &message);
                break;
            }
            let name = item.as_text().map(str::trim).unwrap_or_default();
            if name.is_empty() {
                self.bad(item, SITUATIONS_USAGE);
            } else if situations.iter().any(|s| s.eq_ignore_ascii_case(name)) {
                self.bad(item, "This situation is listed twice. Keep one.");
            } else {
                situations.push(name.to_owned());
            }
        }
        situations
    }

    fn visitor_groups(&mut self, node: &Node) -> Vec<(&'static str, Located<String>)> {
        let mut groups = Vec::new();
        for (field, value) in self.entries(node, &VISITOR_GROUPS) {
            let group = field.key;
            let context = |t: &str| is_context_name(t).then(|| t.to_owned());
            if let Some(context) = self.setting(value, GROUP_CONTEXT_USAGE, context) {
                let pos = value.pos.clone();
                groups.push((
                    group,
                    Located {
                        value: context,
                        pos,
                    },
                ));
            }
        }
        groups
    }
}

/// `Text`, or `Text` followed by letters, digits or `_`, as variant keys are written.
fn is_context_name(name: &str) -> bool {
    name.strip_prefix("Text")
        .is_some_and(|rest| rest.chars().all(|c| c.is_alphanumeric() || c == '_'))
}

/// The URL when `text` is a plain `http(s)://host...` address that is safe to hand to a page.
fn stream_url(text: &str) -> Option<&str> {
    let lower = text.to_ascii_lowercase();
    let rest = ["http://", "https://"]
        .iter()
        .find_map(|scheme| lower.strip_prefix(scheme))?;
    let host = rest.split(['/', '?', '#']).next().unwrap_or_default();
    let plain = text
        .chars()
        .all(|c| c.is_ascii_graphic() && !"\"'<>`\\{}|^".contains(c));
    (!host.is_empty() && !host.starts_with('@') && plain).then_some(text)
}

/// The default context of each visitor group, used when the bundle has it.
pub(crate) fn default_context(group: &str) -> &'static str {
    match group {
        "group" => "TextGroup",
        "children" => "TextChild",
        _ => "Text",
    }
}

/// A picture under pages/ or media/ in a format the console's browser shows; the
/// description ends with the formats.
fn map_schema(description: &'static str) -> Value {
    let formats: Vec<String> = MAP_FORMATS.iter().map(|f| any_case(f)).collect();
    json!({
        "type": "string",
        "pattern": format!(r"^\s*(pages|media)/.+\.({})\s*$", formats.join("|")),
        "description": format!("{description} ({}).", MAP_FORMATS.join(", ")),
    })
}

/// `webrtc`, `none` or an MJPEG stream's address.
fn camera_schema(description: &'static str) -> Value {
    json!({
        "description": description,
        "anyOf": [
            { "enum": ["webrtc", "none"] },
            {
                "type": "string",
                "pattern": r#"^\s*[hH][tT][tT][pP][sS]?://[^/?#@\s"'<>`\\{}|^][^\s"'<>`\\{}|^]*\s*$"#,
            },
        ],
    })
}

/// One name or a list of 1 to 9 different names.
fn situations_schema(description: &'static str) -> Value {
    let name = words("A short name the operator marks, e.g. `question`.");
    json!({
        "description": description,
        "anyOf": [
            { "type": "null" },
            name,
            {
                "type": "array",
                "minItems": 1,
                "maxItems": MAX_SITUATIONS,
                "uniqueItems": true,
                "items": name,
            },
        ],
    })
}

#[cfg(test)]
mod tests {
    use crate::config_file::test_support::parse;

    use super::*;
    use crate::config::OperatorConfig;

    fn located(file: &ConfigFile) -> Vec<(&'static str, u32, u32)> {
        file.diagnostics
            .iter()
            .map(|d| (d.code.as_str(), d.line, d.column))
            .collect()
    }

    #[test]
    fn the_documented_example_is_read() {
        let file = parse(
            "operator:\n  map: pages/images/map.png\n  camera: webrtc\n  \
             situations: [question, misunderstanding, laughter, interruption, leaving]\n  \
             visitor_groups: { single: Text, group: TextGroup, children: TextChild }\n",
        );
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        let operator = &file.config.operator;
        assert_eq!(operator.map.as_deref(), Some("pages/images/map.png"));
        let map = file.map.as_ref().expect("map located");
        assert_eq!((map.pos.line, map.pos.column), (2, 8));
        assert_eq!(operator.camera, Camera::WebRtc);
        assert_eq!(
            operator.situations,
            [
                "question",
                "misunderstanding",
                "laughter",
                "interruption",
                "leaving"
            ]
        );
        let groups: Vec<(&str, &str, u32)> = file
            .visitor_groups
            .iter()
            .map(|(g, c)| (*g, c.value.as_str(), c.pos.column))
            .collect();
        assert_eq!(
            groups,
            [
                ("single", "Text", 29),
                ("group", "TextGroup", 42),
                ("children", "TextChild", 63)
            ]
        );
    }

    #[test]
    fn defaults_are_no_map_webrtc_no_situations() {
        let file = parse("operator:\n");
        assert!(file.diagnostics.is_empty());
        assert_eq!(file.config.operator, OperatorConfig::default());
        assert_eq!(file.config.operator.camera, Camera::WebRtc);
        assert!(file.map.is_none() && file.visitor_groups.is_empty());
    }

    #[test]
    fn cameras_are_webrtc_none_or_a_stream_address() {
        let camera = |text: &str| parse(&format!("operator: {{ camera: \"{text}\" }}\n"));
        assert_eq!(camera("none").config.operator.camera, Camera::None);
        assert_eq!(
            camera("http://192.168.1.20:8081/stream.mjpg")
                .config
                .operator
                .camera,
            Camera::Url("http://192.168.1.20:8081/stream.mjpg".to_owned())
        );
        assert_eq!(
            camera("HTTPS://cam.local/").config.operator.camera,
            Camera::Url("HTTPS://cam.local/".to_owned())
        );
        let slip = camera("WebRTC");
        assert_eq!(located(&slip), [("config-bad-value", 1, 21)]);
        assert!(
            slip.diagnostics[0]
                .message
                .contains("Did you mean `webrtc`?")
        );
        for bad in [
            "http://",
            "https:///x",
            "http://cam/a b",
            "http://cam/<x>",
            "rtsp://cam/",
        ] {
            let file = camera(bad);
            assert_eq!(located(&file), [("config-bad-value", 1, 21)], "{bad}");
            assert_eq!(file.config.operator.camera, Camera::WebRtc, "default kept");
        }
    }

    #[test]
    fn the_map_is_a_picture_under_pages_or_media() {
        let map = |text: &str| parse(&format!("operator:\n  map: {text}\n"));
        assert_eq!(
            map("media/plan.SVG").config.operator.map.as_deref(),
            Some("media/plan.SVG")
        );
        let file = map("images/map.png");
        assert_eq!(located(&file), [("config-bad-value", 2, 8)]);
        assert!(
            file.diagnostics[0]
                .message
                .contains("e.g. `pages/images/map.png`"),
            "{}",
            file.diagnostics[0].message
        );
        for bad in [
            "pages/",
            "pages/map.bmp",
            "pages/map",
            "pages/maps.d/plan",
            "\"\"",
        ] {
            let file = map(bad);
            assert_eq!(located(&file), [("config-bad-value", 2, 8)], "{bad}");
            assert!(file.map.is_none() && file.config.operator.map.is_none());
        }
    }

    #[test]
    fn situations_are_one_to_nine_different_names() {
        let file = parse("operator:\n  situations: [a, b, c, d, e, f, g, h, i, j, k]\n");
        assert_eq!(located(&file), [("config-bad-value", 2, 43)]);
        assert!(file.diagnostics[0].message.contains("at most 9"));
        assert_eq!(file.config.operator.situations.len(), 9);
        let file = parse("operator:\n  situations: [Question, \"\", question, [x]]\n");
        assert_eq!(
            located(&file),
            [
                ("config-bad-value", 2, 26),
                ("config-bad-value", 2, 30),
                ("config-bad-value", 2, 40)
            ]
        );
        assert!(file.diagnostics[1].message.contains("listed twice"));
        assert_eq!(file.config.operator.situations, ["Question"]);
        assert_eq!(
            located(&parse("operator:\n  situations: []\n")),
            [("config-bad-value", 2, 15)]
        );
        assert_eq!(
            parse("operator: { situations: leaving }\n")
                .config
                .operator
                .situations,
            ["leaving"]
        );
    }

    #[test]
    fn visitor_groups_are_single_group_children_naming_contexts() {
        let file = parse(
            "operator:\n  visitor_groups:\n    family: TextChild\n    single: Formal\n    \
             childern: TextChild\n",
        );
        assert_eq!(
            located(&file),
            [
                ("config-unknown-key", 3, 5),
                ("config-unknown-key", 5, 5),
                ("config-bad-value", 4, 13)
            ]
        );
        assert!(
            file.diagnostics[1]
                .message
                .contains("Did you mean `children`?")
        );
        assert!(file.visitor_groups.is_empty());
    }
}
