//! Problems found in a bundle, each with a stable code, a place and a plain-language message
//! written for museum staff rather than programmers.

use std::fmt;

use serde::Serialize;

use crate::model::Pos;

/// How bad a problem is: errors stop `docent serve`, warnings do not.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    /// The bundle cannot be served until this is fixed.
    Error,
    /// Worth fixing; the bundle still runs.
    Warning,
}

/// One problem, as `docent check` reports it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// A stable, kebab-case code (`duplicate-label`, `unknown-verb`, ...); documented in docs.
    pub code: &'static str,
    /// What is wrong and how to fix it, in plain words.
    pub message: String,
    /// File relative to the bundle root, `/`-separated.
    pub file: String,
    /// 1-based line; 1 when the problem concerns the whole file, never 0.
    pub line: u32,
    /// 1-based column in characters; 1 when the problem concerns the whole file, never 0.
    pub column: u32,
}

impl Diagnostic {
    /// An error at `pos`.
    pub fn error(code: &'static str, pos: &Pos, message: impl Into<String>) -> Self {
        Self::at(Severity::Error, code, pos, message)
    }

    /// A warning at `pos`.
    pub fn warning(code: &'static str, pos: &Pos, message: impl Into<String>) -> Self {
        Self::at(Severity::Warning, code, pos, message)
    }

    fn at(severity: Severity, code: &'static str, pos: &Pos, message: impl Into<String>) -> Self {
        Diagnostic {
            severity,
            code,
            message: message.into(),
            file: pos.file.to_string(),
            line: pos.line,
            column: pos.column,
        }
    }

    /// True for errors.
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        write!(
            f,
            "{}:{}:{}: {kind}[{}]: {}",
            self.file, self.line, self.column, self.code, self.message
        )
    }
}
