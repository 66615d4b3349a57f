//! The `access:` section of `docent.yaml`: the operator's and the dialog manager's tokens.
//! A token is never repeated in a message (messages end up in logs and terminals); the
//! environment variables named here take precedence over the file at serve time.

use crate::DiagnosticCode;
use crate::acts_file::yaml::{Kind, Node};
use crate::config::{AccessSettings, Credential};
use crate::diagnostic::Diagnostic;

use serde_json::{Value, json};

use super::Reader;
use super::section::{Field, Section, Shape};

/// The settings of `access:`.
pub(crate) const SECTION: Section = Section {
    name: "access",
    required: &[],
    fields: &[
        Field {
            key: "operator_token",
            description: "The credential the operator console shows to connect",
            shape: Shape::Custom(credential_schema),
        },
        Field {
            key: "dm_token",
            description: "The credential the dialog manager shows to connect",
            shape: Shape::Custom(credential_schema),
        },
    ],
};

/// A token: printable characters without spaces, at least [`Credential::MIN_CHARS`] of them
/// (the rest of [`Credential::new`]'s rules need the whole text and stay with `docent check`).
fn credential_schema(description: &'static str) -> Value {
    let min = Credential::MIN_CHARS;
    json!({
        "type": "string",
        "pattern": format!("^[!-~]{{{min},}}$"),
        "description": format!(
            "{description}: at least {min} characters, no spaces, e.g. the output of \
             `openssl rand -hex 16`."
        ),
    })
}

impl Reader {
    /// Reads `access:` into `access`.
    pub(super) fn access(&mut self, node: &Node, access: &mut AccessSettings) {
        if !matches!(node.kind, Kind::Map(_) | Kind::Null) {
            // Not `bad()`: that would repeat the value, which may be a token.
            let message = format!(
                "`access` must be a set of settings ({}), e.g. \
                 `access: {{ operator_token: ... }}`, but it is {} here.",
                SECTION.keys().join(", "),
                node.describe()
            );
            self.diagnostics.push(Diagnostic::error(
                DiagnosticCode::ConfigBadValue,
                &node.pos,
                message,
            ));
            return;
        }
        for (field, value) in self.entries(node, &SECTION) {
            let key = field.key;
            let (who, variable) = match key {
                "operator_token" => ("operator console", "DOCENT_OPERATOR_TOKEN"),
                _ => ("dialog manager", "DOCENT_DM_TOKEN"),
            };
            let token = self.credential(value, key, who, variable);
            match key {
                "operator_token" => access.operator_token = token,
                _ => access.dm_token = token,
            }
        }
    }

    fn credential(
        &mut self,
        node: &Node,
        key: &str,
        who: &str,
        variable: &str,
    ) -> Option<Credential> {
        let advice = format!(
            "Use a long random one, e.g. the output of `openssl rand -hex 16`, or leave it out \
             here and set {variable} when starting Docent."
        );
        let Some(text) = node.as_text() else {
            let message = format!(
                "`{key}` is the token the {who} must show to connect, and it is {} here. \
                 {advice}",
                node.describe()
            );
            self.diagnostics.push(Diagnostic::error(
                DiagnosticCode::ConfigBadValue,
                &node.pos,
                message,
            ));
            return None;
        };
        match Credential::new(text) {
            Ok(token) => Some(token),
            Err(why) => {
                let message =
                    format!("The {who}'s token (`{key}`) is too easy to guess: {why}. {advice}");
                self.diagnostics.push(Diagnostic::error(
                    DiagnosticCode::WeakCredential,
                    &node.pos,
                    message,
                ));
                None
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::config_file::test_support::parse;

    #[test]
    fn tokens_are_read_and_kept_out_of_debug_output() {
        let file = parse(
            "access:\n  operator_token: \"op-0123456789abcdef\"\n  dm_token: dm-0123456789abcdef\n",
        );
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        let access = &file.config.access;
        assert_eq!(
            access.operator_token.as_ref().map(|t| t.expose()),
            Some("op-0123456789abcdef")
        );
        assert_eq!(
            access.dm_token.as_ref().map(|t| t.expose()),
            Some("dm-0123456789abcdef")
        );
        assert!(!format!("{:?}", file.config).contains("0123456789abcdef"));
    }

    #[test]
    fn weak_tokens_are_located_and_never_repeated() {
        let file = parse(
            "access:\n  operator_token: hunter2\n  dm_token: \"a long token with spaces\"\n  \
             dm_tokn: x\n",
        );
        let found: Vec<_> = file
            .diagnostics
            .iter()
            .map(|d| (d.code.as_str(), d.line, d.column))
            .collect();
        assert_eq!(
            found,
            [
                ("config-unknown-key", 4, 3),
                ("weak-credential", 2, 19),
                ("weak-credential", 3, 13),
            ]
        );
        assert!(
            file.diagnostics[0]
                .message
                .contains("Did you mean `dm_token`?")
        );
        let weak = &file.diagnostics[1].message;
        assert!(weak.contains("7 characters, and at least 16"), "{weak}");
        assert!(weak.contains("DOCENT_OPERATOR_TOKEN"), "{weak}");
        assert!(file.diagnostics[2].message.contains("no spaces"));
        assert!(file.diagnostics[2].message.contains("DOCENT_DM_TOKEN"));
        for d in &file.diagnostics {
            assert!(!d.message.contains("hunter2"), "{}", d.message);
            assert!(!d.message.contains("with spaces"), "{}", d.message);
        }
        assert_eq!(file.config.access, Default::default());
    }

    #[test]
    fn an_empty_token_is_a_bad_value() {
        let file = parse("access:\n  operator_token:\n");
        assert_eq!(file.diagnostics.len(), 1);
        assert_eq!(file.diagnostics[0].code, "config-bad-value");
        assert_eq!(
            (file.diagnostics[0].line, file.diagnostics[0].column),
            (2, 17)
        );
        assert!(parse("access:\n").diagnostics.is_empty());
        let file = parse("access: op-0123456789abcdef\n");
        assert_eq!(file.diagnostics[0].code, "config-bad-value");
        assert!(!file.diagnostics[0].message.contains("0123456789"));
    }
}
