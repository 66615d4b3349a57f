//! The tests of `docent-content`, one binary with no async runtime and no server: bundles
//! written into temporary folders (or the repository's own `dialogs/` and `tests/fixtures/`)
//! loaded with `load_bundle`, and every problem checked at its file, line and column, in the
//! words `docent check` prints. `cargo test -p docent-content` runs them alone.

#[path = "../common/check.rs"]
mod check;
#[path = "../common/languages.rs"]
mod languages;
#[path = "../common/mac_copy.rs"]
mod mac_copy;

/// The helpers shared with the root crate's tests, under the name those use.
mod common {
    pub(crate) use super::{check, languages, mac_copy};

    /// The repository's root (this crate is `server/content/`).
    pub fn repo() -> std::path::PathBuf {
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
    }
}

mod acts_yaml;
mod attract;
mod bundle;
mod commands;
mod copied_folders;
mod diagnostics_reference;
mod getting_started;
mod getting_started_files;
mod language_mistakes;
mod language_settings;
mod load;
mod media;
mod not_plain_text;
mod operator;
mod operator_settings;
mod page_behaviour;
mod pages;
mod paths;
mod right_way;
mod shell_strings;
mod texts;
