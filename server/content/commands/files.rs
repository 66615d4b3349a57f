//! The files commands and pages name: each resolved through the bundle's gate once per load
//! (folders listed once), judged in words for the author, and media sniffed by content.

use std::path::{Path, PathBuf};

use crate::DiagnosticCode;
use crate::diagnostic::Diagnostic;
use crate::media::ShownBy;
use crate::model::Pos;
use crate::paths::{BundleArea, Listing, PathError, list_files, read_listing, resolve_listed};
use crate::suggest::did_you_mean;

use super::misplaced::move_hint;
use super::{CommandChecker, PathProblem};

impl CommandChecker<'_> {
    /// A `PROJECT` file the projector cannot show, judged by its content (see `media`).
    pub(super) fn media_format(&self, file: &str, pos: &Pos, out: &mut Vec<Diagnostic>) {
        let Ok(path) = self.resolve(BundleArea::Media, file) else {
            return; // Reported by `check_file`.
        };
        self.sniffs.check(
            &path,
            &format!("media/{file}"),
            ShownBy::Projector,
            pos,
            out,
        );
    }

    pub(super) fn check_file(
        &self,
        area: BundleArea,
        rel: &str,
        pos: &Pos,
        out: &mut Vec<Diagnostic>,
    ) {
        if let Some((err, message)) = self.path_problem(area, rel) {
            out.push(Diagnostic::error(path_error_code(&err), pos, message));
        }
    }

    /// Why `rel` is not a usable file under `area`, in words, or `None` when it is.
    pub fn path_problem(&self, area: BundleArea, rel: &str) -> Option<PathProblem> {
        let key = (area, rel.to_owned());
        if let Some(verdict) = self.verdicts.borrow().get(&key) {
            return verdict.clone();
        }
        let verdict = self.judge_path(area, rel);
        self.verdicts.borrow_mut().insert(key, verdict.clone());
        verdict
    }

    /// [`resolve_in_bundle`] for the checks: each folder is listed once and each path
    /// resolved once per load.
    pub fn resolve(&self, area: BundleArea, rel: &str) -> Result<PathBuf, PathError> {
        let key = (area, rel.to_owned());
        if let Some(found) = self.resolved.borrow().get(&key) {
            return found.clone();
        }
        let list = |dir: &Path| -> Listing {
            if let Some(listing) = self.listings.borrow().get(dir) {
                return listing.clone();
            }
            let listing = read_listing(dir);
            self.listings
                .borrow_mut()
                .insert(dir.to_owned(), listing.clone());
            listing
        };
        let found = resolve_listed(self.root, area, rel, &list);
        self.resolved.borrow_mut().insert(key, found.clone());
        found
    }

    fn judge_path(&self, area: BundleArea, rel: &str) -> Option<PathProblem> {
        let err = self.resolve(area, rel).err()?;
        let folder = area.dir_name();
        let message = match &err {
            PathError::Outside => format!(
                "`{rel}` leads outside the {folder} folder. Write the file's path relative to \
                 `{folder}/`, without `..`, a leading `/`, backslashes or a drive letter; links \
                 pointing outside the bundle are refused too."
            ),
            PathError::Miscased { actual } => format!(
                "The file is called `{actual}`, with different upper and lower case. Write it \
                 exactly like that: on the robot `{rel}` and `{actual}` are different names."
            ),
            PathError::NotAFile => {
                format!("`{folder}/{rel}` is a folder, not a file. Name a file inside it.")
            }
            PathError::NotFound => {
                let hint = match self.misplaced(area, rel) {
                    Some(found) => move_hint(area, rel, &found),
                    None => did_you_mean(rel, self.listing(area).iter().map(String::as_str)),
                };
                format!("There is no file `{folder}/{rel}`.{hint}")
            }
        };
        Some((err, message))
    }

    /// The file under `area` whose name is close to the missing `rel` (`index.htm` for
    /// `index.html`), as a path from the bundle root.
    pub(crate) fn similar_file(&self, area: BundleArea, rel: &str) -> Option<String> {
        let files = self.listing(area);
        let near = crate::suggest::closest(rel, files.iter().map(String::as_str))?;
        Some(format!("{}/{near}", area.dir_name()))
    }

    fn listing(&self, area: BundleArea) -> &[String] {
        let cell = match area {
            BundleArea::Pages => &self.pages,
            BundleArea::Media => &self.media,
        };
        cell.get_or_init(|| list_files(self.root, area))
    }
}

/// The diagnostic code for a path refused by the gate.
pub(crate) fn path_error_code(err: &PathError) -> DiagnosticCode {
    match err {
        PathError::Outside => DiagnosticCode::PathOutsideBundle,
        PathError::Miscased { .. } => DiagnosticCode::MiscasedFile,
        PathError::NotFound | PathError::NotAFile => DiagnosticCode::MissingFile,
    }
}
