//! Reading a bundle's files on every core: each acts file (parsed, texts checked, commands
//! checked) and the pages are jobs taken in turn by a few worker threads. Results come back in
//! job order, so what is reported never depends on which thread ran what.
//!
//! Every thread reading YAML has a large stack: nesting is recursive to read, and a file nested
//! as deep as the parser's budget allows must be refused with a message, not crash the load on
//! a small thread stack (tokio's blocking threads have 2 MiB). These threads are made once and
//! kept (`readers`): a server reloading its bundle all day would otherwise start new threads
//! for every save, and each new thread takes over whichever of the allocator's arenas a thread
//! that ended left free, mixing the long-lived bundle with the short-lived buffers of recording
//! uploads there; the freed memory then stays in the process (bench/README.md, "Soak").

use std::collections::BTreeMap;
use std::io::Read;
use std::num::NonZeroUsize;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, OnceLock};

use rayon::iter::{IntoParallelIterator, ParallelIterator};

use crate::DiagnosticCode;
use crate::acts_file::{WrittenAct, read_acts_file, yaml::MAX_FILE_BYTES};
use crate::commands::CommandChecker;
use crate::config::SiteConfig;
use crate::contexts::check_declared;
use crate::diagnostic::Diagnostic;
use crate::language::Language;
use crate::load::ActsReplacements;
use crate::media::MediaFindings;
use crate::media::convert::Conversion;
use crate::model::{CommandSpec, Located, Pos, Variant};
use crate::pages::{PageLabels, check_pages};

/// Stack of each thread reading YAML: room for nesting up to the parsers' depth limit.
const READING_STACK_BYTES: usize = 32 << 20;

/// The threads that read bundles, one per core, started at the first load and kept.
/// `None` when no thread could be started (a process limit).
fn readers() -> Option<&'static rayon::ThreadPool> {
    static READERS: OnceLock<Option<rayon::ThreadPool>> = OnceLock::new();
    READERS
        .get_or_init(|| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(cores())
                .stack_size(READING_STACK_BYTES)
                .thread_name(|i| format!("bundle reader {i}"))
                .build()
                .inspect_err(|error| {
                    tracing::warn!(%error, "no thread to read bundles on: reading on the caller's")
                })
                .ok()
        })
        .as_ref()
}

fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, NonZeroUsize::get)
}

/// Runs `work` on a thread with room for deep YAML, or here if no thread can be started.
pub(super) fn on_reading_stack<T: Send>(work: impl FnOnce() -> T + Send) -> T {
    match readers() {
        Some(readers) => readers.install(work),
        None => work(),
    }
}

/// One acts file, read and checked.
pub(super) struct CheckedFile {
    /// Its labelled acts, in written order, commands checked.
    pub acts: Vec<CheckedAct>,
    /// Labels seen in parts skipped because of YAML errors.
    pub unread_labels: Vec<String>,
    /// Nothing of the file could be read: any label may be in it.
    pub unreadable: bool,
    /// How many of its acts have a text key with each language after the `@` (`Text@de:`).
    pub tagged: BTreeMap<Language, usize>,
}

/// An act with a label, its commands parsed and checked.
pub(super) struct CheckedAct {
    pub label: Located<String>,
    pub variants: Vec<Variant>,
    /// The usable commands, in written order.
    pub commands: Vec<Located<CommandSpec>>,
    pub group: Option<String>,
    pub key: Option<Located<char>>,
    pub keywords: Vec<String>,
}

/// Everything read from the bundle's files.
pub(super) struct Gathered {
    /// The acts files that could be opened, in the order of the names given.
    pub files: Vec<CheckedFile>,
    /// The act labels the pages use.
    pub pages: PageLabels,
    /// The media conversions the checks planned, each file once, in job order.
    pub conversions: Vec<Conversion>,
}

/// One unit of work for a worker.
#[derive(Clone, Copy)]
enum Job<'n> {
    Pages,
    ActsFile(&'n str),
}

/// What a job produced, with the problems it found.
enum Done {
    Pages(PageLabels),
    ActsFile(Option<CheckedFile>),
}

/// Reads the acts files `names` (top-level files of `root`) and checks every page, using
/// every core. Problems are appended to `out` in job order: the pages', then each file's.
pub(super) fn gather(
    root: &Path,
    names: &[String],
    config: &SiteConfig,
    replaced: &ActsReplacements,
    out: &mut Vec<Diagnostic>,
) -> Gathered {
    // The pages first: they are the largest single job, so the files fill in around them.
    let jobs: Vec<Job<'_>> = std::iter::once(Job::Pages)
        .chain(names.iter().map(|name| Job::ActsFile(name)))
        .collect();
    let workers = cores().min(jobs.len());
    let next = AtomicUsize::new(0);
    let work = || {
        // Each worker has its own checker: its caches are per thread, and a folder listed or
        // a file sniffed twice costs less than threads waiting on one another.
        let checker = CommandChecker::new(root, config);
        let mut done = Vec::new();
        loop {
            let i = next.fetch_add(1, Ordering::Relaxed);
            let Some(&job) = jobs.get(i) else {
                return (done, checker.media().take_findings());
            };
            let mut problems = Vec::new();
            let result = run(job, &checker, config, replaced, &mut problems);
            done.push((i, result, problems));
        }
    };
    // As many workers as cores, each taking the next job until none is left; on the reading
    // threads (a nested `install` runs where it is).
    let results: Vec<_> =
        on_reading_stack(|| (0..workers).into_par_iter().map(|_| work()).collect());
    let (done, findings): (Vec<_>, Vec<_>) = results.into_iter().unzip();
    let (conversions, mut told) = MediaFindings::merge(findings);
    out.append(&mut told);
    let mut results: Vec<_> = done.into_iter().flatten().collect();
    results.sort_by_key(|(i, ..)| *i);
    let mut gathered = Gathered {
        files: Vec::with_capacity(names.len()),
        pages: PageLabels::default(),
        conversions,
    };
    for (_, result, mut problems) in results {
        out.append(&mut problems);
        match result {
            Done::Pages(labels) => gathered.pages = labels,
            Done::ActsFile(file) => gathered.files.extend(file),
        }
    }
    gathered
}

fn run(
    job: Job<'_>,
    checker: &CommandChecker<'_>,
    config: &SiteConfig,
    replaced: &ActsReplacements,
    out: &mut Vec<Diagnostic>,
) -> Done {
    match job {
        Job::Pages => Done::Pages(check_pages(checker, out)),
        Job::ActsFile(name) => {
            let replacement = replaced.get(name).map(Vec::as_slice);
            Done::ActsFile(read_checked(name, replacement, checker, config, out))
        }
    }
}

/// One acts file read (or `replacement`, its new content), its texts and commands checked;
/// `None` when it cannot be opened.
fn read_checked(
    name: &str,
    replacement: Option<&[u8]>,
    checker: &CommandChecker<'_>,
    config: &SiteConfig,
    out: &mut Vec<Diagnostic>,
) -> Option<CheckedFile> {
    let file: Arc<str> = Arc::from(name);
    let path = checker.root().join(name);
    // A symlinked acts file must still live inside the bundle.
    if !path
        .canonicalize()
        .is_ok_and(|p| p.starts_with(checker.root()))
    {
        let message = "This acts file is a link to a place outside the bundle folder. Copy the \
                       file into the bundle instead.";
        out.push(Diagnostic::error(
            DiagnosticCode::PathOutsideBundle,
            &Pos::start_of(file),
            message,
        ));
        return None;
    }
    let bytes = match replacement {
        Some(bytes) => bytes.to_vec(),
        None => read_limited(&path, &file).map_err(|p| out.push(p)).ok()?,
    };
    let mut read = read_acts_file(&file, &bytes, &config.speech, &config.languages);
    out.append(&mut read.diagnostics);
    let mut tagged: BTreeMap<Language, usize> = BTreeMap::new();
    for language in read.acts.iter().flat_map(|a| &a.tagged) {
        *tagged.entry(language.clone()).or_default() += 1;
    }
    let acts = read
        .acts
        .into_iter()
        .filter_map(|written| {
            let WrittenAct {
                label,
                variants,
                commands,
                group,
                key,
                keywords,
                tagged: _,
            } = written;
            // An act without a usable label is reported by the reader and goes no further.
            let label = label?;
            let commands = commands
                .iter()
                .filter_map(|c| checker.check(c, out))
                .collect();
            check_declared(config, &variants, out);
            Some(CheckedAct {
                label,
                variants,
                commands,
                group,
                key,
                keywords,
            })
        })
        .collect();
    Some(CheckedFile {
        acts,
        unread_labels: read.unread_labels,
        unreadable: read.unreadable,
        tagged,
    })
}

/// The file's bytes, reading at most one byte past the size limit (the parser reports it).
pub(super) fn read_limited(path: &Path, file: &Arc<str>) -> Result<Vec<u8>, Diagnostic> {
    let limit = u64::try_from(MAX_FILE_BYTES)
        .unwrap_or(u64::MAX)
        .saturating_add(1);
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(limit).read_to_end(&mut bytes))
        .map(|_| bytes)
        .map_err(|e| {
            Diagnostic::error(
                DiagnosticCode::UnreadableFile,
                &Pos::start_of(file.clone()),
                format!("Docent could not read this file ({e}). Check that it is readable."),
            )
        })
}
