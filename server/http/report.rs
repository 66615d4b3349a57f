//! The content report: the page at `/report` (an askama template whose script,
//! `static/report/main.js`, signs in with the operator console's sign-in module and fills the
//! page in) and its data at `GET /api/report`, which needs the operator's or dialog manager's
//! credential (`Authorization: Bearer`, as `/api/operator`). The report tells the same truth
//! as `docent check` on the files as they are on disk now (`cli::check::checked`, the same
//! check): while a save is refused, its problems are listed and the report says that the
//! running bundle is the last good one, and since when.

use std::time::{SystemTime, UNIX_EPOCH};

use askama::Template;
use axum::Json;
use axum::extract::State;
use axum::response::{IntoResponse, Response};

use serde::Serialize;

use crate::cli::check::checked;
use crate::content::report::{ContentReport, content_report};
use crate::http::AppError;
use crate::http::auth::Authorized;
use crate::http::shells::html;
use crate::state::AppState;

/// `pages/report/report.html`: the report's shell.
#[derive(Template)]
#[template(path = "report/report.html")]
pub struct ReportPage<'a> {
    /// Where the page fetches the report, e.g. `/api/report`.
    pub api_path: &'a str,
    /// False on an `--open` development server: the page fetches without asking.
    pub needs_credential: bool,
}

/// `GET /report`: the shell. Open to anyone: it holds no content and does nothing until its
/// reader signs in.
pub async fn report_page(State(state): State<AppState>) -> Response {
    let page = ReportPage {
        api_path: "/api/report",
        needs_credential: !state.access.is_open(),
    };
    html(page.render())
}

/// What `GET /api/report` answers: the content report, and whether the files on disk were
/// refused.
#[derive(Serialize)]
pub struct ReportNow {
    /// Acts, pages and media of the files on disk, or of the running bundle while they are
    /// refused; `problems` are always those of the files on disk, as `docent check` lists them.
    #[serde(flatten)]
    pub report: ContentReport,
    /// Set while the files on disk have errors: the running bundle is the last good one.
    pub refused: Option<Refused>,
}

/// The files on disk have errors; the last good bundle keeps running.
#[derive(Serialize)]
pub struct Refused {
    /// How many errors the files on disk have.
    pub errors: usize,
    /// When the running bundle went live, in milliseconds since 1970 (the page writes it in
    /// its reader's time).
    pub live_since_ms: u64,
}

/// `GET /api/report` (bearer): the report of the files on disk now. Built off the async
/// runtime, since it reads the whole bundle.
pub async fn get_report(_: Authorized, State(state): State<AppState>) -> Response {
    let live = state.dispatcher.bundle();
    let live_since = state.reload.live_since();
    match tokio::task::spawn_blocking(move || report_now(&live, live_since)).await {
        Ok(report) => Json(report).into_response(),
        Err(e) => AppError::internal(e).into_response(),
    }
}

/// The report of the files in `live`'s folder; `live` (running since `live_since`) stands in
/// for acts, pages and media when they do not load.
fn report_now(live: &crate::content::Bundle, live_since: SystemTime) -> ReportNow {
    let disk = checked(&live.root);
    let errors = disk.diagnostics.iter().filter(|d| d.is_error()).count();
    let mut report = match &disk.bundle {
        Some(bundle) => content_report(bundle),
        None => content_report(live),
    };
    report.problems = disk.diagnostics;
    let refused = (errors > 0).then(|| Refused {
        errors,
        live_since_ms: live_since
            .duration_since(UNIX_EPOCH)
            .map_or(0, |d| u64::try_from(d.as_millis()).unwrap_or(u64::MAX)),
    });
    ReportNow { report, refused }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_report_page_carries_its_contract_and_no_content() {
        let page = ReportPage {
            api_path: "/api/report",
            needs_credential: true,
        }
        .render()
        .expect("renders");
        assert!(page.starts_with("<!doctype html>"), "{page}");
        assert!(page.contains(r#"data-api="/api/report""#), "{page}");
        assert!(page.contains(r#"data-credential="required""#), "{page}");
        assert!(page.contains(r#"src="/static/report/main.js""#), "{page}");
        assert!(page.contains(r#"href="/static/report.css""#), "{page}");
        assert!(page.contains(r#"<dialog id="signin""#), "{page}");
        assert!(page.contains(r#"method="dialog""#), "{page}");
        for id in ["problems", "acts", "pages", "media", "print", "filter"] {
            assert!(page.contains(&format!(r#"id="{id}""#)), "no #{id}");
        }
    }

    #[test]
    fn every_report_script_is_served() {
        for name in ["report/main.js", "report/render.js", "report.css"] {
            assert!(crate::http::static_files::lookup(name).is_some(), "{name}");
        }
        let (_, main) = crate::http::static_files::lookup("report/main.js").expect("main");
        for line in main.lines().filter(|l| l.starts_with("import ")) {
            let module = line.split('"').nth(1).expect("a quoted module");
            let name = module.trim_start_matches("./").replace("../", "");
            let name = if module.starts_with("../") {
                name
            } else {
                format!("report/{name}")
            };
            assert!(
                crate::http::static_files::lookup(&name).is_some(),
                "{module} is imported but not served"
            );
        }
    }

    /// Regression (issue 28): while a save was refused, `/report` said "0 problems" although
    /// `docent check` on the same files failed.
    #[test]
    fn a_refused_save_is_reported_with_the_files_problems_and_the_running_bundles_time() {
        let dir = tempfile::tempdir().expect("a folder");
        let acts = dir.path().join("acts.yaml");
        std::fs::write(&acts, "- Label: GREET\n  Text: [Hello]\n").expect("written");
        let live = crate::content::load_bundle(dir.path())
            .bundle
            .expect("a good bundle");
        let since = UNIX_EPOCH + std::time::Duration::from_secs(1_800_000_000);

        let good = report_now(&live, since);
        assert!(good.refused.is_none());
        assert!(good.report.problems.iter().all(|d| !d.is_error()));

        std::fs::write(
            &acts,
            "- Label: GREET\n  Text: [Hello]\n  Cmds: [FLY_AWAY now]\n",
        )
        .expect("written");
        let refused = report_now(&live, since);
        let told = refused.refused.as_ref().expect("refused");
        assert_eq!(told.errors, 1);
        assert_eq!(told.live_since_ms, 1_800_000_000_000);
        assert_eq!(refused.report.problems, checked(dir.path()).diagnostics);
        assert!(
            refused
                .report
                .problems
                .iter()
                .any(|d| d.code == "unknown-verb")
        );
        // The running bundle's acts stay listed: it is what visitors meet.
        assert_eq!(refused.report.acts.len(), 1);
    }
}
