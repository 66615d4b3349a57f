//! `attract:` in `docent.yaml` (under `kiosk:`, or in a schedule range): the attract loop
//! an unused touchscreen runs. The pages and the act it names are collected with their places
//! in [`ScreenRefs`] and checked against the bundle later, like every page and act
//! (`check_screen_refs`, called by `load.rs`).

use std::time::Duration;

use crate::DiagnosticCode;
use crate::acts_file::yaml::{Kind, Node};
use crate::attract::AttractLoop;
use crate::commands::{CommandChecker, path_error_code};
use crate::diagnostic::Diagnostic;
use crate::duration::parse_duration;
use crate::model::Located;
use crate::paths::BundleArea;
use crate::suggest::did_you_mean;

use serde_json::{Value, json};

use super::Reader;
use super::section::{Field, Section, Shape};
use crate::schema::words;

/// What an attract loop is, for the author (under `kiosk:` and in a schedule's ranges).
pub(crate) const DESCRIPTION: &str = "The attract loop: after a time without a touch the kiosk \
                                      shows pages in turn or triggers an act, until the first \
                                      touch, which returns to the home page.";

/// The settings of an `attract:` section.
pub(crate) const SECTION: Section = Section {
    name: "attract",
    required: &[],
    fields: &[
        Field {
            key: "after",
            description: "How long the touchscreen waits without a touch before the attract \
                          loop starts, e.g. `3m` (2m unless set).",
            shape: Shape::Duration,
        },
        Field {
            key: "pages",
            description: "The pages the attract loop shows in turn.",
            shape: Shape::Custom(pages_schema),
        },
        Field {
            key: "every",
            description: "How long each attract page stays on screen, e.g. `10s` (the \
                          default); with only an act, how often it is repeated (once unless \
                          set).",
            shape: Shape::Duration,
        },
        Field {
            key: "act",
            description: "The label of the act triggered when the loop starts, e.g. `INVITE`.",
            shape: Shape::Pattern(r"^\S+$"),
        },
    ],
};

/// One page or a list of pages.
fn pages_schema(description: &'static str) -> Value {
    let page = words("A page under pages/, e.g. `attract/a.html`.");
    json!({
        "description": description,
        "anyOf": [page, { "type": "array", "items": page, "minItems": 1 }],
    })
}
const AFTER_USAGE: &str = "`after` is how long the touchscreen waits without a touch before \
                           the attract loop starts: a length of time with its unit, e.g. \
                           `after: 3m`.";
const EVERY_USAGE: &str = "`every` is how long each attract page stays on screen (with only \
                           an act: how often the act is repeated), at least one second, e.g. \
                           `every: 10s`.";
const PAGES_USAGE: &str = "`pages` lists the pages under pages/ the attract loop shows in \
                           turn, e.g. `pages: [attract/a.html, attract/b.html]`.";
const ACT_USAGE: &str = "`act` is the label of the act the attract loop triggers when it \
                         starts, e.g. `act: INVITE`.";
const NEEDS_CONTENT: &str = "An attract loop needs `pages`, an `act`, or both, e.g. \
                             `attract: {after: 3m, pages: [attract/a.html], every: 10s}` or \
                             `attract: {after: 3m, act: INVITE}`.";
/// `after` when not written.
const DEFAULT_AFTER: Duration = Duration::from_secs(120);

/// The pages and acts the kiosk's own settings name (attract loops, schedule), with their
/// places, checked against the bundle once it is read.
#[derive(Debug, Default)]
pub(crate) struct ScreenRefs {
    /// Pages under `pages/`: attract pages, the closed page, schedule home pages.
    pub pages: Vec<Located<String>>,
    /// Acts the attract loops trigger.
    pub acts: Vec<Located<String>>,
}

impl Reader {
    /// Reads an `attract:` section; `None` (after reporting) when it is unusable.
    pub(super) fn attract(&mut self, node: &Node) -> Option<AttractLoop> {
        let mut attract = AttractLoop {
            after: DEFAULT_AFTER,
            pages: Vec::new(),
            every: None,
            act: None,
        };
        let mut usable = true;
        for (field, value) in self.entries(node, &SECTION) {
            match field.key {
                "after" => {
                    let after = |t: &str| parse_duration(t).filter(|d| !d.is_zero());
                    match self.setting(value, AFTER_USAGE, after) {
                        Some(after) => attract.after = after,
                        None => usable = false,
                    }
                }
                "every" => {
                    let every = |t: &str| parse_duration(t).filter(|d| d.as_millis() >= 1000);
                    attract.every = self.setting(value, EVERY_USAGE, every);
                    usable &= attract.every.is_some();
                }
                "pages" => match self.attract_pages(value) {
                    Some(pages) => attract.pages = pages,
                    None => usable = false,
                },
                _ => {
                    let label = |t: &str| (!t.chars().any(char::is_whitespace)).then(|| t.into());
                    let act: Option<String> = self.setting(value, ACT_USAGE, label);
                    if let Some(act) = &act {
                        let pos = value.pos.clone();
                        let located = Located {
                            value: act.clone(),
                            pos,
                        };
                        self.screen_refs.acts.push(located);
                    }
                    usable &= act.is_some();
                    attract.act = act;
                }
            }
        }
        if usable && attract.pages.is_empty() && attract.act.is_none() {
            self.bad(node, NEEDS_CONTENT);
            return None;
        }
        usable.then_some(attract)
    }

    /// `pages:` of an attract loop: one page or a list of them.
    fn attract_pages(&mut self, node: &Node) -> Option<Vec<String>> {
        let items: Vec<&Node> = match &node.kind {
            Kind::Seq(items) if !items.is_empty() => items.iter().collect(),
            Kind::Str { .. } => vec![node],
            _ => {
                self.bad(node, PAGES_USAGE);
                return None;
            }
        };
        let mut pages = Vec::new();
        for item in items {
            let page = self.page_setting(item, PAGES_USAGE)?;
            pages.push(page);
        }
        Some(pages)
    }

    /// A page under `pages/` named in the kiosk's settings, remembered to be checked later.
    pub(super) fn page_setting(&mut self, node: &Node, usage: &str) -> Option<String> {
        let page = self.setting(node, usage, |t| Some(t.to_owned()))?;
        let located = Located {
            value: page.clone(),
            pos: node.pos.clone(),
        };
        self.screen_refs.pages.push(located);
        Some(page)
    }
}

/// Every page the kiosk's settings name must be a page of the bundle (the checks a
/// `DISPLAY_PAGE` path gets), and every act they trigger must exist.
pub(crate) fn check_screen_refs(
    refs: &ScreenRefs,
    checker: &CommandChecker<'_>,
    knows: impl Fn(&str) -> bool,
    labels: &[&str],
    out: &mut Vec<Diagnostic>,
) {
    for Located { value, pos } in &refs.pages {
        if let Some((err, problem)) = checker.path_problem(BundleArea::Pages, value) {
            let message = format!(
                "{problem} The kiosk shows this page by its own settings (an attract loop or \
                 the schedule): add it, or fix the name in docent.yaml."
            );
            out.push(Diagnostic::error(path_error_code(&err), pos, message));
        }
    }
    for Located { value, pos } in &refs.acts {
        if knows(value) {
            continue;
        }
        let hint = did_you_mean(value, labels.iter().copied());
        let message = format!(
            "The attract loop triggers the act `{value}`, but no act has that label.{hint} \
             Fix `act` in docent.yaml or add the act."
        );
        out.push(Diagnostic::error(DiagnosticCode::UnknownAct, pos, message));
    }
}
