//! A file a page or act names, missing from its folder but saved elsewhere in the bundle: the
//! home page beside `acts.yaml` instead of in `pages/`, a film in `pages/` instead of `media/`,
//! a page one folder too deep; and acts files saved in a folder instead of at the top. New
//! authors do this often; "there is no file" alone sends them looking for a typo in a name
//! that is right.

use std::path::Path;

use crate::DiagnosticCode;
use crate::diagnostic::Diagnostic;
use crate::model::Pos;
use crate::paths::BundleArea;

use super::CommandChecker;

impl CommandChecker<'_> {
    /// Where a file `rel`, missing under `area`, lies instead (a path from the bundle root),
    /// looking only near: the top of the bundle, the other area folder, and one folder down
    /// from the top or from `area`. `None` when it is not near.
    pub(crate) fn misplaced(&self, area: BundleArea, rel: &str) -> Option<String> {
        let folder = area.dir_name();
        let other = match area {
            BundleArea::Pages => BundleArea::Media,
            BundleArea::Media => BundleArea::Pages,
        };
        let name = rel.rsplit('/').next().unwrap_or(rel);
        let mut places = vec![rel.to_owned(), format!("{}/{rel}", other.dir_name())];
        if name != rel {
            places.push(name.to_owned());
            places.push(format!("{folder}/{name}"));
        }
        for dir in subfolders(self.root(), "") {
            if dir != folder {
                places.push(format!("{dir}/{rel}"));
            }
        }
        for dir in subfolders(self.root(), folder) {
            places.push(format!("{folder}/{dir}/{rel}"));
        }
        places.into_iter().find(|place| is_file(self.root(), place))
    }
}

/// Acts files (`.yaml`, `.yml`) saved one folder down from the top of the bundle (in
/// `pages/`, `media/`, or a folder of their own), as paths from the root, sorted: where the
/// acts went when none are at the top.
pub(crate) fn acts_files_elsewhere(root: &Path) -> Vec<String> {
    let mut found = Vec::new();
    for dir in subfolders(root, "") {
        let Ok(entries) = std::fs::read_dir(root.join(&dir)) else {
            continue;
        };
        for name in entries
            .flatten()
            .filter_map(|e| e.file_name().into_string().ok())
        {
            let lower = name.to_ascii_lowercase();
            let yaml = lower.ends_with(".yaml") || lower.ends_with(".yml");
            let rel = format!("{dir}/{name}");
            if yaml && !name.starts_with('.') && is_file(root, &rel) {
                found.push(rel);
            }
        }
    }
    found.sort();
    found
}

/// The folders one down from `root` that are bundles of their own (acts files at their top,
/// beside a `pages` folder or a `docent.yaml`), each with its first acts file: `root` is then
/// a folder of bundles (`dialogs/`), given by mistake for one of them.
pub(crate) fn bundles_inside(root: &Path) -> Vec<(String, String)> {
    let mut found: Vec<(String, String)> = Vec::new();
    for rel in acts_files_elsewhere(root) {
        let Some((dir, _)) = rel.split_once('/') else {
            continue;
        };
        let own = root.join(dir);
        let bundle = own.join("pages").is_dir() || own.join("docent.yaml").is_file();
        if bundle && !rel.ends_with("/docent.yaml") && found.last().is_none_or(|(d, _)| d != dir) {
            found.push((dir.to_owned(), rel));
        }
    }
    found
}

/// `not-a-bundle` for a folder of bundles: names them and the path to give instead.
pub(crate) fn folder_of_bundles(root: &Path, bundles: &[(String, String)]) -> Option<Diagnostic> {
    let ((first, acts), rest) = bundles.split_first()?;
    let folder = root.file_name().map_or_else(
        || root.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let names = match rest {
        [] => format!("`{first}` holds"),
        _ => {
            let all: Vec<String> = bundles.iter().map(|(d, _)| format!("`{d}`")).collect();
            format!("{} each hold", all.join(", "))
        }
    };
    let message = format!(
        "`{folder}` is a folder of bundles, not a bundle: {names} acts files and pages of \
         their own. Give the path of one of them instead, for example `{folder}/{first}`."
    );
    Some(Diagnostic::error(
        DiagnosticCode::NotABundle,
        &Pos::start_of(acts.as_str()),
        message,
    ))
}

/// `no-acts`: at the acts file saved in a folder, if there is one (told to move it up).
pub(crate) fn no_acts(root: &Path) -> Diagnostic {
    let elsewhere = acts_files_elsewhere(root);
    let Some(first) = elsewhere.first() else {
        let message = "No acts files found. Acts are written in .yaml files at the top of the \
                       bundle folder, next to pages/ and media/ (for example acts.yaml).";
        return Diagnostic::error(DiagnosticCode::NoActs, &Pos::start_of("acts.yaml"), message);
    };
    let (folder, name) = first.split_once('/').unwrap_or(("", first));
    let message = format!(
        "No acts files found at the top of the bundle: `{name}` is in the `{folder}` folder, \
         where Docent does not look for acts. Move it up into the bundle folder `{}`, next to \
         the `{folder}` folder.",
        root.file_name()
            .map_or_else(|| "".into(), |n| n.to_string_lossy())
    );
    Diagnostic::error(
        DiagnosticCode::NoActs,
        &Pos::start_of(first.as_str()),
        message,
    )
}

/// The names of the visible folders in `root/under` (not `.git` or a Mac's `.Trashes`).
fn subfolders(root: &Path, under: &str) -> Vec<String> {
    let Ok(entries) = std::fs::read_dir(root.join(under)) else {
        return Vec::new();
    };
    let mut names: Vec<String> = entries
        .flatten()
        .filter(|entry| entry.file_type().is_ok_and(|t| t.is_dir()))
        .filter_map(|entry| entry.file_name().into_string().ok())
        .filter(|name| !name.starts_with('.'))
        .collect();
    names.sort();
    names
}

/// Whether `rel` is a plain file in the bundle (a link is not followed: it may lead out).
fn is_file(root: &Path, rel: &str) -> bool {
    std::fs::symlink_metadata(root.join(rel)).is_ok_and(|m| m.is_file())
}

/// What to tell about `rel` (missing under `area`) found at `found` instead.
pub(crate) fn move_hint(area: BundleArea, rel: &str, found: &str) -> String {
    let folder = area.dir_name();
    let place = if found.contains('/') {
        format!("There is a file `{found}`")
    } else {
        format!("There is a file `{found}` at the top of the bundle, beside the acts files")
    };
    let to = if rel.contains('/') || found.starts_with(&format!("{folder}/")) {
        format!("move it to `{folder}/{rel}`")
    } else {
        format!("move it into the `{folder}` folder")
    };
    format!(" {place}: {to}.")
}
