//! ARCHITECTURE.md stays a true map of the code, at country level: it names every crate of the
//! workspace and every top-level module of the runtime crate, and every code path it writes in
//! backticks still exists; each crate root (the four `lib.rs` files and `server/cli/mod.rs`)
//! opens with a `//!` map naming each module it declares; the map stays short; the format
//! crates depend only downward and on no async runtime. A crate or module added without its place in the maps, or
//! a file renamed under the map's feet, fails here with the list of what to fix.
//!
//! Each check has a test that plants an omission and sees it reported, so none passes on
//! nothing.

use std::fs;
use std::path::{Path, PathBuf};

/// Extensions of the backticked paths in ARCHITECTURE.md that must name a real file.
const CODE_EXTENSIONS: [&str; 7] = ["rs", "js", "mjs", "html", "css", "sh", "py"];

/// The crate roots whose `//!` header must name every module they declare.
const CRATE_ROOTS: [&str; 5] = [
    "server/lib.rs",
    "server/content/lib.rs",
    "server/protocol/lib.rs",
    "server/corpus/lib.rs",
    "server/cli/mod.rs",
];

/// Folders never walked: build output, installed packages, git and editor state.
fn skipped_dir(name: &str) -> bool {
    name == "target" || name == "node_modules" || name.starts_with('.')
}

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(relative: &str) -> String {
    let path = repo().join(relative);
    fs::read_to_string(&path).unwrap_or_else(|e| panic!("reading {}: {e}", path.display()))
}

fn architecture() -> String {
    read("ARCHITECTURE.md")
}

/// Every file under `dir` (recursively), as paths relative to the repository with `/`.
fn files_under(dir: &Path) -> Vec<String> {
    let mut found = Vec::new();
    let mut pending: Vec<PathBuf> = vec![dir.to_path_buf()];
    while let Some(dir) = pending.pop() {
        let entries =
            fs::read_dir(&dir).unwrap_or_else(|e| panic!("listing {}: {e}", dir.display()));
        for entry in entries {
            let entry = entry.unwrap_or_else(|e| panic!("listing {}: {e}", dir.display()));
            let name = entry.file_name().to_string_lossy().into_owned();
            let kind = entry
                .file_type()
                .unwrap_or_else(|e| panic!("file type of {}: {e}", entry.path().display()));
            if kind.is_dir() {
                if !skipped_dir(&name) {
                    pending.push(entry.path());
                }
            } else if kind.is_file() && !name.starts_with('.') {
                let relative = entry
                    .path()
                    .strip_prefix(repo())
                    .unwrap_or_else(|e| panic!("{} is outside the repo: {e}", dir.display()))
                    .to_string_lossy()
                    .replace('\\', "/");
                found.push(relative);
            }
        }
    }
    found.sort();
    found
}

/// `map` without its fenced blocks (the diagram), whose triple backticks would otherwise pair
/// with the inline ones.
fn without_fences(map: &str) -> String {
    let mut inside = false;
    let mut kept = String::new();
    for line in map.lines() {
        if line.trim_start().starts_with("```") {
            inside = !inside;
        } else if !inside {
            kept.push_str(line);
            kept.push('\n');
        }
    }
    kept
}

/// The backticked spans of `text`, fences left out.
fn backticked(text: &str) -> Vec<String> {
    without_fences(text)
        .split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

/// The backticked spans of `map` that look like a path to a code file: no spaces, no
/// wildcard, a code extension (`ws/writer.rs`, `static/kiosk.js`, `lib.rs`).
fn written_paths(map: &str) -> Vec<String> {
    backticked(map)
        .into_iter()
        .filter(|span| {
            let plain = span
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.' | '/'));
            let extension = span.rsplit_once('.').map(|(_, ext)| ext);
            plain && extension.is_some_and(|ext| CODE_EXTENSIONS.contains(&ext))
        })
        .collect()
}

/// The paths written in `map` that no file of the repository ends with.
fn stale(map: &str) -> Vec<String> {
    let all = files_under(repo());
    let mut missing: Vec<String> = written_paths(map)
        .into_iter()
        .filter(|written| {
            let tail = format!("/{written}");
            !all.iter()
                .any(|file| file == written || file.ends_with(&tail))
        })
        .collect();
    missing.sort();
    missing.dedup();
    missing
}

#[test]
fn every_code_path_written_in_the_map_exists() {
    let map = architecture();
    let written = written_paths(&map);
    // The scan must see the map's paths at all, or this test would pass on nothing.
    for known in ["ws/session.rs", "static/kiosk.js", "corpus/writer.rs"] {
        assert!(
            written.iter().any(|w| w == known),
            "ARCHITECTURE.md's `{known}` was not read as a path; the scan is broken"
        );
    }
    let missing = stale(&map);
    assert!(
        missing.is_empty(),
        "ARCHITECTURE.md names {} file(s) that no longer exist: fix or remove them in \
         ARCHITECTURE.md:\n  {}",
        missing.len(),
        missing.join("\n  ")
    );
}

#[test]
fn a_path_gone_from_the_repo_is_reported() {
    let renamed = format!(
        "{}\n`ws/no_such_file.rs` and `no-such-script.js`\n",
        architecture()
    );
    let gone = stale(&renamed);
    for name in ["ws/no_such_file.rs", "no-such-script.js"] {
        assert!(
            gone.iter().any(|g| g == name),
            "`{name}` named in the map but absent from the repo was not reported: {gone:?}"
        );
    }
}

/// The most lines ARCHITECTURE.md may have: a map a newcomer reads in ten minutes. Detail
/// belongs in each crate's `lib.rs` map and in docs/.
const MAX_MAP_LINES: usize = 210;

/// The number of lines of `map` when it has more than [`MAX_MAP_LINES`].
fn too_long(map: &str) -> Option<usize> {
    let lines = map.lines().count();
    (lines > MAX_MAP_LINES).then_some(lines)
}

#[test]
fn the_map_stays_short_enough_to_read_in_ten_minutes() {
    let map = architecture();
    assert!(map.lines().count() > 50, "ARCHITECTURE.md was not read");
    if let Some(lines) = too_long(&map) {
        panic!(
            "ARCHITECTURE.md has {lines} lines, more than {MAX_MAP_LINES}: move detail into the \
             crates' `lib.rs` maps or docs/ instead"
        );
    }
}

#[test]
fn a_map_grown_too_long_is_reported() {
    let grown = format!(
        "{}{}",
        architecture(),
        "- one more clause\n".repeat(MAX_MAP_LINES)
    );
    assert!(
        too_long(&grown).is_some(),
        "a map of {} lines passed",
        grown.lines().count()
    );
}

/// The workspace's members as `Cargo.toml`'s `members` list writes them (`.`, `bench`,
/// `server/content`...), each with its package name from its own manifest.
fn workspace_members() -> Vec<(String, String)> {
    let manifest = read("Cargo.toml");
    let list = manifest
        .split_once("members = [")
        .and_then(|(_, rest)| rest.split_once(']'))
        .map(|(list, _)| list)
        .expect("Cargo.toml has a `members = [...]` list");
    let members: Vec<String> = list
        .split(',')
        .map(|m| m.trim().trim_matches('"').to_string())
        .filter(|m| !m.is_empty())
        .collect();
    members
        .into_iter()
        .map(|member| {
            let own = if member == "." {
                "Cargo.toml".to_string()
            } else {
                format!("{member}/Cargo.toml")
            };
            let name = package_name(&read(&own))
                .unwrap_or_else(|| panic!("{own} has no `name = \"...\"` under [package]"));
            (member, name)
        })
        .collect()
}

/// The `name` of a manifest's `[package]` section.
fn package_name(manifest: &str) -> Option<String> {
    let package = manifest.split_once("[package]")?.1;
    let section = package.split("\n[").next().unwrap_or(package);
    section.lines().find_map(|line| {
        let value = line.trim().strip_prefix("name")?.trim().strip_prefix('=')?;
        Some(value.trim().trim_matches('"').to_string())
    })
}

/// The members `map` does not name: each must appear by its package name in backticks and,
/// but for the root, by its folder.
fn unnamed_members(map: &str, members: &[(String, String)]) -> Vec<String> {
    let spans = backticked(map);
    members
        .iter()
        .filter(|(folder, name)| {
            let by_name = spans.iter().any(|s| s == name);
            let by_folder = folder == "." || map.contains(folder.as_str());
            !(by_name && by_folder)
        })
        .map(|(folder, name)| format!("{name} ({folder})"))
        .collect()
}

#[test]
fn every_workspace_member_is_named_in_the_map() {
    let members = workspace_members();
    // The scan must see the members at all.
    assert!(
        members.iter().any(|(_, name)| name == "docent-content") && members.len() >= 4,
        "Cargo.toml's members were not read: {members:?}"
    );
    let missing = unnamed_members(&architecture(), &members);
    assert!(
        missing.is_empty(),
        "ARCHITECTURE.md does not name workspace member(s) {missing:?}: give each its paragraph \
         under \"The crates\" (package name in backticks, and its folder)"
    );
}

#[test]
fn a_workspace_member_left_out_of_the_map_is_reported() {
    let map = architecture().replace("docent-corpus", "(left out)");
    let missing = unnamed_members(&map, &workspace_members());
    assert!(
        missing.iter().any(|m| m.starts_with("docent-corpus ")),
        "docent-corpus left out of the map was not reported: {missing:?}"
    );
}

/// The modules `source` declares (`mod x;`, `pub mod x;`, `pub(crate) mod x;`), in order.
/// Inline modules (`mod tests {`) and re-exported crates (`pub use docent_content as
/// content;`) are not declarations of a file.
fn declared_modules(source: &str) -> Vec<String> {
    source
        .lines()
        .filter_map(|line| {
            let line = line.trim();
            let rest = line
                .strip_prefix("pub(crate) ")
                .or_else(|| line.strip_prefix("pub "))
                .unwrap_or(line);
            let name = rest.strip_prefix("mod ")?.strip_suffix(';')?.trim();
            let plain =
                !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
            plain.then(|| name.to_string())
        })
        .collect()
}

/// The `//!` lines that open `source`, joined.
fn header(source: &str) -> String {
    source
        .lines()
        .map_while(|line| line.strip_prefix("//!"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The modules `source` declares that its `//!` header does not name as `x` in backticks
/// (a bare `x`, or an intra-doc link [`x`]).
fn unmapped_modules(source: &str) -> Vec<String> {
    let header = header(source);
    let named = backticked(&header);
    declared_modules(source)
        .into_iter()
        .filter(|module| module != "tests" && !named.iter().any(|n| n == module))
        .collect()
}

#[test]
fn every_crate_root_opens_with_a_map_of_its_modules() {
    let mut problems = Vec::new();
    for root in CRATE_ROOTS {
        let source = read(root);
        // The scan must see declarations at all.
        assert!(
            !declared_modules(&source).is_empty(),
            "{root}: no `mod` lines read; the scan is broken"
        );
        let missing = unmapped_modules(&source);
        if !missing.is_empty() {
            problems.push(format!("{root}: {}", missing.join(", ")));
        }
    }
    assert!(
        problems.is_empty(),
        "crate roots declare module(s) their `//!` map does not name (write each as `name` in \
         the header, saying in a line what it holds):\n  {}",
        problems.join("\n  ")
    );
}

#[test]
fn a_module_left_out_of_a_crate_roots_map_is_reported() {
    let planted = format!("{}\npub mod planted_module;\n", read("server/lib.rs"));
    let missing = unmapped_modules(&planted);
    assert_eq!(
        missing,
        ["planted_module"],
        "a module declared but absent from server/lib.rs's map was not reported alone"
    );
    // A name written in prose but not in backticks does not count as mapped.
    let prose = format!("//! planted_module, in words\n{planted}");
    assert_eq!(unmapped_modules(&prose), ["planted_module"]);
}

/// The top-level modules of the runtime crate (its `mod` lines in `server/lib.rs`) that `map`
/// does not name, as `x`, `x/` or `x.rs` in backticks.
fn unnamed_modules(map: &str, lib: &str) -> Vec<String> {
    let spans = backticked(map);
    declared_modules(lib)
        .into_iter()
        .filter(|module| {
            let forms = [module.clone(), format!("{module}/"), format!("{module}.rs")];
            !spans.iter().any(|s| forms.contains(s))
        })
        .collect()
}

#[test]
fn every_top_level_module_of_the_runtime_is_named_in_the_map() {
    let lib = read("server/lib.rs");
    assert!(
        declared_modules(&lib).iter().any(|m| m == "dispatch"),
        "server/lib.rs's modules were not read"
    );
    let missing = unnamed_modules(&architecture(), &lib);
    assert!(
        missing.is_empty(),
        "ARCHITECTURE.md does not name the runtime's module(s) {missing:?}: give each its line \
         under \"Inside the runtime crate\""
    );
}

#[test]
fn a_runtime_module_left_out_of_the_map_is_reported() {
    let lib = format!("{}\npub mod planted_module;\n", read("server/lib.rs"));
    assert_eq!(unnamed_modules(&architecture(), &lib), ["planted_module"]);
    let map = (architecture().replace("`dispatch/`", "dispatch")).replace("`dispatch`", "dispatch");
    let missing = unnamed_modules(&map, &read("server/lib.rs"));
    assert!(
        missing.iter().any(|m| m == "dispatch"),
        "`dispatch/` taken out of the map was not reported: {missing:?}"
    );
}
