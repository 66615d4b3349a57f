//! `docent explain [CODE]`: one problem's entry from the reference (docs/DIAGNOSTICS.md), like
//! `rustc --explain`, so the explanation is at hand where `docent check` printed the code. The
//! text is compiled in from the checker's own table (`docent_content::explain`). Without a
//! code, every code with its severity, by kind. Exit status 0, or 1 for a code Docent does
//! not have (with the nearest one when there is one).

use std::fmt::Write as _;
use std::process::ExitCode;

use docent_content::DiagnosticCode;
use docent_content::explain::{Group, explain_text, find_code, nearest_code, page};

/// What `docent explain` takes.
#[derive(clap::Args)]
pub struct ExplainArgs {
    /// The code `docent check` printed in brackets, such as `unknown-verb`; without it, every
    /// code.
    code: Option<String>,
}

/// Prints the entry of the code asked for, or the list of codes.
pub fn run(args: &ExplainArgs) -> ExitCode {
    let Some(text) = args.code.as_deref() else {
        print!("{}", every_code());
        return ExitCode::SUCCESS;
    };
    match find_code(text) {
        Some(code) => {
            print!("{}", explain_text(code));
            ExitCode::SUCCESS
        }
        None => {
            let near = nearest_code(text)
                .map_or_else(String::new, |code| format!(" Did you mean `{code}`?"));
            eprintln!(
                "docent: no problem is called `{text}`.{near} `docent explain` alone lists \
                 every code."
            );
            ExitCode::FAILURE
        }
    }
}

/// Every code with its severity, under the heading of its kind.
fn every_code() -> String {
    let mut out = String::new();
    for &group in Group::ALL {
        let pages: Vec<_> = DiagnosticCode::ALL
            .iter()
            .map(|&c| page(c))
            .filter(|p| p.group == Some(group))
            .collect();
        if pages.is_empty() {
            continue;
        }
        let _ = writeln!(out, "{}:", group.title().replace('`', ""));
        for p in pages {
            let _ = writeln!(out, "  {:<32} {}", p.code.as_str(), p.severity);
        }
        out.push('\n');
    }
    out.push_str(
        "Type `docent explain CODE` for one of them (docs/DIAGNOSTICS.md has them all).\n",
    );
    out
}
