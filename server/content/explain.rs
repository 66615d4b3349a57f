//! The reference of every problem `docent check` reports, made from the checker's own table
//! (`diagnostic.rs`) so the two cannot drift: a code's summary is its doc comment there, and
//! the rest (its kind, severity, fix, and a broken example with its fix) is its page,
//! `diagnostics/CODE.md`, compiled into the binary. `docent explain CODE` prints one code
//! ([`explain_text`]); `docs/DIAGNOSTICS.md` is [`reference_markdown`], checked against the
//! file by a test (`DOCENT_BLESS=1` rewrites it).
//!
//! A page opens with front matter between two `---` lines (`group: acts`, `severity: error`,
//! `fix: Add ...`: see `diagnostics/missing-label.md`), then the Markdown of the entry.

use std::fmt::Write as _;

use crate::diagnostic::DiagnosticCode;
use crate::suggest::closest;

/// The kinds of problem, each a table of the reference, in its order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Group {
    /// The folder and its files.
    Bundle,
    /// How YAML reads the layout of a file.
    Yaml,
    /// The keys of an act.
    Acts,
    /// `Cmds:` and their verbs.
    Commands,
    /// A text YAML changed on its way to the robot.
    YamlText,
    /// What a speech synthesiser would make of a text.
    Speech,
    /// Context variants and acts nothing triggers.
    Contexts,
    /// Translations and the bundle's languages.
    Languages,
    /// `data-act` on pages.
    Pages,
    /// `docent.yaml`.
    Settings,
    /// The markup of pages, and pictures, films and sounds.
    Media,
}

impl Group {
    /// Every group, in the reference's order.
    pub const ALL: &'static [Group] = &[
        Group::Bundle,
        Group::Yaml,
        Group::Acts,
        Group::Commands,
        Group::YamlText,
        Group::Speech,
        Group::Contexts,
        Group::Languages,
        Group::Pages,
        Group::Settings,
        Group::Media,
    ];

    /// The word a page's `group:` line uses.
    pub fn slug(self) -> &'static str {
        match self {
            Group::Bundle => "bundle",
            Group::Yaml => "yaml",
            Group::Acts => "acts",
            Group::Commands => "commands",
            Group::YamlText => "yaml-text",
            Group::Speech => "speech",
            Group::Contexts => "contexts",
            Group::Languages => "languages",
            Group::Pages => "pages",
            Group::Settings => "settings",
            Group::Media => "media",
        }
    }

    /// The group's heading in the reference.
    pub fn title(self) -> &'static str {
        match self {
            Group::Bundle => "The bundle and its files",
            Group::Yaml => "YAML layout",
            Group::Acts => "Acts",
            Group::Commands => "Commands",
            Group::YamlText => "What YAML did to a text",
            Group::Speech => "What the robot will say",
            Group::Contexts => "Contexts and unused acts",
            Group::Languages => "Languages",
            Group::Pages => "Pages",
            Group::Settings => "Settings (`docent.yaml`)",
            Group::Media => "Pages and media",
        }
    }

    /// What the group's table says before its rows (empty for most).
    fn intro(self) -> &'static str {
        match self {
            Group::YamlText => {
                "These catch a text that reads well in your editor but reaches the robot changed. \
                 The message\nquotes what the robot would really say."
            }
            Group::Speech => {
                "Every text alternative and every `SAY` is checked for what a speech synthesiser \
                 reads\ndifferently from what you see. An error when the robot would certainly \
                 say something you did\nnot mean; a warning when it may be what you want."
            }
            _ => "",
        }
    }

    fn from_slug(slug: &str) -> Option<Group> {
        Group::ALL.iter().copied().find(|g| g.slug() == slug)
    }
}

/// One code's page, read from its front matter and body.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Page {
    /// The code.
    pub code: DiagnosticCode,
    /// Its kind (`None` when the page's `group:` is missing or unknown; a test refuses that).
    pub group: Option<Group>,
    /// `error`, `warning`, `note`, or two of them joined by `or`.
    pub severity: &'static str,
    /// How to fix it, in one sentence or two.
    pub fix: &'static str,
    /// The entry: what it is, a broken example, where it is reported, the fix (Markdown).
    pub body: &'static str,
}

/// The page of `code`, from `diagnostics/CODE.md`.
pub fn page(code: DiagnosticCode) -> Page {
    let source = code.page_source();
    let (front, body) = source
        .strip_prefix("---\n")
        .and_then(|rest| rest.split_once("\n---\n"))
        .unwrap_or(("", source));
    let field = |name: &str| {
        front
            .lines()
            .find_map(|line| line.strip_prefix(name)?.strip_prefix(':'))
            .map_or("", str::trim)
    };
    Page {
        code,
        group: Group::from_slug(field("group")),
        severity: field("severity"),
        fix: field("fix"),
        body: body.trim(),
    }
}

/// The code's summary: its doc comment in `diagnostic.rs`, as one paragraph.
pub fn summary(code: DiagnosticCode) -> String {
    let words: Vec<&str> = code.summary_lines().iter().map(|l| l.trim()).collect();
    words.join(" ")
}

/// The code written as `text` (`unknown-verb`), if Docent has it.
pub fn find_code(text: &str) -> Option<DiagnosticCode> {
    let text = text.trim().trim_matches('`').to_ascii_lowercase();
    DiagnosticCode::ALL
        .iter()
        .copied()
        .find(|c| c.as_str() == text)
}

/// The code nearest to a mistyped `text`, for "did you mean".
pub fn nearest_code(text: &str) -> Option<DiagnosticCode> {
    let near = closest(text, DiagnosticCode::ALL.iter().map(|c| c.as_str()))?;
    find_code(near)
}

/// What is wrong with the pages, for the test that holds them to their form: an unknown
/// group or severity, no fix, or no broken example with its fix (two code blocks).
pub fn page_problems() -> Vec<String> {
    let mut problems = Vec::new();
    for &code in DiagnosticCode::ALL {
        let page = page(code);
        let name = format!("diagnostics/{code}.md");
        if page.group.is_none() {
            problems.push(format!("{name}: `group:` is none of {}", group_slugs()));
        }
        let severities_known = page
            .severity
            .split(" or ")
            .all(|s| matches!(s, "error" | "warning" | "note"));
        if page.severity.is_empty() || !severities_known {
            problems.push(format!(
                "{name}: `severity:` is not error, warning or note (or two joined by `or`)"
            ));
        }
        if page.fix.is_empty() {
            problems.push(format!("{name}: no `fix:`"));
        }
        if page.body.matches("```").count() < 4 {
            problems.push(format!(
                "{name}: no broken example with its fix (two code blocks)"
            ));
        }
        if summary(code).is_empty() {
            problems.push(format!("{code}: no doc comment in diagnostic.rs"));
        }
    }
    problems
}

fn group_slugs() -> String {
    let slugs: Vec<&str> = Group::ALL.iter().map(|g| g.slug()).collect();
    slugs.join(", ")
}

/// One code explained for the terminal (`docent explain CODE`): Markdown, which reads as
/// plain text.
pub fn explain_text(code: DiagnosticCode) -> String {
    let page = page(code);
    format!(
        "{code} ({severity})\n\n{summary}\n\nHow to fix it: {fix}\n\n{body}\n\n\
         Every problem Docent reports: docs/DIAGNOSTICS.md#{code}\n",
        severity = page.severity,
        summary = wrap(&summary(code), 92),
        fix = wrap(page.fix, 92),
        body = page.body,
    )
}

/// `text` broken into lines of at most `width` characters, at spaces (a longer word stays whole).
fn wrap(text: &str, width: usize) -> String {
    let mut out = String::with_capacity(text.len());
    let mut line_len = 0;
    for word in text.split_whitespace() {
        let len = word.chars().count();
        if line_len > 0 && line_len + 1 + len > width {
            out.push('\n');
            line_len = 0;
        } else if line_len > 0 {
            out.push(' ');
            line_len += 1;
        }
        out.push_str(word);
        line_len += len;
    }
    out
}

/// The whole reference, `docs/DIAGNOSTICS.md`: a table for each group, then each code's entry.
pub fn reference_markdown() -> String {
    let pages: Vec<Page> = DiagnosticCode::ALL.iter().map(|&c| page(c)).collect();
    let mut out = String::from(HEADER);
    if pages.iter().any(|p| p.severity.contains("note")) {
        out.push_str(NOTE_SEVERITY);
    }
    out.push_str(AFTER_SEVERITIES);
    for &group in Group::ALL {
        let rows: Vec<&Page> = pages.iter().filter(|p| p.group == Some(group)).collect();
        if rows.is_empty() {
            continue;
        }
        let _ = write!(out, "\n### {}\n\n", group.title());
        if !group.intro().is_empty() {
            let _ = write!(out, "{}\n\n", group.intro());
        }
        out.push_str("| code | severity | what it means | how to fix it |\n");
        out.push_str("| --- | --- | --- | --- |\n");
        for p in rows {
            let what = local_links(&summary(p.code));
            let fix = local_links(p.fix);
            let _ = writeln!(out, "| `{}` | {} | {what} | {fix} |", p.code, p.severity);
        }
    }
    out.push_str(ONE_BY_ONE);
    for &group in Group::ALL {
        let entries: Vec<&Page> = pages.iter().filter(|p| p.group == Some(group)).collect();
        if entries.is_empty() {
            continue;
        }
        let _ = write!(out, "\n### {}, one by one\n", group.title());
        for p in entries {
            let _ = write!(out, "\n#### `{}`\n\n{}\n", p.code, local_links(p.body));
        }
    }
    out
}

/// Links to an anchor of the authoring guide (`(#yaml-quoting-rules)`) made to work from the
/// reference: `(AUTHORING.md#yaml-quoting-rules)`. Links to a code stay in the reference.
fn local_links(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find("](#") {
        let (before, after) = rest.split_at(at + 2);
        out.push_str(before);
        let anchor_end = after[1..].find(')').map_or(after.len(), |i| i + 1);
        let anchor = &after[1..anchor_end];
        let in_reference = find_code(anchor).is_some()
            || matches!(
                anchor,
                "every-problem-docent-reports" | "problems-one-by-one"
            );
        if !in_reference {
            out.push_str("AUTHORING.md");
        }
        rest = after;
    }
    out.push_str(rest);
    out
}

const HEADER: &str = "\
<!-- Generated from Docent's own table of problems: the codes and their summaries in
server/content/diagnostic.rs, each code's entry in server/content/diagnostics/CODE.md. Do not
edit this file: edit those, then run
DOCENT_BLESS=1 cargo test --locked -p docent-content --test content diagnostics_reference
(without DOCENT_BLESS the test fails while this file is out of date). -->

# Problems Docent reports

Every problem Docent reports (in `docent check`, `docent serve`, the operator console and the
content report) has a code, such as `unknown-verb`. This page lists them all: first a table
for each kind of problem, then each problem one by one with a broken example and its fix. To
read one in the terminal, type `docent explain` and the code:

```text
$ docent explain unknown-verb
```

How to read what `docent check` prints is in
[AUTHORING.md](AUTHORING.md#reading-what-docent-check-says).

## Every problem Docent reports

*Error* means the bundle cannot be served until it is fixed. *Warning* means it works, but
you should look.
";

const NOTE_SEVERITY: &str = "*Note* tells you what Docent does for you (nothing to fix).\n";

const AFTER_SEVERITIES: &str = "
Each code also has an entry with a broken example and its fix in
[Problems, one by one](#problems-one-by-one); the entry for a code is at the code itself,
for example [`#text-cut-by-comment`](#text-cut-by-comment).
";

const ONE_BY_ONE: &str = "
## Problems, one by one

Every code `docent check` reports, in the order of the tables above, each with a small
broken example and its fix. The examples show only the lines that matter; each one was
checked by putting it into a copy of `dialogs/paper-fig4` and running `docent check`.
*Reported at* says where the caret `^` points.
";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_link_into_the_guide_is_made_to_point_at_it_and_one_to_a_code_stays() {
        assert_eq!(
            local_links("see [quoting](#yaml-quoting-rules) and [`unknown-act`](#unknown-act)."),
            "see [quoting](AUTHORING.md#yaml-quoting-rules) and [`unknown-act`](#unknown-act)."
        );
    }

    #[test]
    fn a_long_summary_is_wrapped_at_spaces_for_the_terminal() {
        assert_eq!(wrap("one two three four", 9), "one two\nthree\nfour");
        assert_eq!(wrap("unbreakable-word x", 4), "unbreakable-word\nx");
    }

    #[test]
    fn a_code_is_found_as_typed_and_a_slip_gets_the_nearest() {
        assert_eq!(
            find_code(" Unknown-Verb "),
            Some(DiagnosticCode::UnknownVerb)
        );
        assert_eq!(find_code("unknown-vreb"), None);
        assert_eq!(
            nearest_code("unknown-vreb"),
            Some(DiagnosticCode::UnknownVerb)
        );
    }

    #[test]
    fn a_page_is_read_from_its_front_matter_and_body() {
        let page = page(DiagnosticCode::MissingLabel);
        assert_eq!(
            (page.group, page.severity, page.fix),
            (Some(Group::Acts), "error", "Add `Label: SOME_NAME`.")
        );
        assert!(page.body.starts_with("*Error.*"), "{}", page.body);
        assert_eq!(
            summary(DiagnosticCode::MissingLabel),
            "An act has no `Label`."
        );
    }
}
