//! JSON Schemas of the two content formats, for editors: the acts file ([`acts_schema`]) and
//! `docent.yaml` ([`config_schema`]). VS Code's YAML extension (yaml-language-server) reads
//! them through a `# yaml-language-server: $schema=...` first line and flags mistakes while
//! the author types, with the descriptions as hover help.
//!
//! Draft-07, because that is the draft yaml-language-server implements fully (newer drafts are
//! partial there). The schemas are built from the loader's own constants (the act keys, the
//! built-in verbs) and, for `docent.yaml`, from the reader's one definition per section
//! (`config_file/section.rs`), so the two cannot drift; tests in this module and
//! `tests/schema.rs` hold them to what the loader accepts. `docent check` stays the authority:
//! some rules need the whole bundle (does a page exist, is a site command declared) and no
//! schema can say them.
//!
//! - `acts`: the acts file.
//! - `config`: `docent.yaml`.

use serde_json::{Value, json};

mod acts;
mod config;

pub use acts::acts_schema;
pub use config::config_schema;
pub(crate) use config::section_schema;

/// The draft every schema declares.
const DRAFT: &str = "http://json-schema.org/draft-07/schema#";

/// A context name: `Text`, or `Text` then letters, digits or `_` (any alphabet), as the
/// loader's `is_context_name` accepts. `\p{...}` needs the `u` flag, which ajv and
/// yaml-language-server both set.
pub(crate) const VARIANT_KEY_PATTERN: &str = r"^Text[\p{Alphabetic}\p{N}_]*$";

/// A schema as the committed `docs/schema/*.json` files hold it: pretty JSON and a newline.
pub fn to_file_text(schema: &Value) -> String {
    let mut text = serde_json::to_string_pretty(schema).unwrap_or_default();
    text.push('\n');
    text
}

/// A value written as text that must not be blank; YAML numbers and yes/no values are
/// accepted too (the loader keeps them as written and only warns).
pub(crate) fn words(description: &str) -> Value {
    json!({
        "type": ["string", "number", "boolean"],
        "pattern": r"\S",
        "description": description,
    })
}

/// A length of time with its unit, as `duration.rs` parses it.
pub(crate) fn duration(description: &str) -> Value {
    json!({
        "type": "string",
        "pattern": r"^\s*(\d+(\.\d*)?|\.\d+)(ms|s|m|h)\s*$",
        "description": description,
        "examples": ["500ms", "2s", "1.5m"],
    })
}

/// One of fixed words.
pub(crate) fn choice(words: &[&str], description: &str) -> Value {
    json!({ "enum": words, "description": description })
}

/// A regular expression matching `word` in any case (`png` → `[pP][nN][gG]`), since JSON
/// Schema patterns take no flags.
pub(crate) fn any_case(word: &str) -> String {
    word.chars()
        .map(|c| {
            if c.is_ascii_alphabetic() {
                format!("[{}{}]", c.to_ascii_lowercase(), c.to_ascii_uppercase())
            } else {
                regex_escape(c)
            }
        })
        .collect()
}

/// `c` as a regular expression matching itself.
fn regex_escape(c: char) -> String {
    if r"\^$.|?*+()[]{}/-".contains(c) {
        format!("\\{c}")
    } else {
        c.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn any_case_matches_each_letter_in_both_cases() {
        assert_eq!(any_case("png"), "[pP][nN][gG]");
        assert_eq!(any_case("a.b"), r"[aA]\.[bB]");
    }

    #[test]
    fn both_schemas_declare_draft_07() {
        assert_eq!(acts_schema()["$schema"], DRAFT);
        assert_eq!(config_schema()["$schema"], DRAFT);
    }
}
