//! The command line's subcommands that are more than a call: `docent corpus` (list, show,
//! purge, export, printed for people), on top of the corpus crate, and `docent translations`
//! (export, import), on top of the content crate's `translations`, and `docent fleet`, the
//! fleet view alone, and `docent explain`, one problem's entry from the reference; and
//! `docent check`, the problems of a bundle.
//!
//! - `check`: `docent check`, and how problems are counted and drawn (`serve` shows them too);
//!   `corpus`: `docent corpus` and its arguments; `corpus_show`: one session in full;
//!   `corpus_export`: exports with a progress bar; `units`: counts, sizes and durations as
//!   people read them; `translations`: `docent translations`; `fleet`: `docent fleet`'s
//!   arguments and start; `explain`: `docent explain`; `start`: what `docent serve` prints
//!   beside the addresses (access, preview, a refused address).

pub mod check;
pub mod corpus;
mod corpus_export;
mod corpus_show;
pub mod explain;
pub mod fleet;
pub mod start;
pub mod translations;
mod units;
