//! The `codebook:` section of `docent.yaml`: the annotation tiers researchers code a recorded
//! session with on the `/sessions` page (the paper's dialog situations, visitor behaviour
//! classes), each tier's codes in written order, each code with an optional one-key shortcut.
//! A top-level section rather than part of `corpus:` because it describes how a corpus is
//! *read* (coded), not how it is recorded, and a bundle may share it between sites.
//!
//! ```yaml
//! codebook:
//!   situation: { question: q, laughter: l, leaving: x }
//!   behaviour: { approaching: a, watching: w, touching: t, leaving-group: }
//! ```
//!
//! Absent, the codebook is one tier, `situation`, of `operator.situations` with the keys 1 to
//! 9 (the order the console's Alt+Shift+1..9 marks them in).

use serde::Serialize;

use crate::DiagnosticCode;
use crate::acts_file::yaml::{Kind, Node};
use crate::diagnostic::Diagnostic;
use crate::model::Pos;

use serde_json::{Value, json};

use super::Reader;

/// The schema of `codebook:`: tier name to codes, each code with a one-key shortcut or none;
/// or a list of codes without shortcuts.
pub(crate) fn schema(description: &'static str) -> Value {
    let key = json!({
        "anyOf": [
            { "type": "null" },
            { "type": "string", "pattern": "^[A-Za-z0-9]$" },
            { "type": "integer", "minimum": 0, "maximum": 9 },
        ],
        "description": "The code's shortcut on the /sessions page: one letter or digit, or \
                        nothing (chosen by click only).",
    });
    let code = json!({ "type": "string", "minLength": 1, "maxLength": MAX_NAME });
    let tier = json!({
        "description": "A tier's codes: `{question: q, laughter: l}` (code: shortcut), or a \
                        list of codes without shortcuts.",
        "anyOf": [
            { "type": "object", "minProperties": 1, "additionalProperties": key },
            { "type": "array", "minItems": 1, "items": code, "uniqueItems": true },
        ],
    });
    json!({
        "description": description,
        "anyOf": [
            { "type": "null" },
            {
                "type": "object",
                "propertyNames": { "pattern": "^[A-Za-z][A-Za-z0-9._-]{0,63}$" },
                "additionalProperties": tier,
            },
        ],
    })
}

/// The tier the default codebook (from `operator.situations`) codes.
pub const DEFAULT_TIER: &str = "situation";
/// The names of the exports' own tiers (`corpus/export/tiers.rs`): a codebook tier may not
/// take one, nor one of their numbered forms (`speech-2`).
const EXPORT_TIERS: &[&str] = &["speech", "act", "commands", "pages", "touches", "marks"];
/// The other names an EAF uses, in the one `xsd:ID` space tier names share
/// (`corpus/export/eaf/elements.rs`), separated by spaces (names, not diagnostic codes).
const EAF_NAMES: &str = "utterance act-label event instant act-labels und";
/// Longest code or tier name.
const MAX_NAME: usize = 64;

const CODEBOOK_USAGE: &str = "`codebook` lists annotation tiers, each a set of codes with an \
                              optional one-key shortcut, e.g. `codebook: {situation: \
                              {question: q, laughter: l}}`.";
const TIER_USAGE: &str = "A tier's name starts with a letter and has only letters, digits, \
                          `-`, `_` and `.` (ELAN and Praat use it as the tier's name), e.g. \
                          `situation` or `visitor-behaviour`.";
const CODE_USAGE: &str = "A code is a short name on one line, at most 64 characters, e.g. \
                          `question`.";

/// The annotation tiers researchers code sessions with, in written order.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Codebook {
    /// Its tiers.
    pub tiers: Vec<CodebookTier>,
}

/// One annotation tier and its codes.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CodebookTier {
    /// The tier's name (also its name in the exports).
    pub name: String,
    /// Its codes, in written order.
    pub codes: Vec<Code>,
}

/// A code and its shortcut.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Code {
    /// The code, as annotations and exports write it.
    pub code: String,
    /// Its shortcut on the `/sessions` page: a lower-case letter or a digit.
    pub key: Option<char>,
}

impl Codebook {
    /// The default codebook: one `situation` tier of the operator's situations, keyed 1 to 9.
    pub fn from_situations(situations: &[String]) -> Codebook {
        if situations.is_empty() {
            return Codebook::default();
        }
        let codes = (situations.iter().enumerate())
            .map(|(n, s)| Code {
                code: s.clone(),
                key: char::from_digit(n as u32 + 1, 10),
            })
            .collect();
        let tier = CodebookTier {
            name: DEFAULT_TIER.to_owned(),
            codes,
        };
        Codebook { tiers: vec![tier] }
    }

    /// The tier named `name`.
    pub fn tier(&self, name: &str) -> Option<&CodebookTier> {
        self.tiers.iter().find(|t| t.name == name)
    }
}

impl CodebookTier {
    /// Whether `code` is one of this tier's codes.
    pub fn has(&self, code: &str) -> bool {
        self.codes.iter().any(|c| c.code == code)
    }
}

/// Whether `name` can name a tier: an XML name ELAN takes as an id, and none of the exports'.
fn tier_name_ok(name: &str) -> bool {
    let mut chars = name.chars();
    let first = chars.next().is_some_and(|c| c.is_ascii_alphabetic());
    first
        && name.len() <= MAX_NAME
        && chars.all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
}

/// Whether `name` is taken by the exports: one of their own tiers or one of its numbered
/// forms, a codebook tier's point tier (`NAME-points`), or a name of the EAF's id space.
fn reserved(name: &str) -> bool {
    let digits = |n: &str| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit());
    let base = match name.rsplit_once('-') {
        Some((base, n)) if digits(n) => base,
        _ => name,
    };
    EXPORT_TIERS.contains(&base)
        || EAF_NAMES.split(' ').any(|n| n == name)
        || base.ends_with("-points")
        || ["coded-", "codebook-", "cveid_"]
            .iter()
            .any(|p| name.starts_with(p))
        || ["a", "ts"]
            .iter()
            .any(|p| name.strip_prefix(p).is_some_and(digits))
}

/// A shortcut as written, if it is one letter or digit (letters in lower case).
fn shortcut(text: &str) -> Option<char> {
    let mut chars = text.trim().chars();
    match (chars.next(), chars.next()) {
        (Some(c), None) if c.is_ascii_alphanumeric() => Some(c.to_ascii_lowercase()),
        _ => None,
    }
}

impl Reader {
    /// Reads `codebook:`.
    pub(super) fn codebook(&mut self, node: &Node) -> Codebook {
        let entries = match &node.kind {
            Kind::Map(entries) => entries,
            Kind::Null => return Codebook::default(),
            _ => {
                self.bad(node, CODEBOOK_USAGE);
                return Codebook::default();
            }
        };
        let mut codebook = Codebook::default();
        let mut tiers_seen: Vec<(&str, &Pos)> = Vec::new();
        let mut keys_seen: Vec<(char, String, Pos)> = Vec::new();
        for (name_node, codes_node) in entries {
            let name = name_node.as_text().map(str::trim).unwrap_or_default();
            if let Some((_, first)) = tiers_seen.iter().find(|(n, _)| *n == name) {
                self.twice(name_node, name, first);
                continue;
            }
            tiers_seen.push((name, &name_node.pos));
            if !tier_name_ok(name) {
                self.bad(name_node, TIER_USAGE);
                continue;
            }
            if reserved(name) {
                let message = format!(
                    "`{name}` is a name the exports use themselves (their tiers {}; names \
                     ending in `-points` or starting with `coded-` or `codebook-`). Give the \
                     annotation tier another name, e.g. `{name}-code`.",
                    EXPORT_TIERS.join(", ")
                );
                self.bad(name_node, &message);
                continue;
            }
            let codes = self.codes(codes_node, &mut keys_seen);
            let name = name.to_owned();
            codebook.tiers.push(CodebookTier { name, codes });
        }
        codebook
    }

    /// One tier's codes: `{code: key, ...}`, or a list of codes without keys.
    fn codes(&mut self, node: &Node, keys_seen: &mut Vec<(char, String, Pos)>) -> Vec<Code> {
        let pairs: Vec<(&Node, Option<&Node>)> = match &node.kind {
            Kind::Map(entries) => entries.iter().map(|(k, v)| (k, Some(v))).collect(),
            Kind::Seq(items) => items.iter().map(|i| (i, None)).collect(),
            _ => {
                self.bad(node, CODEBOOK_USAGE);
                return Vec::new();
            }
        };
        if pairs.is_empty() {
            self.bad(node, CODEBOOK_USAGE);
        }
        let mut codes: Vec<(Code, &Pos)> = Vec::new();
        for (code_node, key_node) in pairs {
            let code = code_node.as_text().map(str::trim).unwrap_or_default();
            if code.is_empty() || code.len() > MAX_NAME || code.contains(['\n', '\r', '\t']) {
                self.bad(code_node, CODE_USAGE);
                continue;
            }
            if let Some((_, first)) = codes.iter().find(|(c, _)| c.code == code) {
                let first = (*first).clone();
                self.twice(code_node, code, &first);
                continue;
            }
            let key = key_node.and_then(|k| self.key(k, code, keys_seen));
            let code = code.to_owned();
            codes.push((Code { code, key }, &code_node.pos));
        }
        codes.into_iter().map(|(code, _)| code).collect()
    }

    /// A code's shortcut: none when empty; reported when it is not one letter or digit, or
    /// another code has it.
    fn key(
        &mut self,
        node: &Node,
        code: &str,
        keys_seen: &mut Vec<(char, String, Pos)>,
    ) -> Option<char> {
        if matches!(node.kind, Kind::Null) {
            return None;
        }
        let written = node.as_text().unwrap_or_default();
        let Some(key) = shortcut(written) else {
            let message = format!(
                "The shortcut of `{code}` must be one letter (a to z) or one digit (0 to 9), or \
                 nothing for a code chosen by click only (`{code}:` or `{code}: ~`). Found: \
                 {}.",
                node.as_text()
                    .map_or_else(|| node.describe().to_owned(), |t| format!("`{t}`"))
            );
            let diagnostic = Diagnostic::error(DiagnosticCode::CodebookBadKey, &node.pos, message);
            self.diagnostics.push(diagnostic);
            return None;
        };
        if let Some((_, other, first)) = keys_seen.iter().find(|(k, _, _)| *k == key) {
            let message = format!(
                "The key `{key}` is already the shortcut of `{other}` (line {}, column {}); one \
                 key marks one code (`A` and `a` count as the same). Choose another key for \
                 `{code}`.",
                first.line, first.column
            );
            let diagnostic =
                Diagnostic::error(DiagnosticCode::CodebookKeyTaken, &node.pos, message);
            self.diagnostics.push(diagnostic);
            return None;
        }
        keys_seen.push((key, code.to_owned(), node.pos.clone()));
        Some(key)
    }

    /// Reports a tier or code written twice (`duplicate-key`).
    fn twice(&mut self, node: &Node, name: &str, first: &Pos) {
        let message = format!(
            "`{name}` is written twice here (first on line {}). Keep one.",
            first.line
        );
        (self.diagnostics).push(Diagnostic::error(
            DiagnosticCode::DuplicateKey,
            &node.pos,
            message,
        ));
    }
}

#[cfg(test)]
mod tests {
    use crate::config_file::test_support::parse;

    use super::*;

    fn located(text: &str) -> Vec<(&'static str, u32, u32)> {
        let file = parse(text);
        (file.diagnostics.iter())
            .map(|d| (d.code.as_str(), d.line, d.column))
            .collect()
    }

    #[test]
    fn the_documented_example_is_read_in_written_order() {
        let file = parse(
            "codebook:\n  situation: { question: q, laughter: L, leaving: 1 }\n  \
             behaviour: [approaching, watching]\n",
        );
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        let codebook = &file.config.codebook;
        let names: Vec<&str> = codebook.tiers.iter().map(|t| t.name.as_str()).collect();
        assert_eq!(names, ["situation", "behaviour"]);
        let situation = codebook.tier("situation").expect("situation");
        let keys: Vec<(&str, Option<char>)> = (situation.codes.iter())
            .map(|c| (c.code.as_str(), c.key))
            .collect();
        assert_eq!(
            keys,
            [
                ("question", Some('q')),
                ("laughter", Some('l')),
                ("leaving", Some('1'))
            ]
        );
        assert!(
            codebook
                .tier("behaviour")
                .expect("behaviour")
                .has("watching")
        );
    }

    #[test]
    fn without_a_codebook_the_situations_are_one_tier_keyed_one_to_nine() {
        let file = parse("operator:\n  situations: [question, laughter]\n");
        let tier = &file.config.codebook.tiers[0];
        assert_eq!(tier.name, DEFAULT_TIER);
        let keys: Vec<Option<char>> = tier.codes.iter().map(|c| c.key).collect();
        assert_eq!(keys, [Some('1'), Some('2')]);
        assert!(parse("home: a.html\n").config.codebook.tiers.is_empty());
    }

    #[test]
    fn a_key_given_twice_is_reported_at_the_second_naming_the_first() {
        let text = "codebook:\n  situation: {question: q}\n  behaviour: {quiet: Q}\n";
        assert_eq!(located(text), [("codebook-key-taken", 3, 22)]);
        let file = parse(text);
        assert!(
            file.diagnostics[0]
                .message
                .contains("`question` (line 2, column 25)")
        );
        let quiet = &file.config.codebook.tiers[1].codes[0];
        assert_eq!((quiet.code.as_str(), quiet.key), ("quiet", None));
    }

    #[test]
    fn a_key_that_is_not_one_letter_or_digit_is_reported() {
        assert_eq!(
            located("codebook:\n  situation: {question: qq, laughter: \" \", pause: [x]}\n"),
            [
                ("codebook-bad-key", 2, 25),
                ("codebook-bad-key", 2, 39),
                ("codebook-bad-key", 2, 51)
            ]
        );
    }

    #[test]
    fn codes_and_tiers_written_twice_and_bad_names_are_reported() {
        assert_eq!(
            located(
                "codebook:\n  situation: [question, question]\n  situation: [x]\n  \
                 2nd: [a]\n  speech-2: [b]\n  empty: []\n  mood-points: [c]\n  ts3: [d]\n"
            ),
            [
                ("duplicate-key", 2, 25),
                ("duplicate-key", 3, 3),
                ("config-bad-value", 4, 3),
                ("config-bad-value", 5, 3),
                ("config-bad-value", 6, 10),
                ("config-bad-value", 7, 3),
                ("config-bad-value", 8, 3)
            ]
        );
    }
}
