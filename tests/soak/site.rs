//! The soak's bundle: acts a kiosk page offers (`data-act`), spoken by the `log` adapter (no
//! sound device; a `SAY` takes as long as its words would), sessions that a tap starts and 5 s
//! without one ends, recording on (the default consent). Saving it anew changes every act's
//! text, as an author would between two visits.

use std::fs;
use std::path::PathBuf;

/// How many acts the page offers.
pub const ACTS: usize = 20;

/// A bundle in a temporary folder, saved anew by [`Site::save`].
pub struct Site {
    dir: tempfile::TempDir,
    saves: usize,
}

impl Site {
    /// Writes version 1 of the bundle.
    pub fn new() -> Site {
        let dir = tempfile::tempdir().expect("a bundle folder");
        let bundle = dir.path().join("bundle");
        fs::create_dir_all(bundle.join("pages")).expect("pages folder");
        fs::write(
            bundle.join("docent.yaml"),
            "speech: { adapter: log, rate: 600 }\ncorpus: { session_idle: 5s }\n",
        )
        .expect("docent.yaml");
        let buttons: String = (0..ACTS)
            .map(|n| format!("<button data-act=\"{}\">Exhibit {n}</button>\n", label(n)))
            .collect();
        fs::write(
            bundle.join("pages/index.html"),
            format!("<html><body>\n{buttons}</body></html>\n"),
        )
        .expect("index.html");
        fs::write(bundle.join("acts.yaml"), acts(1)).expect("acts.yaml");
        Site { dir, saves: 1 }
    }

    /// The bundle folder.
    pub fn bundle(&self) -> PathBuf {
        self.dir.path().join("bundle")
    }

    /// Saves the next version of the acts file in one step (written beside, then renamed), so
    /// that a reload never reads half a file.
    pub fn save(&mut self) {
        self.saves += 1;
        let staged = self.dir.path().join("acts.yaml.new");
        fs::write(&staged, acts(self.saves)).expect("stage the acts");
        fs::rename(&staged, self.bundle().join("acts.yaml")).expect("save the acts");
    }

    /// How many times the acts were saved after the first version.
    pub fn reloads(&self) -> usize {
        self.saves - 1
    }
}

/// The label of act `n`.
pub fn label(n: usize) -> String {
    format!("EXHIBIT_{}", n % ACTS)
}

fn acts(version: usize) -> String {
    (0..ACTS)
        .map(|n| {
            let label = label(n);
            format!(
                "- Label: {label}\n  Text:\n    - \"Exhibit {n}, as told in version {version}.\"\n"
            )
        })
        .collect()
}
