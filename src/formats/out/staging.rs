//! Safe output folders: a kit is written into a staging folder beside the
//! output folder DIR and takes DIR's place in one atomic step once
//! complete, so a failed, interrupted or killed build leaves the old kit or
//! the new one, whole, and never touches a file that is not lamella's
//! ([`super::manifest`] says which are).
//!
//! Rules:
//! * `--out DIR` a symbolic link is followed: the kit goes where it
//!   points, and the link stays. DIR is a folder or a new path; the
//!   current directory is refused (DIR is replaced by a new folder: the
//!   shell would be left in the old one).
//! * Before any work, a file lamella would write (`plan.json`, `takeoff.*`,
//!   `assembly.pdf`) that is there and is not lamella's stops the build,
//!   as does a `sheets` that is not a real folder (a link in DIR is never
//!   written through); a sheet in the way stops it before anything moves.
//! * The staging folder `.NAME.lamella-build-PID` (marked `.lamella-staging`
//!   while it is written) has a journal beside it,
//!   `.NAME.lamella-build-PID.journal`, from before the folder is made to
//!   after the commit: it says the folder and what is in it are lamella's
//!   doing. The commit, once the new kit and its manifest (size and CRC-32
//!   of every file) are staged:
//!   1. the marker is removed;
//!   2. every entry of DIR that is not lamella's (the user's files and
//!      folders, at the top or in `sheets/`) moves into the staging folder,
//!      one rename each, so the old kit in DIR stays whole;
//!   3. DIR and the staging folder are exchanged in one rename (Linux
//!      `renameat2(RENAME_EXCHANGE)`): DIR is the new kit with the user's
//!      entries, the staging folder the old kit;
//!   4. the old kit's files are removed one by one (only those its manifest
//!      vouches for, and lamella's at the names the new kit has); anything
//!      else found there goes back into DIR; then the folder;
//!   5. the journal is removed.
//!
//!   A DIR that does not exist yet is the staging folder renamed to DIR.
//!   Where the exchange is not available (other systems, some file
//!   systems), step 3 is two renames, DIR aside to
//!   `.NAME.lamella-build-PID-old` and the staging folder to DIR: a kill
//!   between them leaves no DIR until the next command into DIR.
//! * So after a kill at any instant DIR holds the old kit or the new one,
//!   whole; a user's entries moved in step 2 may sit in the staging folder.
//!   The next lamella command into DIR finishes what a killed build left
//!   (a journal whose process is gone): DIR is put back if it is missing,
//!   the user's entries go back into DIR, lamella's files in the staging
//!   folder (a marked one: all of it) are removed, then the folder and the
//!   journal. An entry that cannot go back (DIR has one of the same name
//!   by then) stops that command, naming the folder.
//! * A kill, not a power cut: nothing is flushed to the disk.

use super::manifest::{self, Entry, Manifest, FOLDERS, MANIFEST};
use crate::error::{Error, Result};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The marker inside a staging folder still being written.
const MARKER: &str = ".lamella-staging";

/// Test hook: sleep this many milliseconds once everything is staged,
/// before anything is moved (so a test can kill the build there).
pub const PAUSE_ENV: &str = "LAMELLA_PAUSE_BEFORE_COMMIT_MS";

/// Test hook: kill the process (SIGKILL) just before the N-th step of the
/// commit (counted from 1: each removal, rename or exchange that changes
/// DIR, the staging folder or the journal).
pub const KILL_ENV: &str = "LAMELLA_KILL_AT_STEP";

/// Test hook: commit as where the atomic exchange is not available (two
/// renames).
pub const NO_EXCHANGE_ENV: &str = "LAMELLA_NO_RENAME_EXCHANGE";

/// The paths of one build's staging into DIR.
#[derive(Debug, Clone)]
struct Paths {
    /// DIR.
    dir: PathBuf,
    /// The staging folder (after the exchange: the old kit).
    tmp: PathBuf,
    /// Where DIR goes aside when there is no exchange.
    aside: PathBuf,
    /// The journal.
    journal: PathBuf,
}

impl Paths {
    fn of(parent: &Path, name: &str, pid: u32) -> Paths {
        let base = format!(".{name}.lamella-build-{pid}");
        Paths {
            dir: parent.join(name),
            tmp: parent.join(&base),
            aside: parent.join(format!("{base}-old")),
            journal: parent.join(format!("{base}.journal")),
        }
    }
}

/// A build's output being staged.
#[derive(Debug)]
pub struct Staging {
    paths: Paths,
    files: Mutex<Manifest>,
    committed: bool,
}

impl Staging {
    /// Start staging output for `dir` (followed when it is a link).
    /// Finishes what a killed build into it left; refuses a `dir` that is
    /// a file or the current directory, and one where an entry named in
    /// `fixed_names` is there and is not lamella's (`sheets`: not a real
    /// folder).
    pub fn begin(dir: &Path, fixed_names: &[&str]) -> Result<Staging> {
        let (parent, name) = parent_and_name(dir)?;
        let real = parent.join(&name);
        if is_current_dir(&real) {
            return Err(Error::output(
                dir,
                "is the current directory: a build replaces its output folder by a new one, which would leave you in the old one; choose a folder below it (e.g. --out kit)",
            ));
        }
        std::fs::create_dir_all(&parent).map_err(|e| Error::io(&parent, e))?;
        recover_stale(&real)?;
        let paths = Paths::of(&parent, &name, std::process::id());
        // Leftovers under this process id are a gone process's.
        recover(&paths)?;
        manifest::check_names(&super::output_dir(dir)?, fixed_names)?;
        std::fs::write(
            &paths.journal,
            format!("lamella build {} into {name}\n", std::process::id()),
        )
        .map_err(|e| Error::io(&paths.journal, e))?;
        let staging = Staging {
            paths,
            files: Mutex::new(Manifest::new()),
            committed: false,
        };
        let tmp = &staging.paths.tmp;
        std::fs::create_dir(tmp).map_err(|e| Error::io(tmp, e))?;
        std::fs::write(tmp.join(MARKER), std::process::id().to_string())
            .map_err(|e| Error::io(tmp, e))?;
        Ok(staging)
    }

    /// The staging folder.
    pub fn staging_dir(&self) -> &Path {
        &self.paths.tmp
    }

    /// Where a staged file goes once staged; an error for a name lamella
    /// does not write (the one list of them: [`manifest::is_lamella_name`]).
    fn staged_path(&self, rel: &str) -> Result<PathBuf> {
        if !manifest::is_lamella_name(rel) {
            return Err(Error::output(
                &self.paths.dir.join(rel),
                "internal: not a name lamella writes",
            ));
        }
        let path = self.paths.tmp.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(|e| Error::io(parent, e))?;
        }
        Ok(path)
    }

    fn record(&self, rel: &str, entry: Entry) -> Result<()> {
        self.files
            .lock()
            .map_err(|_| Error::output(&self.paths.dir, "a writer thread failed"))?
            .insert(rel.to_string(), entry);
        Ok(())
    }

    /// Stage `rel` (a `/`-separated path inside DIR) with `bytes`.
    pub fn write(&self, rel: &str, bytes: &[u8]) -> Result<()> {
        let path = self.staged_path(rel)?;
        super::direct::write_file(&path, bytes)
            .map_err(|e| Error::io(&self.paths.dir.join(rel), e))?;
        self.record(
            rel,
            Entry {
                bytes: bytes.len() as u64,
                crc32: crc32fast::hash(bytes),
            },
        )
    }

    /// Stage `rel` with what `write` streams into it (buffered, or past
    /// the page cache: [`super::direct`]).
    pub fn write_with(
        &self,
        rel: &str,
        write: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
    ) -> Result<()> {
        let path = self.staged_path(rel)?;
        let mut w = super::direct::Writer::create(&path)
            .map_err(|e| Error::io(&self.paths.dir.join(rel), e))?;
        let mut counted = Counted {
            inner: &mut w,
            hasher: crc32fast::Hasher::new(),
            bytes: 0,
        };
        let r = write(&mut counted);
        let entry = Entry {
            bytes: counted.bytes,
            crc32: counted.hasher.finalize(),
        };
        r.and_then(|()| w.finish())
            .map_err(|e| Error::io(&self.paths.dir.join(rel), e))?;
        self.record(rel, entry)
    }

    /// Move the staged kit into DIR (see the module doc).
    pub fn commit(mut self) -> Result<()> {
        if let Some(ms) = std::env::var(PAUSE_ENV)
            .ok()
            .and_then(|v| v.parse::<u64>().ok())
        {
            std::thread::sleep(std::time::Duration::from_millis(ms));
        }
        let files: Manifest = std::mem::take(
            &mut *self
                .files
                .lock()
                .map_err(|_| Error::output(&self.paths.dir, "a writer thread failed"))?,
        );
        let p = self.paths.clone();
        let staged_manifest = p.tmp.join(format!("{MANIFEST}.tmp"));
        std::fs::write(&staged_manifest, manifest::to_text(&files))
            .map_err(|e| Error::io(&p.tmp, e))?;
        rename(&staged_manifest, &p.tmp.join(MANIFEST))?;
        let dir_exists = std::fs::symlink_metadata(&p.dir).is_ok();
        // What of DIR goes with the new kit: found (and anything in the
        // way refused) before anything moves.
        let carry = if dir_exists {
            carried(&p.dir, &files)?
        } else {
            Vec::new()
        };
        step();
        remove_file(&p.tmp.join(MARKER))?;
        if dir_exists {
            for rel in &carry {
                let to = p.tmp.join(rel);
                if let Some(parent) = to.parent() {
                    if !parent.exists() {
                        std::fs::create_dir(parent).map_err(|e| Error::io(parent, e))?;
                    }
                }
                step();
                rename(&p.dir.join(rel), &to)?;
            }
            // DIR's permissions go with it (after the moves into the
            // staging folder, which a read-only DIR's would stop).
            if let Ok(meta) = std::fs::metadata(&p.dir) {
                let _ = std::fs::set_permissions(&p.tmp, meta.permissions());
            }
            let old = swap(&p)?;
            let mut new_names: BTreeSet<String> = files.keys().cloned().collect();
            new_names.insert(MANIFEST.to_string());
            drain(&old, &p.dir, &new_names, step)?;
        } else {
            step();
            rename(&p.tmp, &p.dir)?;
        }
        step();
        remove_file(&p.journal)?;
        self.committed = true;
        Ok(())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.committed {
            // Roll back (or, past the exchange, forward) what this build
            // did: only ever lamella's own staging.
            let _ = recover(&self.paths);
        }
    }
}

/// A writer that counts and checksums what passes through it.
struct Counted<'a> {
    inner: &'a mut dyn std::io::Write,
    hasher: crc32fast::Hasher,
    bytes: u64,
}

impl std::io::Write for Counted<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.hasher.update(&buf[..n]);
        self.bytes += n as u64;
        Ok(n)
    }

    fn write_all(&mut self, buf: &[u8]) -> std::io::Result<()> {
        self.inner.write_all(buf)?;
        self.hasher.update(buf);
        self.bytes += buf.len() as u64;
        Ok(())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

/// The parent folder and the name of the output folder `dir` (followed
/// when a link; `.` and `..` resolved).
fn parent_and_name(dir: &Path) -> Result<(PathBuf, String)> {
    let mut real = super::output_dir(dir)?;
    if real.file_name().is_none() {
        real = real.canonicalize().map_err(|e| Error::io(dir, e))?;
    }
    let (Some(name), Some(parent)) = (real.file_name(), real.parent()) else {
        return Err(Error::output(
            dir,
            "has no parent folder to stage beside: choose another output directory",
        ));
    };
    let parent = if parent.as_os_str().is_empty() {
        PathBuf::from(".")
    } else {
        parent.to_path_buf()
    };
    Ok((parent, name.to_string_lossy().into_owned()))
}

/// Whether `dir` is the process's current directory.
fn is_current_dir(dir: &Path) -> bool {
    match (
        dir.canonicalize(),
        std::env::current_dir().and_then(|d| d.canonicalize()),
    ) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

/// The entries of DIR that are not lamella's, which go with the new kit
/// (`files`), as paths inside DIR; an error for one in the way of a file
/// the new kit has.
fn carried(dir: &Path, files: &Manifest) -> Result<Vec<PathBuf>> {
    let old = manifest::read(dir)?;
    let has = |folder: &str| {
        files
            .keys()
            .any(|k| k.strip_prefix(folder).is_some_and(|r| r.starts_with('/')))
    };
    let mut carry = Vec::new();
    // Lamella's when it is at a name the new kit has and may be written
    // over, or the old manifest vouches for it; an error when it is in the
    // way of the new kit; else the user's.
    let mut classify = |rel: PathBuf, meta: &std::fs::Metadata| -> Result<()> {
        let p = dir.join(&rel);
        let Some(name) = rel.to_str() else {
            carry.push(rel);
            return Ok(());
        };
        if files.contains_key(name) {
            if !meta.is_file() {
                return Err(manifest::in_the_way(&p, meta));
            }
            if !manifest::replaceable(dir, name, &old) {
                return Err(manifest::foreign(&p));
            }
        } else if !manifest::vouched(dir, name, &old) {
            carry.push(rel);
        }
        Ok(())
    };
    for (name, meta) in entries(dir)? {
        if name == MANIFEST {
            if !meta.is_file() {
                return Err(manifest::in_the_way(&dir.join(MANIFEST), &meta));
            }
            continue;
        }
        if let Some(folder) = FOLDERS.iter().find(|f| **f == name) {
            if meta.is_dir() {
                for (sub, m) in entries(&dir.join(folder))? {
                    classify(Path::new(folder).join(sub), &m)?;
                }
                continue;
            }
            if has(folder) {
                return Err(manifest::in_the_way(&dir.join(folder), &meta));
            }
        }
        classify(PathBuf::from(name), &meta)?;
    }
    Ok(carry)
}

/// The entries of a folder with their metadata (links not followed), by
/// name.
fn entries(dir: &Path) -> Result<Vec<(std::ffi::OsString, std::fs::Metadata)>> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).map_err(|e| Error::io(dir, e))? {
        let e = e.map_err(|e| Error::io(dir, e))?;
        let meta = std::fs::symlink_metadata(e.path()).map_err(|err| Error::io(&e.path(), err))?;
        out.push((e.file_name(), meta));
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    Ok(out)
}

/// Put the staging folder in DIR's place; returns where the old kit is.
fn swap(p: &Paths) -> Result<PathBuf> {
    if std::env::var_os(NO_EXCHANGE_ENV).is_none() {
        step();
        match exchange(&p.dir, &p.tmp) {
            Ok(()) => return Ok(p.tmp.clone()),
            Err(e) if !unsupported(&e) => return Err(Error::io(&p.dir, e)),
            Err(_) => {}
        }
    }
    step();
    rename(&p.dir, &p.aside)?;
    step();
    rename(&p.tmp, &p.dir)?;
    Ok(p.aside.clone())
}

/// Remove what is lamella's in `from` (the old kit after a commit, or
/// the staging folder of a killed build) and put everything else back into
/// `dir`; then remove `from`. Lamella's: files `from`'s manifest vouches
/// for, and lamella's files at the names in `new_names` (the new kit's).
/// `hook` runs before each change (the kill test's steps).
fn drain(from: &Path, dir: &Path, new_names: &BTreeSet<String>, hook: fn()) -> Result<()> {
    let m = manifest::read(from)?;
    let removable = |rel: &Path| -> bool {
        rel.to_str().is_some_and(|r| {
            manifest::vouched(from, r, &m)
                || (new_names.contains(r) && manifest::replaceable(from, r, &m))
        })
    };
    let mut stuck: Option<PathBuf> = None;
    let mut put_back = |rel: PathBuf| -> Result<()> {
        let to = dir.join(&rel);
        if std::fs::symlink_metadata(&to).is_ok() {
            stuck.get_or_insert(rel);
            return Ok(());
        }
        if let Some(parent) = to.parent() {
            if !parent.exists() {
                hook();
                std::fs::create_dir(parent).map_err(|e| Error::io(parent, e))?;
            }
        }
        hook();
        rename(&from.join(&rel), &to)
    };
    for folder in FOLDERS {
        let sheets = from.join(folder);
        if std::fs::symlink_metadata(&sheets).is_ok_and(|m| m.is_dir()) {
            for (name, _) in entries(&sheets)? {
                let rel = Path::new(folder).join(name);
                if removable(&rel) {
                    hook();
                    remove_file(&from.join(&rel))?;
                } else {
                    put_back(rel)?;
                }
            }
            if entries(&sheets)?.is_empty() {
                hook();
                std::fs::remove_dir(&sheets).map_err(|e| Error::io(&sheets, e))?;
            }
        }
    }
    for (name, meta) in entries(from)? {
        let rel = PathBuf::from(&name);
        if name == MANIFEST || (FOLDERS.iter().any(|f| name == *f) && meta.is_dir()) {
            continue;
        }
        if name == MARKER || removable(&rel) {
            hook();
            remove_file(&from.join(&rel))?;
        } else {
            put_back(rel)?;
        }
    }
    if let Some(rel) = stuck {
        return Err(Error::output(
            from,
            format!(
                "holds {} of yours, which an interrupted build moved out of the output folder and cannot put back (a file of that name is there now): move it by hand",
                rel.display()
            ),
        ));
    }
    let m = from.join(MANIFEST);
    if std::fs::symlink_metadata(&m).is_ok_and(|m| m.is_file()) {
        hook();
        remove_file(&m)?;
    }
    hook();
    std::fs::remove_dir(from).map_err(|e| Error::io(from, e))
}

/// Finish what the build of `p` left: DIR put back if it is missing, the
/// staging folder (and the old DIR set aside) drained into DIR, the
/// journal removed. Without a journal only a marked staging folder is
/// removed (nothing else there is known to be lamella's).
fn recover(p: &Paths) -> Result<()> {
    let journal = std::fs::symlink_metadata(&p.journal).is_ok_and(|m| m.is_file());
    let is_dir = |d: &Path| std::fs::symlink_metadata(d).is_ok_and(|m| m.is_dir());
    let marked = |d: &Path| {
        std::fs::symlink_metadata(d.join(MARKER)).is_ok_and(|m| m.is_file())
            && std::fs::symlink_metadata(d).is_ok_and(|m| m.is_dir())
    };
    if !journal {
        if marked(&p.tmp) {
            std::fs::remove_dir_all(&p.tmp).map_err(|e| Error::io(&p.tmp, e))?;
        }
        return Ok(());
    }
    if std::fs::symlink_metadata(&p.dir).is_err() && is_dir(&p.aside) {
        rename(&p.aside, &p.dir)?;
    }
    for from in [&p.tmp, &p.aside] {
        if marked(from) {
            std::fs::remove_dir_all(from).map_err(|e| Error::io(from, e))?;
        } else if is_dir(from) {
            let mut names: BTreeSet<String> = manifest::read(from)?.into_keys().collect();
            names.extend(manifest::read(&p.dir)?.into_keys());
            drain(from, &p.dir, &names, || {})?;
        }
    }
    remove_file(&p.journal)
}

/// Finish what killed builds into `dir` left (their processes gone): see
/// the module doc. Every lamella command writing into `dir` calls this
/// first.
pub fn recover_stale(dir: &Path) -> Result<()> {
    let (Some(name), Some(parent)) = (dir.file_name(), dir.parent()) else {
        return Ok(());
    };
    let parent = if parent.as_os_str().is_empty() {
        Path::new(".")
    } else {
        parent
    };
    let name = name.to_string_lossy();
    let prefix = format!(".{name}.lamella-build-");
    let Ok(list) = std::fs::read_dir(parent) else {
        return Ok(());
    };
    let mut pids = BTreeSet::new();
    for e in list.flatten() {
        let file_name = e.file_name().to_string_lossy().into_owned();
        let Some(rest) = file_name.strip_prefix(&prefix) else {
            continue;
        };
        let digits: String = rest.chars().take_while(|c| c.is_ascii_digit()).collect();
        if let Ok(pid) = digits.parse::<u32>() {
            pids.insert(pid);
        }
    }
    for pid in pids {
        let alive = Path::new("/proc").is_dir() && Path::new(&format!("/proc/{pid}")).exists();
        if !alive && pid != std::process::id() {
            recover(&Paths::of(parent, &name, pid))?;
        }
    }
    Ok(())
}

fn rename(from: &Path, to: &Path) -> Result<()> {
    std::fs::rename(from, to).map_err(|e| Error::io(to, e))
}

fn remove_file(p: &Path) -> Result<()> {
    std::fs::remove_file(p).map_err(|e| Error::io(p, e))
}

/// The kill test's hook: before each step of a commit (see [`KILL_ENV`]).
fn step() {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static AT: std::sync::OnceLock<Option<usize>> = std::sync::OnceLock::new();
    static DONE: AtomicUsize = AtomicUsize::new(0);
    let at = AT.get_or_init(|| std::env::var(KILL_ENV).ok().and_then(|v| v.parse().ok()));
    if let Some(at) = *at {
        if DONE.fetch_add(1, Ordering::SeqCst) + 1 == at {
            // A real SIGKILL, as from outside; abort where `kill` is missing.
            let pid = std::process::id().to_string();
            if std::process::Command::new("kill")
                .args(["-KILL", &pid])
                .status()
                .is_ok()
            {
                loop {
                    std::thread::sleep(std::time::Duration::from_secs(1));
                }
            }
            std::process::abort();
        }
    }
}

/// Whether an exchange failed because the system or the file system does
/// not offer it.
fn unsupported(e: &std::io::Error) -> bool {
    #[cfg(target_os = "linux")]
    {
        matches!(
            e.raw_os_error(),
            Some(libc::EINVAL) | Some(libc::ENOSYS) | Some(libc::EOPNOTSUPP)
        ) || e.kind() == std::io::ErrorKind::Unsupported
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = e;
        true
    }
}

/// Exchange two paths in one atomic rename (`renameat2` with
/// `RENAME_EXCHANGE`, Linux 3.15 on).
#[cfg(target_os = "linux")]
#[allow(unsafe_code)]
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    use std::os::unix::ffi::OsStrExt;
    let a = std::ffi::CString::new(a.as_os_str().as_bytes())?;
    let b = std::ffi::CString::new(b.as_os_str().as_bytes())?;
    // SAFETY: both pointers are NUL-terminated strings that live across
    // the call, which only reads them; AT_FDCWD makes relative paths
    // relative to the current directory, as `std::fs::rename` does.
    let r = unsafe {
        libc::renameat2(
            libc::AT_FDCWD,
            a.as_ptr(),
            libc::AT_FDCWD,
            b.as_ptr(),
            libc::RENAME_EXCHANGE,
        )
    };
    if r == 0 {
        Ok(())
    } else {
        Err(std::io::Error::last_os_error())
    }
}

#[cfg(not(target_os = "linux"))]
fn exchange(_: &Path, _: &Path) -> std::io::Result<()> {
    Err(std::io::Error::from(std::io::ErrorKind::Unsupported))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("lamella-outdir-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).expect("scratch");
        d
    }

    #[test]
    fn new_directory_gets_files_and_manifest() {
        let root = scratch("new");
        let dir = root.join("out");
        let s = Staging::begin(&dir, &["plan.json"]).expect("begin");
        s.write("plan.json", b"{}").expect("write");
        s.write("sheets/sheet-001.dxf", b"x").expect("write");
        s.commit().expect("commit");
        assert_eq!(std::fs::read(dir.join("plan.json")).expect("read"), b"{}");
        assert_eq!(
            std::fs::read_to_string(dir.join(MANIFEST)).expect("manifest"),
            format!(
                "# lamella manifest 2: bytes, CRC-32, path\n2 {:08x} plan.json\n1 {:08x} sheets/sheet-001.dxf\n",
                crc32fast::hash(b"{}"),
                crc32fast::hash(b"x")
            )
        );
        assert_eq!(
            std::fs::read_dir(&root).expect("ls").count(),
            1,
            "no staging left"
        );
    }

    #[test]
    fn foreign_files_are_kept_and_stale_lamella_files_removed() {
        let root = scratch("foreign");
        let dir = root.join("out");
        let s = Staging::begin(&dir, &[]).expect("begin");
        s.write("sheets/sheet-001.dxf", b"1").expect("write");
        s.write("sheets/sheet-002.dxf", b"2").expect("write");
        s.write("sheets/sheet-003.dxf", b"3").expect("write");
        s.commit().expect("commit");
        std::fs::write(dir.join("notes.txt"), "mine").expect("foreign");
        // Changed since lamella wrote it: the user's now.
        std::fs::write(dir.join("sheets/sheet-003.dxf"), "edited").expect("edit");
        let s = Staging::begin(&dir, &[]).expect("begin");
        s.write("sheets/sheet-001.dxf", b"new").expect("write");
        s.commit().expect("commit");
        assert_eq!(
            std::fs::read_to_string(dir.join("notes.txt")).expect("kept"),
            "mine"
        );
        assert_eq!(
            std::fs::read(dir.join("sheets/sheet-001.dxf")).expect("new"),
            b"new"
        );
        assert!(
            !dir.join("sheets/sheet-002.dxf").exists(),
            "stale lamella file"
        );
        assert_eq!(
            std::fs::read_to_string(dir.join("sheets/sheet-003.dxf")).expect("kept"),
            "edited"
        );
        assert_eq!(std::fs::read_dir(&root).expect("ls").count(), 1);
    }

    #[test]
    fn a_foreign_file_in_the_way_is_refused_and_nothing_moves() {
        let root = scratch("refuse");
        let dir = root.join("out");
        std::fs::create_dir_all(dir.join("sheets")).expect("dir");
        std::fs::write(dir.join("sheets/sheet-001.dxf"), "theirs").expect("foreign");
        std::fs::write(dir.join("notes.txt"), "mine").expect("foreign");
        let s = Staging::begin(&dir, &[]).expect("begin");
        s.write("sheets/sheet-001.dxf", b"ours").expect("write");
        let e = s.commit().expect_err("refused").to_string();
        assert!(
            e.contains("sheet-001.dxf") && e.contains("not written by lamella"),
            "{e}"
        );
        assert_eq!(
            std::fs::read_to_string(dir.join("sheets/sheet-001.dxf")).expect("kept"),
            "theirs"
        );
        assert_eq!(
            std::fs::read_to_string(dir.join("notes.txt")).expect("kept"),
            "mine"
        );
        assert!(!dir.join(MANIFEST).exists());
        // A foreign plan.json is refused before any work.
        std::fs::write(dir.join("plan.json"), "{\"mine\": 1}").expect("foreign");
        assert!(Staging::begin(&dir, &["plan.json"]).is_err());
        assert_eq!(
            std::fs::read_dir(&root).expect("ls").count(),
            1,
            "no staging left"
        );
    }

    #[test]
    fn a_name_lamella_does_not_write_is_not_staged() {
        let root = scratch("names");
        let s = Staging::begin(&root.join("out"), &[]).expect("begin");
        assert!(s.write("../victim.txt", b"x").is_err());
        assert!(s.write("notes.txt", b"x").is_err());
        drop(s);
        assert_eq!(std::fs::read_dir(&root).expect("ls").count(), 0);
    }

    /// Where no exchange is offered, the old kit sits beside DIR between
    /// the two renames; the next build puts it back.
    #[test]
    fn a_missing_dir_is_put_back_from_beside_it() {
        let root = scratch("aside");
        let dir = root.join("out");
        let s = Staging::begin(&dir, &[]).expect("begin");
        s.write("plan.json", b"old").expect("write");
        s.commit().expect("commit");
        std::fs::write(dir.join("notes.txt"), "mine").expect("foreign");
        // A killed build (process 1 is never gone: use an id no process has).
        let pid = u32::MAX - 7;
        let p = Paths::of(&root, "out", pid);
        std::fs::write(&p.journal, "x").expect("journal");
        std::fs::create_dir(&p.tmp).expect("staging");
        std::fs::write(p.tmp.join("plan.json"), "new").expect("staged");
        std::fs::write(
            p.tmp.join(MANIFEST),
            manifest::to_text(&Manifest::from([(
                "plan.json".to_string(),
                Entry {
                    bytes: 3,
                    crc32: crc32fast::hash(b"new"),
                },
            )])),
        )
        .expect("manifest");
        std::fs::rename(dir.join("notes.txt"), p.tmp.join("notes.txt")).expect("carried");
        std::fs::rename(&dir, &p.aside).expect("aside");
        recover_stale(&dir).expect("recover");
        assert_eq!(std::fs::read(dir.join("plan.json")).expect("old"), b"old");
        assert_eq!(std::fs::read(dir.join("notes.txt")).expect("kept"), b"mine");
        assert_eq!(std::fs::read_dir(&root).expect("ls").count(), 1);
    }
}
