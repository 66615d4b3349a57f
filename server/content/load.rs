//! Putting a bundle together: settings, the acts files and pages (read on every core by
//! `gather`), acts merged in file-name order, labels across files, and the home page. Every problem found is
//! collected; loading never stops at the first.

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

use crate::DiagnosticCode;
use crate::DiagnosticCode::{ConfigSyntax, FileEncoding, NotPlainText};
use crate::commands::{
    CommandChecker, acts_files_elsewhere, bundles_inside, folder_of_bundles, no_acts,
    path_error_code,
};
use crate::config::SiteConfig;
use crate::config_file::attract::check_screen_refs;
use crate::config_file::schedule::check_past_special_days;
use crate::config_file::{ConfigFile, parse_config};
use crate::contexts::{check_undeclared, contexts};
use crate::diagnostic::Diagnostic;
use crate::gather::{on_reading_stack, read_limited};
use crate::languages_order::gather_as_meant;
use crate::litter::Survey;
use crate::media::convert::Conversion;
use crate::model::{Bundle, Located, Pos};
use crate::operator_check::{check_map, visitor_groups};
use crate::paths::{BundleArea, PathError};
use crate::schedule::WallClock;
use crate::suggest::did_you_mean;
use crate::translated_copy::find_translated_copies;
use crate::unused::check_unused;

mod merge;

use merge::{Merged, check_page_labels, merge_acts};

/// The name of the settings file at the top of a bundle.
const CONFIG_FILE: &str = "docent.yaml";

/// The outcome of loading a bundle: the bundle if it has no errors, and every problem found.
#[derive(Debug)]
pub struct LoadReport {
    /// The loaded bundle; `Some` exactly when no diagnostic is an error.
    pub bundle: Option<Bundle>,
    /// Errors and warnings, sorted by file, line and column.
    pub diagnostics: Vec<Diagnostic>,
    /// The media conversions planned (also when the bundle has errors, so `docent check` can
    /// ask ffmpeg about them); the bundle holds the same.
    pub conversions: Vec<Conversion>,
}

/// Loads and checks the bundle in the folder `root`.
pub fn load_bundle(root: &Path) -> LoadReport {
    load_bundle_replacing(root, &ActsReplacements::new())
}

/// Acts files' contents to read instead of what is on disk, by file name (`acts.yaml`): how
/// `docent translations import` checks its result before writing anything.
pub type ActsReplacements = BTreeMap<String, Vec<u8>>;

/// Loads and checks the bundle in `root` as if the acts files named in `replaced` held those
/// bytes (each must exist on disk: only its content is replaced).
pub fn load_bundle_replacing(root: &Path, replaced: &ActsReplacements) -> LoadReport {
    on_reading_stack(|| load(root, replaced))
}

fn load(root: &Path, replaced: &ActsReplacements) -> LoadReport {
    let started = std::time::Instant::now();
    let mut diagnostics = Vec::new();
    let root = match root.canonicalize() {
        Ok(root) if root.is_dir() => root,
        _ => {
            let message = format!(
                "`{}` is not a folder Docent can open. Give the path of the bundle folder (the \
                 one holding the acts files, pages/ and media/).",
                root.display()
            );
            diagnostics.push(Diagnostic::error(
                DiagnosticCode::NotABundle,
                &Pos::start_of(root.display().to_string()),
                message,
            ));
            return LoadReport {
                bundle: None,
                diagnostics,
                conversions: Vec::new(),
            };
        }
    };
    // `docent serve dialogs` for `docent serve dialogs/museum-tour`: one error saying so,
    // rather than "move your acts file up" and a missing home page.
    let yaml_at_top = (std::fs::read_dir(&root).into_iter().flatten().flatten()).any(|e| {
        let name = e.file_name().to_string_lossy().to_ascii_lowercase();
        name.ends_with(".yaml") || name.ends_with(".yml")
    });
    let has_own = yaml_at_top || root.join("pages").is_dir();
    if !has_own && let Some(told) = folder_of_bundles(&root, &bundles_inside(&root)) {
        diagnostics.push(told);
        return LoadReport {
            bundle: None,
            diagnostics,
            conversions: Vec::new(),
        };
    }
    let settings = read_settings(&root, &mut diagnostics);
    // A docent.yaml YAML could not read drops every setting (the idle act, the contexts):
    // warnings that follow from the defaults would only mislead.
    let unread = [ConfigSyntax, FileEncoding, NotPlainText];
    let settings_unread = diagnostics.iter().any(|d| unread.contains(&d.code));
    let names = acts_file_names(&root, &mut diagnostics);
    let mut leftovers = Survey::find(&root);
    let mut config = settings.config;
    let gathered = gather_as_meant(&root, &names, &mut config, replaced, &mut diagnostics);
    let checker = CommandChecker::new(&root, &config);
    let copies = find_translated_copies(&root, &gathered.files, &config, &mut diagnostics);
    let mut merged = merge_acts(gathered.files, &copies, &mut diagnostics);
    // Acts saved in a folder are unread, not absent: no page is blamed for naming them.
    merged.incomplete |= names.is_empty() && !acts_files_elsewhere(&root).is_empty();
    check_page_labels(gathered.pages, &config, &mut merged, &mut diagnostics);
    check_home(&checker, &config, settings.home.as_ref(), &mut diagnostics);
    check_idle_act(&merged, settings.idle_act.as_ref(), &mut diagnostics);
    {
        let labels: Vec<&str> = merged.index.keys().map(String::as_str).collect();
        let knows = |label: &str| merged.knows(label);
        check_screen_refs(
            &settings.screen_refs,
            &checker,
            knows,
            &labels,
            &mut diagnostics,
        );
    }
    check_reaction_acts(&merged, &settings.reaction_acts, &mut diagnostics);
    check_map(&checker, &config, settings.map.as_ref(), &mut diagnostics);
    // The clock is read once, here: the check itself takes today, so tests fix the date.
    let today = WallClock::now().date;
    check_past_special_days(&settings.special_dates, today, &mut diagnostics);
    leftovers.check_disabled(
        &root,
        &config,
        &|label| merged.knows(label),
        &mut diagnostics,
    );
    leftovers.report(&mut diagnostics);
    if !settings_unread {
        crate::shell_strings::check_shell_strings(&config, &mut diagnostics);
        check_undeclared(&config, &merged.acts, &mut diagnostics);
        let idle = settings.idle_act.as_ref().map(|a| a.value.as_str());
        let reacting = (settings.reaction_acts.iter())
            .chain(&settings.screen_refs.acts)
            .map(|a| a.value.as_str());
        let referenced = (merged.page_acts.iter().map(String::as_str))
            .chain(idle)
            .chain(reacting);
        check_unused(&merged.acts, referenced, &mut diagnostics);
    }
    let conversions = gathered.conversions;
    for conversion in &conversions {
        diagnostics.push(Diagnostic::note(
            DiagnosticCode::MediaConverted,
            &conversion.pos,
            conversion.describe(),
        ));
    }
    let contexts = contexts(&config, &merged.acts);
    config.operator.visitor_groups =
        visitor_groups(&contexts, &settings.visitor_groups, &mut diagnostics);
    diagnostics.sort_by(|a, b| (&a.file, a.line, a.column).cmp(&(&b.file, b.line, b.column)));
    let errors = diagnostics.iter().filter(|d| d.is_error()).count();
    tracing::debug!(
        acts = merged.acts.len(),
        files = names.len(),
        errors,
        elapsed_ms = u64::try_from(started.elapsed().as_millis()).unwrap_or(u64::MAX),
        "content bundle checked"
    );
    let bundle = (errors == 0).then(|| Bundle {
        page_acts: std::mem::take(&mut merged.page_acts),
        page_offers: std::mem::take(&mut merged.page_offers),
        page_languages: std::mem::take(&mut merged.page_languages),
        root: root.clone(),
        acts: merged.acts,
        index: merged.index,
        config,
        contexts,
        diagnostics: diagnostics.clone(),
        conversions: conversions.clone(),
        fingerprint: None,
    });
    LoadReport {
        bundle,
        diagnostics,
        conversions,
    }
}

fn read_settings(root: &Path, out: &mut Vec<Diagnostic>) -> ConfigFile {
    let path = root.join(CONFIG_FILE);
    if !path.exists() {
        return ConfigFile::default();
    }
    let file: Arc<str> = Arc::from(CONFIG_FILE);
    let mut settings = match read_limited(&path, &file) {
        Ok(bytes) => parse_config(&file, &bytes),
        Err(problem) => {
            out.push(problem);
            return ConfigFile::default();
        }
    };
    out.append(&mut settings.diagnostics);
    settings
}

/// Top-level `*.yaml`/`*.yml` files except `docent.yaml`, sorted by name. Hidden files
/// (editor back-ups such as `.acts.yaml`) are skipped.
fn acts_file_names(root: &Path, out: &mut Vec<Diagnostic>) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(root)
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|entry| entry.file_name().into_string().ok())
        .filter(|name| {
            let lower = name.to_ascii_lowercase();
            !name.starts_with('.')
                && name != CONFIG_FILE
                && (lower.ends_with(".yaml") || lower.ends_with(".yml"))
        })
        .filter(|name| root.join(name).is_file())
        .collect();
    names.sort();
    if names.is_empty() {
        out.push(no_acts(root));
    }
    names
}

/// The act `kiosk: idle_act:` names must exist.
fn check_idle_act(merged: &Merged, idle_act: Option<&Located<String>>, out: &mut Vec<Diagnostic>) {
    let Some(Located { value, pos }) = idle_act else {
        return;
    };
    if merged.knows(value) {
        return;
    }
    let hint = did_you_mean(value, merged.index.keys().map(String::as_str));
    let message = format!(
        "The kiosk triggers the act `{value}` when it goes idle, but no act has that label.\
         {hint} Fix `idle_act` in docent.yaml or add the act."
    );
    out.push(Diagnostic::error(DiagnosticCode::UnknownAct, pos, message));
}

/// The acts `reactions:` trigger must exist.
fn check_reaction_acts(merged: &Merged, acts: &[Located<String>], out: &mut Vec<Diagnostic>) {
    for Located { value, pos } in acts.iter().filter(|a| !merged.knows(&a.value)) {
        let hint = did_you_mean(value, merged.index.keys().map(String::as_str));
        let message = format!(
            "This reaction triggers the act `{value}` when the robot notices its event, but \
             no act has that label.{hint} Fix `act:` in the reaction or add the act."
        );
        out.push(Diagnostic::error(DiagnosticCode::UnknownAct, pos, message));
    }
}

/// A home page set in docent.yaml must exist; the default one only earns a warning.
fn check_home(
    checker: &CommandChecker<'_>,
    config: &SiteConfig,
    explicit: Option<&Located<String>>,
    out: &mut Vec<Diagnostic>,
) {
    let Some((err, problem)) = checker.path_problem(BundleArea::Pages, &config.home) else {
        return;
    };
    let misplaced = match err {
        PathError::NotFound => checker.misplaced(BundleArea::Pages, &config.home),
        _ => None,
    };
    // The default home page saved elsewhere, or under another name, is told at the file the
    // author made.
    let made = match &err {
        PathError::NotFound => {
            (misplaced.clone()).or_else(|| checker.similar_file(BundleArea::Pages, &config.home))
        }
        PathError::Miscased { actual } => Some(format!("pages/{actual}")),
        _ => None,
    };
    let pos = match (explicit, made) {
        (Some(home), _) => home.pos.clone(),
        (None, Some(found)) => Pos::start_of(found),
        (None, None) => Pos::start_of(format!("pages/{}", config.home)),
    };
    let code = match err {
        PathError::NotFound | PathError::NotAFile => DiagnosticCode::NoHomePage,
        other => path_error_code(&other),
    };
    let message = match misplaced {
        Some(_) => format!("{problem} Until then the touchscreen has no page to start on."),
        None => format!(
            "{problem} The kiosk starts on this page: add it, or choose another page with \
             `home:` in docent.yaml."
        ),
    };
    out.push(match explicit {
        Some(_) => Diagnostic::error(code, &pos, message),
        None => Diagnostic::warning(code, &pos, message),
    });
}
