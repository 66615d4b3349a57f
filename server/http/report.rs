//! The content report: the page at `/report` (an askama template whose script,
//! `static/report/main.js`, signs in with the operator console's sign-in module and fills the
//! page in) and its data at `GET /api/report`, which needs the operator's or dialog manager's
//! credential (`Authorization: Bearer`, as `/api/operator`).

use askama::Template;
use axum::Json;
use axum::extract::State;
use axum::response::{IntoResponse, Response};

use crate::content::report::content_report;
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

/// `GET /api/report` (bearer): the live bundle's content report. Built off the async runtime,
/// since it reads the bundle's pages.
pub async fn get_report(_: Authorized, State(state): State<AppState>) -> Response {
    let bundle = state.dispatcher.bundle();
    match tokio::task::spawn_blocking(move || content_report(&bundle)).await {
        Ok(report) => Json(report).into_response(),
        Err(e) => AppError::internal(e).into_response(),
    }
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
}
