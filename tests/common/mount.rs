//! Small real file systems for fault tests: a tmpfs of a given size (a disk that fills up),
//! remounted read-only and back. Tests run as root, here and in CI; without it they fail
//! loudly, never skip, since the faults they inject cannot be faked by `chmod` as root.

use std::path::{Path, PathBuf};
use std::process::Command;

/// A tmpfs mounted on a folder, unmounted when dropped.
pub struct Tmpfs {
    at: PathBuf,
}

impl Tmpfs {
    /// Mounts a tmpfs of `kib` KiB on the folder `at` (made if missing).
    pub fn mount(at: &Path, kib: u64) -> Self {
        let uid = Command::new("id").arg("-u").output().expect("id runs");
        let uid = String::from_utf8_lossy(&uid.stdout).trim().to_owned();
        assert_eq!(
            uid, "0",
            "this test mounts a tmpfs and must run as root (it runs as uid {uid})"
        );
        std::fs::create_dir_all(at).expect("mount point");
        let size = format!("size={kib}k");
        run(Command::new("mount")
            .args(["-t", "tmpfs", "-o", &size, "tmpfs"])
            .arg(at));
        Tmpfs { at: at.to_owned() }
    }

    /// Makes it read-only (`writable` false) or writable again, as a remount does.
    pub fn remount(&self, writable: bool) {
        let flags = if writable { "remount,rw" } else { "remount,ro" };
        run(Command::new("mount").args(["-o", flags]).arg(&self.at));
    }

    /// Fills it with `filler` until it is full, then gives `room` bytes back (in whole 4 KiB
    /// pages, which is how a tmpfs counts).
    pub fn fill_leaving(&self, filler: &Path, room: u64) {
        use std::io::Write;
        let mut file = std::fs::File::create(filler).expect("filler");
        let page = vec![0u8; 4096];
        let full = loop {
            if let Err(e) = file.write_all(&page) {
                break e;
            }
        };
        assert_eq!(full.kind(), std::io::ErrorKind::StorageFull, "{full}");
        let len = file.metadata().expect("filler size").len();
        file.set_len(len.saturating_sub(room))
            .expect("room given back");
    }
}

impl Drop for Tmpfs {
    fn drop(&mut self) {
        // Lazily: a server that has not let go of its files yet must not keep it mounted.
        let _ = Command::new("umount").arg("-l").arg(&self.at).status();
    }
}

fn run(command: &mut Command) {
    let out = command.output().expect("mount runs");
    assert!(
        out.status.success(),
        "{command:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}
