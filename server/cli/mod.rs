//! The command line's subcommands that are more than a call: `docent corpus` (list, show,
//! purge, export, printed for people), on top of the corpus crate, and `docent translations`
//! (export, import), on top of the content crate's `translations`.
//!
//! - `corpus.rs`: `docent corpus` and its arguments; `corpus_show.rs`: one session in full;
//!   `corpus_export.rs`: exports with a progress bar; `units.rs`: counts, sizes and durations
//!   as people read them; `translations.rs`: `docent translations`.

pub mod corpus;
mod corpus_export;
mod corpus_show;
pub mod translations;
mod units;
