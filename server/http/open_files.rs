//! File descriptors for the connection limit. Every open connection is one, beside the
//! corpus's files, the bundle's files being served, the folder watcher and the pipes of
//! espeak-ng and ffmpeg. A process that runs out of them cannot accept (the accept loop logs
//! and waits) and cannot open files, which is worse than the `503 too-many-connections` the
//! connection limit gives. So at start-up the soft limit (`RLIMIT_NOFILE`) is raised to the hard
//! one when `server: connections: total` needs it (to what it needs, no more) (systemd's default soft limit is 1,024, the
//! hard one 524,288), and when even the hard limit is too low the person starting Docent is
//! told which setting to change.

use rustix::process::{Resource, Rlimit, getrlimit, setrlimit};

/// Descriptors kept for everything but connections (corpus, bundle files, watcher, pipes).
pub const OWN_FILES: u64 = 64;

/// The open-files limit in force after [`make_room`], and what the person starting Docent
/// must hear about it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OpenFiles {
    /// The soft limit now in force; `None` when unlimited.
    pub limit: Option<u64>,
    /// Set when the limit stays below what `total` connections need.
    pub warning: Option<String>,
}

/// Raises this process's soft open-files limit towards its hard limit when `total`
/// connections and [`OWN_FILES`] need more; says so when they still do not fit.
pub fn make_room(total: usize) -> OpenFiles {
    let before = getrlimit(Resource::Nofile);
    let needed = total as u64 + OWN_FILES;
    let Some(raised) = raise_to(&before, needed) else {
        return checked(before.current, needed, total);
    };
    let new = Rlimit {
        current: Some(raised),
        maximum: before.maximum,
    };
    match setrlimit(Resource::Nofile, new) {
        Ok(()) => {
            // `raise_to` raises only a finite soft limit.
            let from = before.current.unwrap_or(raised);
            tracing::info!(from, to = raised, "raised the open-files limit");
            checked(Some(raised), needed, total)
        }
        Err(e) => {
            let mut kept = checked(before.current, needed, total);
            let cannot = format!("the open-files limit could not be raised ({e})");
            kept.warning = kept.warning.map(|w| format!("{cannot}: {w}"));
            kept
        }
    }
}

/// The soft limit to set for `needed` descriptors: `needed`, or the hard limit when it is
/// lower; `None` when the soft limit is enough already, or cannot go higher. Never more than
/// needed: espeak-ng and ffmpeg inherit it, and a program that uses `select()` breaks beyond
/// 1,024 (why systemd keeps the soft limit there).
fn raise_to(limit: &Rlimit, needed: u64) -> Option<u64> {
    let soft = limit.current?;
    if soft >= needed {
        return None;
    }
    let target = limit.maximum.map_or(needed, |hard| hard.min(needed));
    (target > soft).then_some(target)
}

/// `limit` with a warning when it is below `needed`.
fn checked(limit: Option<u64>, needed: u64, total: usize) -> OpenFiles {
    let warning = limit.filter(|&l| l < needed).map(|l| {
        format!(
            "this process may open only {l} files, but `server: connections: total` is \
             {total} and Docent needs about {OWN_FILES} more for its own files: connections \
             beyond about {} fail with \"too many open files\" instead of being answered \
             `503 too-many-connections`. Give the process at least {needed} \
             (`LimitNOFILE={needed}` in its systemd unit, see docs/DEVICE.md; `ulimit -n \
             {needed}` started by hand), or lower `total` in docent.yaml",
            l.saturating_sub(OWN_FILES)
        )
    });
    OpenFiles { limit, warning }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limit(current: Option<u64>, maximum: Option<u64>) -> Rlimit {
        Rlimit { current, maximum }
    }

    #[test]
    fn the_soft_limit_is_raised_to_what_is_needed_only_when_needed() {
        // systemd's defaults and the default total: raised to what is needed, no further.
        assert_eq!(
            raise_to(&limit(Some(1024), Some(524_288)), 1088),
            Some(1088)
        );
        assert_eq!(raise_to(&limit(Some(4096), Some(4096)), 1088), None);
        // Hard limit lower than needed: raised as far as it goes.
        assert_eq!(raise_to(&limit(Some(256), Some(512)), 1088), Some(512));
        assert_eq!(raise_to(&limit(Some(512), Some(512)), 1088), None);
        // Unlimited either way.
        assert_eq!(raise_to(&limit(None, None), 1088), None);
        assert_eq!(raise_to(&limit(Some(1024), None), 2112), Some(2112));
    }

    #[test]
    fn a_limit_below_the_total_names_the_setting_and_systemd() {
        let said = checked(Some(512), 1088, 1024);
        let warning = said.warning.expect("a warning");
        assert!(
            warning.contains("`server: connections: total` is 1024"),
            "{warning}"
        );
        assert!(warning.contains("LimitNOFILE=1088"), "{warning}");
        assert!(warning.contains("beyond about 448"), "{warning}");
        assert_eq!(checked(Some(1088), 1088, 1024).warning, None);
        assert_eq!(checked(None, 1088, 1024).warning, None);
    }

    #[test]
    fn the_default_total_fits_after_raising_where_the_hard_limit_allows() {
        let hard = getrlimit(Resource::Nofile).maximum;
        let room = make_room(1024);
        let fits = hard.is_none_or(|h| h >= 1024 + OWN_FILES);
        assert_eq!(
            room.warning.is_none(),
            fits,
            "{room:?} under a hard limit of {hard:?}"
        );
        if fits {
            assert!(room.limit.is_none_or(|l| l >= 1024 + OWN_FILES));
        }
    }
}
