//! A site's reactions to robot events (`reactions:` in `docent.yaml`): when the robot notices
//! `event` and its reading passes `if`, trigger `act`, at most once per `cooldown`. The
//! paper's info terminal "reacts to nearby persons and automatically advertises itself";
//! this is how a site says so without code.
//!
//! The condition is the one grammar of `if:`, read here and evaluated by `robot::reactions`:
//! comparisons of a field of the event's data with a value, joined by `and`:
//!
//! ```text
//! condition  = comparison { "and" comparison }
//! comparison = field op value
//! field      = name { "." name }        (a path into the event's data: `distance`, `pose.x`)
//! op         = "<" | "<=" | ">" | ">=" | "==" | "!="
//! value      = number | "quoted text" | true | false
//! ```

use std::fmt;
use std::time::Duration;

use serde_json::Value;

/// The cool-down when a reaction sets none: long enough that a person standing in front of
/// the robot is greeted once, not every time the tracker repeats itself.
pub const DEFAULT_COOLDOWN: Duration = Duration::from_secs(30);

/// One reaction, as read from `docent.yaml`.
#[derive(Clone, Debug, PartialEq)]
pub struct Reaction {
    /// The robot event that sets it off (`person.near`).
    pub event: String,
    /// What the event's data must satisfy; always, when absent.
    pub condition: Option<Condition>,
    /// The act it triggers (checked to exist when the bundle loads).
    pub act: String,
    /// The least time between two of its triggers.
    pub cooldown: Duration,
}

/// An `if:` condition: every comparison must hold.
#[derive(Clone, Debug, PartialEq)]
pub struct Condition {
    comparisons: Vec<Comparison>,
    written: String,
}

#[derive(Clone, Debug, PartialEq)]
struct Comparison {
    field: Vec<String>,
    op: Op,
    value: Literal,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Op {
    Less,
    LessOrEqual,
    Greater,
    GreaterOrEqual,
    Equal,
    NotEqual,
}

#[derive(Clone, Debug, PartialEq)]
enum Literal {
    Number(f64),
    Text(String),
    Bool(bool),
}

/// Why a condition could not be read: what, and where in the written text (a byte offset).
#[derive(Clone, Debug, PartialEq)]
pub struct ConditionError {
    /// Byte offset into the condition's text.
    pub offset: usize,
    /// What is wrong, in the author's words.
    pub message: String,
}

const OPS: [(&str, Op); 6] = [
    ("<=", Op::LessOrEqual),
    (">=", Op::GreaterOrEqual),
    ("==", Op::Equal),
    ("!=", Op::NotEqual),
    ("<", Op::Less),
    (">", Op::Greater),
];

impl Condition {
    /// Reads `text` by the grammar above.
    pub fn parse(text: &str) -> Result<Condition, ConditionError> {
        let mut comparisons = Vec::new();
        let mut rest = Scanner { text, at: 0 };
        loop {
            comparisons.push(rest.comparison()?);
            rest.skip_spaces();
            if rest.done() {
                break;
            }
            if let Some(decimals) = rest.remaining().strip_prefix(',')
                && decimals.starts_with(|c: char| c.is_ascii_digit())
            {
                return Err(rest.error_at(
                    rest.at,
                    "numbers are written with a decimal point, not a comma: `1.5`, not `1,5`"
                        .to_owned(),
                ));
            }
            let word = rest.word();
            if word != "and" {
                return Err(rest.error_at(
                    rest.at - word.len(),
                    format!(
                        "expected `and` and another comparison, or the end, but found `{}`",
                        if word.is_empty() {
                            rest.remaining()
                        } else {
                            word
                        }
                    ),
                ));
            }
        }
        Ok(Condition {
            comparisons,
            written: text.trim().to_owned(),
        })
    }

    /// Whether `data` satisfies every comparison; `Err` says why it cannot be decided (a
    /// field the event did not carry, or one of another kind than its value).
    pub fn holds(&self, data: &Value) -> Result<bool, String> {
        for comparison in &self.comparisons {
            if !comparison.holds(data)? {
                return Ok(false);
            }
        }
        Ok(true)
    }
}

impl fmt::Display for Condition {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.written)
    }
}

impl Comparison {
    fn holds(&self, data: &Value) -> Result<bool, String> {
        let path = self.field.join(".");
        let found = self
            .field
            .iter()
            .try_fold(data, |value, name| value.get(name))
            .ok_or_else(|| format!("the event's data has no field `{path}`"))?;
        let ordering = match (&self.value, found) {
            (Literal::Number(want), Value::Number(n)) => n
                .as_f64()
                .and_then(|got| got.partial_cmp(want))
                .ok_or_else(|| format!("`{path}` is not a comparable number ({n})"))?,
            (Literal::Text(want), Value::String(got)) => got.as_str().cmp(want.as_str()),
            (Literal::Bool(want), Value::Bool(got)) => got.cmp(want),
            (literal, other) => {
                return Err(format!(
                    "`{path}` is {} ({other}), but the condition compares it with {}",
                    kind_of(other),
                    literal.kind()
                ));
            }
        };
        Ok(match self.op {
            Op::Less => ordering.is_lt(),
            Op::LessOrEqual => ordering.is_le(),
            Op::Greater => ordering.is_gt(),
            Op::GreaterOrEqual => ordering.is_ge(),
            Op::Equal => ordering.is_eq(),
            Op::NotEqual => ordering.is_ne(),
        })
    }
}

fn kind_of(value: &Value) -> &'static str {
    match value {
        Value::Null => "null",
        Value::Bool(_) => "true or false",
        Value::Number(_) => "a number",
        Value::String(_) => "text",
        Value::Array(_) => "a list",
        Value::Object(_) => "a set of fields",
    }
}

impl Literal {
    fn kind(&self) -> &'static str {
        match self {
            Literal::Number(_) => "a number",
            Literal::Text(_) => "text",
            Literal::Bool(_) => "true or false",
        }
    }
}

struct Scanner<'t> {
    text: &'t str,
    at: usize,
}

impl<'t> Scanner<'t> {
    fn remaining(&self) -> &'t str {
        &self.text[self.at..]
    }

    fn done(&self) -> bool {
        self.remaining().is_empty()
    }

    fn skip_spaces(&mut self) {
        let rest = self.remaining();
        self.at += rest.len() - rest.trim_start().len();
    }

    fn error_at(&self, offset: usize, message: String) -> ConditionError {
        ConditionError { offset, message }
    }

    /// A run of letters, digits, `_`, `.` and `-` (a field, a number, a word).
    fn word(&mut self) -> &'t str {
        self.skip_spaces();
        let rest = self.remaining();
        let end = rest
            .find(|c: char| !(c.is_alphanumeric() || "_.-+".contains(c)))
            .unwrap_or(rest.len());
        self.at += end;
        &rest[..end]
    }

    fn comparison(&mut self) -> Result<Comparison, ConditionError> {
        self.skip_spaces();
        let start = self.at;
        let field = self.word();
        let names: Vec<String> = field.split('.').map(str::to_owned).collect();
        let is_name = |n: &String| {
            n.chars().next().is_some_and(char::is_alphabetic)
                && n.chars()
                    .all(|c| c.is_alphanumeric() || c == '_' || c == '-')
        };
        if field.is_empty() || !names.iter().all(is_name) {
            let found = if field.is_empty() {
                self.remaining()
            } else {
                field
            };
            return Err(self.error_at(
                start,
                format!(
                    "expected the name of a field of the event's data (e.g. `distance` or \
                     `pose.x`), but found `{found}`"
                ),
            ));
        }
        self.skip_spaces();
        let op_at = self.at;
        let Some((symbol, op)) = OPS.iter().find(|(s, _)| self.remaining().starts_with(s)) else {
            let found = self.remaining();
            let advice = if found.starts_with('=') {
                "; to compare, write two equals signs: `==`"
            } else {
                ""
            };
            return Err(self.error_at(
                op_at,
                format!(
                    "after `{field}` comes a comparison: <, <=, >, >=, == or != (found \
                     `{found}`){advice}"
                ),
            ));
        };
        self.at += symbol.len();
        let value = self.literal()?;
        Ok(Comparison {
            field: names,
            op: *op,
            value,
        })
    }

    fn literal(&mut self) -> Result<Literal, ConditionError> {
        self.skip_spaces();
        let start = self.at;
        if let Some(quoted) = self.remaining().strip_prefix('"') {
            let Some(end) = quoted.find('"') else {
                return Err(self.error_at(start, "this text has no closing `\"`".to_owned()));
            };
            self.at += end + 2;
            return Ok(Literal::Text(quoted[..end].to_owned()));
        }
        let word = self.word();
        match word {
            "true" => Ok(Literal::Bool(true)),
            "false" => Ok(Literal::Bool(false)),
            _ => word
                .parse::<f64>()
                .ok()
                .filter(|n| n.is_finite() && !word.contains(['e', 'E', 'i', 'n', 'N']))
                .map(Literal::Number)
                .ok_or_else(|| {
                    let found = if word.is_empty() {
                        self.remaining()
                    } else {
                        word
                    };
                    self.error_at(
                        start,
                        format!(
                            "expected a number, \"quoted text\", true or false, but found \
                             `{found}`; text is written in double quotes: \"{found}\""
                        ),
                    )
                }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn comparisons_joined_by_and_decide_on_the_data() {
        let c = Condition::parse("distance < 1.5 and person.name == \"Ada\"").unwrap();
        let near = json!({"distance": 1.2, "person": {"name": "Ada"}});
        assert_eq!(c.holds(&near), Ok(true));
        assert_eq!(
            c.holds(&json!({"distance": 2, "person": {"name": "Ada"}})),
            Ok(false)
        );
        let c = Condition::parse("percentage <= 20").unwrap();
        assert_eq!(c.holds(&json!({"percentage": 20})), Ok(true));
        let c = Condition::parse("pressed != false").unwrap();
        assert_eq!(c.holds(&json!({"pressed": true})), Ok(true));
        let c = Condition::parse("data==\"hello\"").unwrap();
        assert_eq!(c.holds(&json!({"data": "hello"})), Ok(true));
        assert_eq!(c.to_string(), "data==\"hello\"");
    }

    #[test]
    fn undecidable_data_is_told_not_taken_as_false() {
        let c = Condition::parse("distance < 1.5").unwrap();
        assert_eq!(
            c.holds(&json!({"range": 1})),
            Err("the event's data has no field `distance`".to_owned())
        );
        assert_eq!(
            c.holds(&json!({"distance": "near"})),
            Err(
                "`distance` is text (\"near\"), but the condition compares it with a number"
                    .to_owned()
            )
        );
    }

    #[test]
    fn mistakes_are_placed_and_explained() {
        let cases = [
            ("distance 1.5", 9, "after `distance` comes a comparison"),
            ("distance < near", 11, "\"quoted text\""),
            ("distance < 1.5 or x > 2", 15, "expected `and`"),
            ("distance < 1,5", 12, "decimal point, not a comma"),
            ("name = \"Ada\"", 5, "two equals signs: `==`"),
            ("< 2", 0, "expected the name of a field"),
            ("name == \"Ada", 8, "no closing"),
            ("distance < 1e3", 11, "expected a number"),
            ("1x < 2", 0, "expected the name of a field"),
        ];
        for (text, offset, words) in cases {
            let err = Condition::parse(text).unwrap_err();
            assert_eq!(err.offset, offset, "{text}: {}", err.message);
            assert!(err.message.contains(words), "{text}: {}", err.message);
        }
    }
}
