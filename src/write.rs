//! The only code that writes output files. Every file is written to a temporary file in its
//! target directory, flushed to disk, and renamed over the target, so a reader sees either
//! the old file or the complete new one — never a partial file.

use std::fs::{self, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Why [`write_all_atomic`] failed.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    /// The same path was given twice.
    #[error("{} is listed twice among the files to write; no output file was changed", .0.display())]
    DuplicatePath(PathBuf),
    /// Writing a temporary file failed; no output file was changed.
    #[error("{source}; no output file was changed")]
    Prepare { path: PathBuf, source: io::Error },
    /// Renaming a finished temporary file over its target failed. The files in `committed`
    /// had already been replaced; the others are unchanged.
    #[error("{source}; {} of {total} output files had already been replaced", .committed.len())]
    Commit {
        path: PathBuf,
        source: io::Error,
        committed: Vec<PathBuf>,
        total: usize,
    },
}

/// Atomically replaces (or creates) `path` with `bytes`. On error nothing is left behind
/// and the error message names the path.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let tmp = prepare(path, bytes)?;
    commit(&tmp, path)?;
    sync_dir(parent(path));
    Ok(())
}

/// Atomically replaces (or creates) several files, all or nothing per directory: first every
/// file is written and flushed, then each directory's set is put in place in one step.
///
/// For a directory that holds only regular files and links (a preset's output folder), a
/// complete copy of it is staged next to it — the unchanged files hard-linked, the new ones
/// written — and exchanged with it in one `renameat2(RENAME_EXCHANGE)` (Linux): a reader,
/// even one that looks while the process is killed, sees the whole old set or the whole new
/// one. Elsewhere (a directory holding subdirectories, a file system or system without the
/// exchange) the files are renamed one by one in the order given (the pipeline puts every
/// sidecar last, so readers find a set interrupted between renames through the sidecar's
/// digests). Concurrent writers of one directory are serialized by a lock on it.
///
/// A failure before the first directory is put in place changes nothing; the staged copies
/// are always removed. SIGINT/SIGTERM/SIGHUP arriving meanwhile are held ([`crate::signals`])
/// until the directory being exchanged is complete, then end the process. Leftovers of killed
/// writers are removed first ([`sweep_leftovers`]).
pub fn write_all_atomic<P: AsRef<Path>, B: AsRef<[u8]>>(
    files: &[(P, B)],
) -> Result<(), WriteError> {
    let files: Vec<(&Path, &[u8])> = files
        .iter()
        .map(|(p, b)| (p.as_ref(), b.as_ref()))
        .collect();
    for (i, (path, _)) in files.iter().enumerate() {
        if files[..i].iter().any(|(other, _)| other == path) {
            return Err(WriteError::DuplicatePath(path.to_path_buf()));
        }
    }
    // the directories, in the order of their first file
    let mut dirs: Vec<&Path> = Vec::new();
    for &(p, _) in &files {
        if !dirs.contains(&parent(p)) {
            dirs.push(parent(p));
        }
    }
    for d in &dirs {
        sweep_leftovers(d);
        if let Some(up) = staging_parent(d) {
            sweep_leftovers(up);
        }
    }

    // A rename cannot replace a directory (or, portably, anything but a file): find that
    // before the first rename, so such a target fails the whole set with nothing replaced.
    for &(path, _) in &files {
        if let Ok(m) = fs::symlink_metadata(path) {
            if !m.file_type().is_file() {
                return Err(WriteError::Prepare {
                    path: path.to_path_buf(),
                    source: io::Error::new(
                        io::ErrorKind::AlreadyExists,
                        format!(
                            "cannot replace {}: it exists and is not a regular file (a directory or a link?)",
                            path.display()
                        ),
                    ),
                });
            }
        }
    }

    let critical = crate::signals::Critical::begin();
    // locks in a fixed order (no two writers wait on each other)
    let mut order: Vec<&Path> = dirs.clone();
    order.sort();
    let mut locks = Vec::new();
    for d in order {
        match lock_dir(d) {
            Ok(l) => locks.push(l),
            Err(source) => {
                // (named by its first file: the path the caller gave)
                let first = files.iter().find(|(p, _)| parent(p) == d).map(|(p, _)| *p);
                return Err(WriteError::Prepare {
                    path: first.unwrap_or(d).to_path_buf(),
                    source: io::Error::new(
                        source.kind(),
                        format!("cannot write {}: {source}", first.unwrap_or(d).display()),
                    ),
                });
            }
        }
    }
    let mut staged: Vec<Staged> = Vec::with_capacity(dirs.len());
    for d in &dirs {
        let set: Vec<(&Path, &[u8])> = files
            .iter()
            .copied()
            .filter(|(p, _)| parent(p) == *d)
            .collect();
        let result = if critical.interrupted().is_some() {
            Err((
                d.to_path_buf(),
                io::Error::new(io::ErrorKind::Interrupted, "interrupted by a signal"),
            ))
        } else {
            stage(d, &set)
        };
        match result {
            Ok(s) => staged.push(s),
            Err((path, source)) => {
                for s in &staged {
                    s.discard();
                }
                return Err(WriteError::Prepare { path, source });
            }
        }
    }

    let pause = std::env::var("BRDFBAKE_TEST_PAUSE_BEFORE_COMMIT")
        .ok()
        .and_then(|v| v.parse::<usize>().ok());
    let mut committed: Vec<PathBuf> = Vec::with_capacity(files.len());
    let total = files.len();
    for (i, s) in staged.iter().enumerate() {
        if pause == Some(i) {
            test_pause(i, staged.len(), &critical);
        }
        if critical.interrupted().is_some() {
            for s in &staged[i..] {
                s.discard();
            }
            return Err(WriteError::Commit {
                path: s.dir.clone(),
                source: io::Error::new(io::ErrorKind::Interrupted, "interrupted by a signal"),
                committed,
                total,
            });
        }
        if let Err((path, source)) = s.commit(&mut committed) {
            for s in &staged[i + 1..] {
                s.discard();
            }
            sync_dirs(&committed);
            return Err(WriteError::Commit {
                path,
                source,
                committed,
                total,
            });
        }
    }
    sync_dirs(&committed);
    drop(locks);
    critical.finish();
    Ok(())
}

/// A test hook (`BRDFBAKE_TEST_PAUSE_BEFORE_COMMIT=k`): before putting the k-th directory in
/// place, say so on stderr and wait up to 30 s (or until a signal arrives), so a test can kill
/// the process at every point of the commit.
fn test_pause(i: usize, n: usize, critical: &crate::signals::Critical) {
    eprintln!("brdfbake: paused before commit {i} of {n}");
    let start = std::time::Instant::now();
    while critical.interrupted().is_none() && start.elapsed().as_secs() < 30 {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
}

/// The directory a staged copy of `dir` is made in (its parent), if `dir` can be exchanged
/// at all (it has a parent and a name).
fn staging_parent(dir: &Path) -> Option<&Path> {
    dir.file_name()?;
    Some(parent(dir))
}

/// A lock on a directory, held until dropped (`flock` on the directory itself; re-taken if the
/// directory was exchanged while waiting for it).
struct DirLock {
    #[cfg(unix)]
    _file: fs::File,
}

fn lock_dir(dir: &Path) -> io::Result<DirLock> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        use std::os::unix::io::AsRawFd;
        loop {
            let f =
                fs::File::open(dir).map_err(|e| describe(e, "cannot open the directory", dir))?;
            // SAFETY: flock on a descriptor we own
            if unsafe { libc::flock(f.as_raw_fd(), libc::LOCK_EX) } != 0 {
                return Err(describe(io::Error::last_os_error(), "cannot lock", dir));
            }
            // the directory may have been exchanged by the writer we waited for
            let (held, now) = (f.metadata()?, fs::metadata(dir)?);
            if held.ino() == now.ino() && held.dev() == now.dev() {
                return Ok(DirLock { _file: f });
            }
        }
    }
    #[cfg(not(unix))]
    {
        let _ = dir;
        Ok(DirLock {})
    }
}

/// A directory's new files, staged.
struct Staged {
    /// The directory.
    dir: PathBuf,
    /// A complete copy of the directory with the new files (exchange), or `None`: the new
    /// files are the temporary files in `temps`, renamed one by one.
    copy: Option<PathBuf>,
    /// (temporary file, target) in the order given, when there is no copy.
    temps: Vec<(PathBuf, PathBuf)>,
    /// The targets, for [`WriteError::Commit`].
    targets: Vec<PathBuf>,
}

impl Staged {
    /// Removes what was staged.
    fn discard(&self) {
        if let Some(c) = &self.copy {
            let _ = fs::remove_dir_all(c);
        }
        for (t, _) in &self.temps {
            let _ = fs::remove_file(t);
        }
    }

    /// Puts the new files in place: one exchange, or renames in order.
    fn commit(&self, committed: &mut Vec<PathBuf>) -> Result<(), (PathBuf, io::Error)> {
        if let Some(copy) = &self.copy {
            match exchange(copy, &self.dir) {
                Ok(()) => {
                    // the copy's path now holds the old directory
                    let _ = fs::remove_dir_all(copy);
                    sync_dir(parent(&self.dir));
                    committed.extend(self.targets.iter().cloned());
                    return Ok(());
                }
                // a file system without the exchange (EINVAL): the new files one by one
                Err(e)
                    if e.raw_os_error() == Some(EINVAL)
                        || e.kind() == io::ErrorKind::Unsupported =>
                {
                    for path in &self.targets {
                        let from = copy.join(path.file_name().expect("a file path"));
                        if let Err(e) = commit(&from, path) {
                            let _ = fs::remove_dir_all(copy);
                            return Err((path.clone(), e));
                        }
                        committed.push(path.clone());
                    }
                    let _ = fs::remove_dir_all(copy);
                    return Ok(());
                }
                Err(e) => {
                    let _ = fs::remove_dir_all(copy);
                    return Err((
                        self.dir.clone(),
                        describe(e, "cannot put in place the new files of", &self.dir),
                    ));
                }
            }
        }
        for (i, (tmp, path)) in self.temps.iter().enumerate() {
            if let Err(e) = commit(tmp, path) {
                for (t, _) in &self.temps[i + 1..] {
                    let _ = fs::remove_file(t);
                }
                return Err((path.clone(), e));
            }
            committed.push(path.clone());
        }
        Ok(())
    }
}

/// Stages the new `files` of `dir`: as a complete copy of the directory when it can be
/// exchanged, else as temporary files next to their targets.
fn stage(dir: &Path, files: &[(&Path, &[u8])]) -> Result<Staged, (PathBuf, io::Error)> {
    let targets: Vec<PathBuf> = files.iter().map(|(p, _)| p.to_path_buf()).collect();
    if let Some(copy) = exchangeable(dir)
        .then(|| staging_copy(dir, files))
        .transpose()?
        .flatten()
    {
        return Ok(Staged {
            dir: dir.to_path_buf(),
            copy: Some(copy),
            temps: Vec::new(),
            targets,
        });
    }
    let mut temps = Vec::with_capacity(files.len());
    for &(path, bytes) in files {
        match prepare(path, bytes) {
            Ok(tmp) => temps.push((tmp, path.to_path_buf())),
            Err(e) => {
                for (t, _) in &temps {
                    let _ = fs::remove_file(t);
                }
                return Err((path.to_path_buf(), e));
            }
        }
    }
    Ok(Staged {
        dir: dir.to_path_buf(),
        copy: None,
        temps,
        targets,
    })
}

/// Whether `dir` may be replaced by an exchange: a real directory (not a link to one) with a
/// parent, on a system that has the exchange.
fn exchangeable(dir: &Path) -> bool {
    cfg!(target_os = "linux")
        && staging_parent(dir).is_some()
        && fs::symlink_metadata(dir).is_ok_and(|m| m.is_dir())
}

/// A complete copy of `dir` with `files` written into it, made next to `dir`: its other
/// regular files hard-linked (copied where a link is refused), its links recreated. `None`
/// when `dir` holds something else (a subdirectory, a device): it is then written file by
/// file.
fn staging_copy(
    dir: &Path,
    files: &[(&Path, &[u8])],
) -> Result<Option<PathBuf>, (PathBuf, io::Error)> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let fail = |p: &Path, e: io::Error| (p.to_path_buf(), e);
    let entries: Vec<fs::DirEntry> = fs::read_dir(dir)
        .map_err(|e| fail(dir, describe(e, "cannot read the directory", dir)))?
        .collect::<io::Result<_>>()
        .map_err(|e| fail(dir, describe(e, "cannot read the directory", dir)))?;
    let new: Vec<&std::ffi::OsStr> = files.iter().filter_map(|(p, _)| p.file_name()).collect();
    let mut carried = Vec::new();
    for e in &entries {
        let name = e.file_name();
        if new.contains(&name.as_os_str()) || name.to_str().and_then(temp_owner).is_some() {
            continue;
        }
        let t = e.file_type().map_err(|er| fail(&e.path(), er))?;
        if !(t.is_file() || t.is_symlink()) {
            return Ok(None);
        }
        carried.push((e.path(), t.is_symlink()));
    }
    let name = dir
        .file_name()
        .expect("exchangeable")
        .to_string_lossy()
        .into_owned();
    let up = parent(dir);
    let copy = loop {
        let c = up.join(format!(
            ".{name}{TEMP_MARK}{}-{}",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        match fs::create_dir(&c) {
            Ok(()) => break c,
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => {
                return Err(fail(
                    dir,
                    describe(e, "cannot create a staging directory next to", dir),
                ))
            }
        }
    };
    let fill = || -> Result<(), (PathBuf, io::Error)> {
        if let Ok(m) = fs::metadata(dir) {
            let _ = fs::set_permissions(&copy, m.permissions());
        }
        for (p, link) in &carried {
            let to = copy.join(p.file_name().expect("an entry"));
            let r = if *link {
                fs::read_link(p).and_then(|target| symlink(&target, &to))
            } else {
                fs::hard_link(p, &to).or_else(|_| fs::copy(p, &to).map(|_| ()))
            };
            r.map_err(|e| fail(p, describe(e, "cannot stage", p)))?;
        }
        for &(path, bytes) in files {
            let to = copy.join(path.file_name().expect("a file path"));
            let mut f = OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&to)
                .map_err(|e| fail(path, describe(e, "cannot write", path)))?;
            f.write_all(bytes)
                .and_then(|()| f.sync_all())
                .map_err(|e| fail(path, describe(e, "cannot write", path)))?;
        }
        sync_dir(&copy);
        Ok(())
    };
    match fill() {
        Ok(()) => Ok(Some(copy)),
        Err(e) => {
            let _ = fs::remove_dir_all(&copy);
            Err(e)
        }
    }
}

#[cfg(unix)]
fn symlink(target: &Path, link: &Path) -> io::Result<()> {
    std::os::unix::fs::symlink(target, link)
}

#[cfg(not(unix))]
fn symlink(_target: &Path, link: &Path) -> io::Result<()> {
    Err(io::Error::new(
        io::ErrorKind::Unsupported,
        format!("cannot recreate the link {}", link.display()),
    ))
}

#[cfg(unix)]
const EINVAL: i32 = libc::EINVAL;
#[cfg(not(unix))]
const EINVAL: i32 = 22;

/// Exchanges two directories in one step (`renameat2` with `RENAME_EXCHANGE`, Linux 3.15+).
fn exchange(a: &Path, b: &Path) -> io::Result<()> {
    #[cfg(target_os = "linux")]
    {
        use std::ffi::CString;
        use std::os::unix::ffi::OsStrExt;
        let ca = CString::new(a.as_os_str().as_bytes())?;
        let cb = CString::new(b.as_os_str().as_bytes())?;
        // SAFETY: two NUL-terminated paths that live through the call
        let r = unsafe {
            libc::syscall(
                libc::SYS_renameat2,
                libc::AT_FDCWD,
                ca.as_ptr(),
                libc::AT_FDCWD,
                cb.as_ptr(),
                libc::RENAME_EXCHANGE,
            )
        };
        if r == 0 {
            Ok(())
        } else {
            Err(io::Error::last_os_error())
        }
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = (a, b);
        Err(io::Error::new(
            io::ErrorKind::Unsupported,
            "no directory exchange here",
        ))
    }
}

/// `io::Error` of the same kind, with `what` and the path in the message.
fn describe(e: io::Error, what: &str, path: &Path) -> io::Error {
    io::Error::new(e.kind(), format!("{what} {}: {e}", path.display()))
}

/// The directory `path` is in (`.` for a bare file name).
fn parent(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Writes `bytes` to a new temporary file next to `path` and flushes it to disk. Returns the
/// temporary file's path; on error no temporary file remains.
fn prepare(path: &Path, bytes: &[u8]) -> io::Result<PathBuf> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    prepare_counted(path, bytes, &COUNTER)
}

/// [`prepare`] with the counter that numbers the temporary files.
fn prepare_counted(path: &Path, bytes: &[u8], counter: &AtomicU64) -> io::Result<PathBuf> {
    let name = path.file_name().ok_or_else(|| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("cannot write {}: not a file path", path.display()),
        )
    })?;
    // `.<name>.tmp-<pid>-<n>`: a leftover of a killed process whose id this one reuses can
    // hold the same name, so an existing one is skipped (create_new), never opened
    let mut attempts = 0;
    let (tmp, mut file) = loop {
        let tmp = parent(path).join(format!(
            ".{}{TEMP_MARK}{}-{}",
            name.to_string_lossy(),
            std::process::id(),
            counter.fetch_add(1, Ordering::Relaxed)
        ));
        match OpenOptions::new().write(true).create_new(true).open(&tmp) {
            Ok(f) => break (tmp, f),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists && attempts < 1000 => {
                attempts += 1;
            }
            Err(e) => return Err(describe(e, "cannot create a temporary file for", path)),
        }
    };
    let written = file.write_all(bytes).and_then(|()| file.sync_all());
    drop(file);
    if let Err(e) = written {
        let _ = fs::remove_file(&tmp);
        return Err(describe(e, "cannot write", path));
    }
    Ok(tmp)
}

/// What marks our temporary files: `.<name>.tmp-<pid>-<n>`.
const TEMP_MARK: &str = ".tmp-";

/// The process id in a temporary file's name, if it is one of ours.
fn temp_owner(file_name: &str) -> Option<u32> {
    let rest = file_name.strip_prefix('.')?;
    let at = rest.rfind(TEMP_MARK)?;
    let (pid, n) = rest[at + TEMP_MARK.len()..].split_once('-')?;
    if rest[..at].is_empty() || n.is_empty() || !n.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    pid.parse().ok()
}

/// Whether process `pid` is alive (on Unix; elsewhere every owner counts as alive, so
/// nothing is removed).
fn alive(pid: u32) -> bool {
    #[cfg(unix)]
    {
        if pid == std::process::id() {
            return true;
        }
        let Ok(p) = libc::pid_t::try_from(pid) else {
            return false;
        };
        // SAFETY: signal 0 only checks that the process exists and may be signalled.
        let r = unsafe { libc::kill(p, 0) };
        r == 0 || io::Error::last_os_error().raw_os_error() == Some(libc::EPERM)
    }
    #[cfg(not(unix))]
    {
        let _ = pid;
        true
    }
}

/// Removes the temporary files that killed writers left in `dir` (ours by name, their
/// process gone); a file whose process still runs — another bake writing there now — is
/// kept. Best effort: what cannot be removed stays (it is never read). Returns how many
/// were removed.
pub fn sweep_leftovers(dir: &Path) -> usize {
    let Ok(entries) = fs::read_dir(dir) else {
        return 0;
    };
    let mut removed = 0;
    for e in entries.flatten() {
        let name = e.file_name();
        let Some(pid) = name.to_str().and_then(temp_owner) else {
            continue;
        };
        if alive(pid) {
            continue;
        }
        // a temporary file, or a staged copy of a directory (crate::write::staging_copy)
        let gone = match e.file_type() {
            Ok(t) if t.is_file() => fs::remove_file(e.path()).is_ok(),
            Ok(t) if t.is_dir() => fs::remove_dir_all(e.path()).is_ok(),
            _ => false,
        };
        if gone {
            removed += 1;
        }
    }
    removed
}

/// Renames the finished temporary file over `path`; removes it if that fails.
fn commit(tmp: &Path, path: &Path) -> io::Result<()> {
    fs::rename(tmp, path).map_err(|e| {
        let _ = fs::remove_file(tmp);
        describe(e, "cannot replace", path)
    })
}

/// Flushes a directory entry change to disk (best effort; a no-op where directories cannot
/// be opened).
fn sync_dir(dir: &Path) {
    #[cfg(unix)]
    if let Ok(d) = fs::File::open(dir) {
        let _ = d.sync_all();
    }
    #[cfg(not(unix))]
    let _ = dir;
}

/// [`sync_dir`] on each distinct parent directory of `paths`.
fn sync_dirs(paths: &[PathBuf]) {
    let mut done: Vec<&Path> = Vec::new();
    for p in paths {
        let dir = parent(p);
        if !done.contains(&dir) {
            sync_dir(dir);
            done.push(dir);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every entry of `dir`, sorted.
    fn entries(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn writes_and_replaces() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.exr");
        write_atomic(&path, b"first").unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"first");
        write_atomic(&path, b"second, longer").unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"second, longer");
        write_atomic(&path, b"").unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"");
        assert_eq!(entries(dir.path()), ["a.exr"]);
    }

    #[test]
    fn missing_directory_is_an_error_naming_the_path() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("missing").join("a.exr");
        let err = write_atomic(&path, b"x").unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::NotFound);
        assert!(
            err.to_string().contains(&path.display().to_string()),
            "{err}"
        );
        assert!(entries(dir.path()).is_empty());
    }

    /// A target that cannot be replaced (a directory) fails at the rename; the temporary
    /// file is removed.
    #[test]
    fn failed_rename_leaves_no_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("taken");
        fs::create_dir(&path).unwrap();
        fs::write(path.join("inside"), b"keep").unwrap();
        let err = write_atomic(&path, b"x").unwrap_err();
        assert!(
            err.to_string().contains(&path.display().to_string()),
            "{err}"
        );
        assert_eq!(entries(dir.path()), ["taken"]);
        assert_eq!(fs::read(path.join("inside")).unwrap(), b"keep");
    }

    #[test]
    fn write_all_changes_nothing_when_a_file_cannot_be_written() {
        let dir = tempfile::tempdir().unwrap();
        let kept = dir.path().join("a.json");
        fs::write(&kept, b"old").unwrap();
        let files = vec![
            (kept.clone(), b"new".to_vec()),
            (dir.path().join("b.exr"), b"new".to_vec()),
            (dir.path().join("missing").join("c.exr"), b"new".to_vec()),
        ];
        let err = write_all_atomic(&files).unwrap_err();
        assert!(matches!(err, WriteError::Prepare { .. }), "{err:?}");
        assert!(err.to_string().contains("c.exr"), "{err}");
        assert_eq!(fs::read(&kept).unwrap(), b"old");
        assert_eq!(entries(dir.path()), ["a.json"]);
    }

    #[test]
    fn write_all_writes_every_file() {
        let dir = tempfile::tempdir().unwrap();
        let sub = dir.path().join("sub");
        fs::create_dir(&sub).unwrap();
        fs::write(dir.path().join("a"), b"old").unwrap();
        let files = vec![
            (dir.path().join("a"), b"1".to_vec()),
            (sub.join("b"), b"2".to_vec()),
        ];
        write_all_atomic(&files).unwrap();
        assert_eq!(fs::read(dir.path().join("a")).unwrap(), b"1");
        assert_eq!(fs::read(sub.join("b")).unwrap(), b"2");
        assert_eq!(entries(dir.path()), ["a", "sub"]);
        assert_eq!(entries(&sub), ["b"]);

        let dup = vec![
            (sub.join("b"), b"3".to_vec()),
            (sub.join("b"), b"4".to_vec()),
        ];
        assert!(matches!(
            write_all_atomic(&dup),
            Err(WriteError::DuplicatePath(_))
        ));
        assert_eq!(fs::read(sub.join("b")).unwrap(), b"2");
    }

    #[test]
    fn temporary_names_are_recognized() {
        assert_eq!(temp_owner(".dfg.exr.tmp-123-4"), Some(123));
        assert_eq!(temp_owner(".a.tmp-b.json.tmp-77-0"), Some(77));
        for not_ours in [
            "dfg.exr",
            ".dfg.exr",
            ".tmp-1-2",
            ".x.tmp-1-",
            ".x.tmp-a-1",
            ".x.tmp-1-2b",
            "x.tmp-1-2",
        ] {
            assert_eq!(temp_owner(not_ours), None, "{not_ours}");
        }
    }

    /// Leftovers of a dead process are swept, a live process' and other files are kept, and
    /// a leftover holding the name this process would use next is skipped, not reused.
    #[test]
    fn leftovers_are_swept_and_never_collide() {
        let dir = tempfile::tempdir().unwrap();
        // a process id that is not running: a child that has exited and been reaped
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let dead = child.id();
        child.wait().unwrap();
        let me = std::process::id();
        for n in [
            format!(".a.exr.tmp-{dead}-0"),
            format!(".a.json.tmp-{dead}-7"),
            format!(".a.exr.tmp-{me}-999"),
            "keep.txt".into(),
            ".hidden".into(),
        ] {
            fs::write(dir.path().join(n), b"x").unwrap();
        }
        assert_eq!(sweep_leftovers(dir.path()), 2);
        let left = entries(dir.path());
        assert!(left.contains(&format!(".a.exr.tmp-{me}-999")), "{left:?}");
        assert!(left.contains(&"keep.txt".to_string()) && left.contains(&".hidden".to_string()));
        // every name this process may pick next is taken: prepare skips them all
        let path = dir.path().join("b.exr");
        for n in 0..50 {
            fs::write(dir.path().join(format!(".b.exr.tmp-{me}-{n}")), b"old").unwrap();
        }
        let counter = AtomicU64::new(0);
        let tmp = prepare_counted(&path, b"new", &counter).unwrap();
        assert_eq!(
            tmp.file_name().unwrap().to_string_lossy(),
            format!(".b.exr.tmp-{me}-50")
        );
        commit(&tmp, &path).unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"new");
        for n in 0..50 {
            let p = dir.path().join(format!(".b.exr.tmp-{me}-{n}"));
            assert_eq!(
                fs::read(p).unwrap(),
                b"old",
                "a live process' file was touched"
            );
        }
    }

    /// A target that is a directory fails the whole set before anything is replaced.
    #[test]
    fn write_all_refuses_a_target_that_is_not_a_file_before_any_rename() {
        let dir = tempfile::tempdir().unwrap();
        let blocked = dir.path().join("blocked");
        fs::create_dir(&blocked).unwrap();
        fs::write(blocked.join("x"), b"").unwrap();
        let files = vec![
            (dir.path().join("a"), b"1".to_vec()),
            (blocked.clone(), b"2".to_vec()),
            (dir.path().join("c"), b"3".to_vec()),
        ];
        match write_all_atomic(&files).unwrap_err() {
            WriteError::Prepare { path, source } => {
                assert_eq!(path, blocked);
                assert!(
                    source.to_string().contains("not a regular file"),
                    "{source}"
                );
            }
            other => panic!("unexpected error {other:?}"),
        }
        // nothing was replaced or created, and no temporary file is left
        assert_eq!(entries(dir.path()), ["blocked"]);
    }
}
