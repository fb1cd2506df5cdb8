//! One process at a time in a run directory. Two processes writing one directory (a resume started while the run, or
//! a forgotten copy of it, still goes on) interleave their rows into one `timeseries.csv`, leave holes of zero bytes in
//! it and drop rows of `segments.csv`, and both end with success. A run holds an advisory lock (flock(2)) on
//! `<out>/.gc2d-rs.lock` while it works; the system releases it when the process ends, however it ends, so a killed run
//! leaves no stale lock behind.

use std::fs::File;
use std::path::Path;

/// The lock file's name in a run directory.
pub const LOCK_FILE: &str = ".gc2d-rs.lock";

/// The lock on a run directory, held until it is dropped (or the process ends).
#[derive(Debug)]
pub struct RunLock {
    _file: File,
}

/// Locks the run directory `out` for this process, or says which process holds it. Where the system has no flock
/// (not Unix), or the file system refuses it, the run goes on unlocked, as before.
pub fn lock_run_directory(out: &Path) -> Result<RunLock, String> {
    let path = out.join(LOCK_FILE);
    let file = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .create(true)
        .truncate(false)
        .open(&path)
        .map_err(|e| format!("cannot open the lock file {}: {e}", path.display()))?;
    #[cfg(unix)]
    {
        use std::io::{Read, Seek, Write};
        use std::os::fd::AsRawFd;
        // SAFETY: flock(2) on a descriptor this function owns; it has no memory effects.
        let locked = unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) } == 0;
        if !locked {
            let error = std::io::Error::last_os_error();
            if error.raw_os_error() != Some(libc::EWOULDBLOCK) {
                return Ok(RunLock { _file: file });
            }
            let mut holder = String::new();
            let _ = (&file).read_to_string(&mut holder);
            let holder = match holder.trim() {
                "" => "another gc2d-rs process".to_owned(),
                pid => format!("another gc2d-rs process (pid {pid})"),
            };
            return Err(format!(
                "{} is in use by {holder}: two runs writing one directory would mix their outputs. Wait for it to \
                 end or stop it, or choose another --out",
                out.display()
            ));
        }
        let mut file = file;
        let _ = file.set_len(0).and_then(|()| file.rewind()).and_then(|()| write!(file, "{}", std::process::id()));
        Ok(RunLock { _file: file })
    }
    #[cfg(not(unix))]
    Ok(RunLock { _file: file })
}

/// Why a run directory `dir` without a checkpoint has none, where the reason is a run still writing it (it writes
/// `final.ckpt` when it ends, periodic checkpoints only with `--checkpoint-every`); `None` where no run holds it, so
/// that the caller's own message (not a run directory?) stands.
pub fn still_running_without_checkpoint(dir: &Path) -> Option<String> {
    is_locked(dir).then(|| {
        format!(
            "a gc2d-rs run is still writing {} and has written no checkpoint yet (final.ckpt comes when it ends; \
             periodic ones only with --checkpoint-every)",
            dir.display()
        )
    })
}

/// True when another process holds the lock of the run directory `out` now; false where it is free, where it has no
/// lock file, and where the system has no flock. Takes the lock only for the moment of the test.
pub fn is_locked(out: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::fd::AsRawFd;
        let Ok(file) = File::open(out.join(LOCK_FILE)) else { return false };
        // SAFETY: flock(2) on a descriptor this function owns; it has no memory effects. The lock, if taken, ends
        // when `file` is closed.
        let taken = unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) } == 0;
        !taken && std::io::Error::last_os_error().raw_os_error() == Some(libc::EWOULDBLOCK)
    }
    #[cfg(not(unix))]
    {
        let _ = out;
        false
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    #[test]
    fn a_locked_directory_is_refused_until_its_lock_is_dropped() {
        let out = tempfile::tempdir().unwrap();
        let held = lock_run_directory(out.path()).unwrap();
        let refused = lock_run_directory(out.path()).unwrap_err();
        assert!(refused.contains("is in use by another gc2d-rs process (pid "), "{refused}");
        assert!(refused.contains(&std::process::id().to_string()), "{refused}");
        assert!(is_locked(out.path()));
        drop(held);
        assert!(!is_locked(out.path()), "free once dropped");
        assert!(lock_run_directory(out.path()).is_ok());
        assert!(!is_locked(&out.path().join("no such run")), "a directory without a lock file is free");
    }
}
