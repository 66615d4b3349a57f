//! `docent-content`: content bundles: loading a bundle folder (acts files, `docent.yaml`, `pages/`, `media/`)
//! into a [`Bundle`], and reporting every problem found with its place.
//!
//! This is the only crate that reads YAML (with `serde-saphyr`) and the only place that
//! decides whether a path stays inside a bundle. It depends on nothing else in the workspace and
//! has no async runtime, no HTTP and no MQTT in its dependencies (its manifest says so, and
//! `tests/architecture_map.rs` holds it to that): loading does no network I/O.
//!
//! Map:
//! - `args`: a command's argument as a typed value, parsed once at load.
//! - `model`: the loaded data (acts, variants, commands, positions).
//! - `config`: validated site settings; `config_file`: parsing `docent.yaml`, with one
//!   declarative definition per section (`config_file/section.rs`) that the schema is
//!   generated from; `config_policy`: channel policies and source priorities;
//!   `config_corpus`: the `corpus:` settings (what starts a visitor session, its consent,
//!   what the kiosk records); `config_server`: the server's own limits (`server:`
//!   connections, timeouts, message size, outgoing queues).
//! - `language`: a language tag (`en`, `de`, `pt-br`) and a bundle's languages.
//! - `contexts`: the context names a bundle uses, and misspelt variant keys.
//! - `acts_file`: parsing one acts file, keeping every position.
//! - `commands`: parsing and checking `VERB argument` strings, and the files they name.
//! - `pages`: checking HTML pages (acts, links, pictures, encoding, hidden content).
//! - `media`: what a media file really is (by its first bytes) and whether Chromium shows it.
//! - `paths`: resolving a relative path inside the bundle (shared with the HTTP file routes).
//! - `encoding`: files not saved as UTF-8, explained; `plain_text`: a `.yaml` file that is
//!   no text at all (a Word document, RTF, PDF...), named.
//! - `duration`: `2s`, `500ms`, `1.5m`; `size`: amounts of storage, `4 GB`, `1.5 GiB`.
//! - `attract`, `schedule`: the kiosk's attract loop and opening hours, parsed once.
//! - `shell_strings`: the kiosk shell's own words in every language (built in, and the site's
//!   `kiosk: strings:`), and the warning for a declared language without them.
//! - `highlight`: the areas of a `HIGHLIGHT` argument.
//! - `operator_check`: what the operator console uses (act keys, map, visitor groups),
//!   checked against the whole bundle.
//! - `diagnostic`: a problem found, with its stable code, severity, place and message;
//!   `render`: diagnostics drawn for people (source line, caret, hint); `explain`: every
//!   code explained, from its doc comment and its page `diagnostics/CODE.md` (`docent
//!   explain`, `docs/DIAGNOSTICS.md`).
//! - `reaction`: the site's `reactions:` to robot events, and the grammar of their `if:`.
//! - `speech`: what the robot will really say: emoji, addresses, markup, placeholders and
//!   length in spoken texts.
//! - `suggest`: "did you mean" for labels, keys, verbs and file names.
//! - `unused`: acts that nothing triggers.
//! - `litter`: files copied folders and editors leave behind (`._name`, `.DS_Store`, `~`),
//!   ignored with one note, and acts files disabled by renaming.
//! - `translated_copy`: an acts file that translates another (`acts_de.yaml`, `de/acts.yaml`),
//!   told once instead of a duplicate label per act.
//! - `languages_order`: `languages:` written the wrong way round, told once at `docent.yaml`
//!   and read as meant.
//! - `voices`: the languages no installed espeak-ng voice speaks (start-up and `docent check`).
//! - `gather`: reading the acts files and pages on every core.
//! - `load`: putting it together: `load_bundle`.
//! - `fingerprint`: the bundle's content as one SHA-256, for a session's manifest.
//! - `schema`: JSON Schemas of the acts file and `docent.yaml` (walked from `config_file`'s
//!   section definitions), for editors.
//! - `consent`: what a session's visitors agreed to (`corpus: consent`, manifests, marks).
//! - `names`: robot event names, robot ids and the broker's address, as `docent.yaml` writes
//!   them and the runtime reads them.
//! - `spreadsheet`: CSV cells a spreadsheet would run as formulas, neutralised in every CSV
//!   Docent writes (translations, corpus exports).
//! - `translations`: the texts as a table for a translator (CSV or XLIFF) and a filled table
//!   written back into the acts files (`docent translations`, whose command line is the
//!   root crate's).
//! - `report`: the content report (acts, pages, media, problems) behind `/report`.

pub mod args;
pub mod attract;
pub mod config;
pub mod diagnostic;
pub mod explain;
pub mod language;
pub mod model;
pub mod names;
pub mod reaction;
pub mod report;
pub mod schedule;
pub mod schema;

mod acts_file;
mod commands;
mod config_corpus;
mod config_file;
mod config_policy;
mod config_server;
mod consent;
mod contexts;
mod duration;
mod encoding;
mod fingerprint;
mod gather;
mod highlight;
mod languages_order;
mod litter;
mod load;
mod media;
mod operator_check;
mod pages;
mod paths;
mod plain_text;
mod render;
pub mod shell_strings;
pub mod size;
mod speech;
pub mod spreadsheet;
mod suggest;
mod translated_copy;
pub mod translations;
mod unused;
mod voices;

pub use args::{Args, MediaKind};
pub use consent::Consent;
pub use diagnostic::{Diagnostic, DiagnosticCode, Severity};
pub use duration::parse_duration;
pub use fingerprint::{bundle_fingerprint, corpus_fingerprint};
pub use highlight::{Area, Shape};
pub use language::{Language, Languages};
pub use litter::is_litter;
pub use load::{ActsReplacements, LoadReport, load_bundle, load_bundle_replacing};
pub use media::convert::{Conversion, ConvertInto, ConvertWhy, OVERSIZED_SIDE, SCALED_SIDE};
pub use model::{
    Act, Bundle, CommandSpec, DEFAULT_VARIANT, Located, Pos, Translation, Variant, Verb,
};
pub use pages::act_delay;
pub use paths::{BundleArea, PathError, resolve_in_bundle};
pub use render::{Colour, render_diagnostics};
pub use speech::speaking_time;
pub use suggest::closest;
pub use voices::{EspeakChoice, espeak_speaks, no_voice_diagnostics, unspoken_languages};
