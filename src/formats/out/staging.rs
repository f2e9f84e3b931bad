//! Safe output directories: everything is written into a staging folder
//! beside the output directory and moved into place only once complete, so
//! an interrupted or failed build leaves earlier output as it was.
//!
//! Rules:
//! * lamella records what it wrote in `DIR/.lamella-manifest`; a
//!   `plan.json` of schema `lamella-plan/…` (from `nodes`, `check`,
//!   `parts`, `nest`) is also lamella's;
//! * a DIR that holds only lamella's files is swapped whole: DIR is renamed
//!   aside, the staging folder renamed to DIR, the old one removed;
//! * a DIR that also holds other files keeps them: lamella's files are
//!   replaced one by one (each rename atomic), lamella files of the last
//!   build that this one does not make are removed, nothing else is
//!   touched; a file lamella would write whose name is taken by a foreign
//!   file stops the build before anything is moved (an error naming it);
//! * a staging folder left by a killed build (`.NAME.lamella-build-PID`,
//!   marked inside) is removed by the next build into the same DIR once
//!   its process is gone.

use crate::error::{Error, Result};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The manifest of what lamella wrote, relative paths one per line.
pub const MANIFEST: &str = ".lamella-manifest";

/// The marker inside a staging folder (holds the process id).
const MARKER: &str = ".lamella-staging";

/// Test hook: sleep this many milliseconds once everything is staged,
/// before anything is moved (so a test can kill the build there).
pub const PAUSE_ENV: &str = "LAMELLA_PAUSE_BEFORE_COMMIT_MS";

/// A build's output being staged.
#[derive(Debug)]
pub struct Staging {
    dir: PathBuf,
    tmp: PathBuf,
    files: Mutex<BTreeSet<String>>,
    committed: bool,
}

impl Staging {
    /// Start staging output for `dir`. Refuses a `dir` that is a file, and
    /// one where a file named in `fixed_names` exists but is not lamella's.
    pub fn begin(dir: &Path, fixed_names: &[&str]) -> Result<Staging> {
        if dir.exists() && !dir.is_dir() {
            return Err(Error::output(
                dir,
                "is a file, not a directory: choose another output directory",
            ));
        }
        if dir.is_dir() {
            let ours = manifest(dir)?;
            for name in fixed_names {
                let p = dir.join(name);
                if p.exists() && !is_lamellas(dir, name, &ours) {
                    return Err(foreign_err(&p));
                }
            }
        }
        let name = dir
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "out".into());
        let parent = match dir.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        std::fs::create_dir_all(&parent).map_err(|e| Error::io(&parent, e))?;
        remove_stale(&parent, &name);
        let tmp = parent.join(format!(".{name}.lamella-build-{}", std::process::id()));
        if tmp.exists() {
            std::fs::remove_dir_all(&tmp).map_err(|e| Error::io(&tmp, e))?;
        }
        std::fs::create_dir_all(&tmp).map_err(|e| Error::io(&tmp, e))?;
        std::fs::write(tmp.join(MARKER), std::process::id().to_string())
            .map_err(|e| Error::io(&tmp, e))?;
        Ok(Staging {
            dir: dir.to_path_buf(),
            tmp,
            files: Mutex::new(BTreeSet::new()),
            committed: false,
        })
    }

    /// The staging folder.
    pub fn staging_dir(&self) -> &Path {
        &self.tmp
    }

    /// Stage `rel` (a `/`-separated path inside DIR) with `bytes`.
    pub fn write(&self, rel: &str, bytes: &[u8]) -> Result<()> {
        let path = self.tmp.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(|e| Error::io(parent, e))?;
        }
        super::direct::write_file(&path, bytes).map_err(|e| Error::io(&self.dir.join(rel), e))?;
        self.files
            .lock()
            .map_err(|_| Error::output(&self.dir, "a writer thread failed"))?
            .insert(rel.to_string());
        Ok(())
    }

    /// Stage `rel` with what `write` streams into it (buffered, or past
    /// the page cache: [`super::direct`]).
    pub fn write_with(
        &self,
        rel: &str,
        write: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
    ) -> Result<()> {
        let path = self.tmp.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(|e| Error::io(parent, e))?;
        }
        let mut w =
            super::direct::Writer::create(&path).map_err(|e| Error::io(&self.dir.join(rel), e))?;
        write(&mut w)
            .and_then(|()| w.finish())
            .map_err(|e| Error::io(&self.dir.join(rel), e))?;
        self.files
            .lock()
            .map_err(|_| Error::output(&self.dir, "a writer thread failed"))?
            .insert(rel.to_string());
        Ok(())
    }

    /// Move the staged files into DIR (see the module doc).
    pub fn commit(mut self) -> Result<()> {
        if let Some(ms) = std::env::var(PAUSE_ENV)
            .ok()
            .and_then(|v| v.parse::<u64>().ok())
        {
            std::thread::sleep(std::time::Duration::from_millis(ms));
        }
        let files: BTreeSet<String> = std::mem::take(
            &mut *self
                .files
                .lock()
                .map_err(|_| Error::output(&self.dir, "a writer thread failed"))?,
        );
        let list: String = files.iter().map(|f| format!("{f}\n")).collect();
        std::fs::write(self.tmp.join(MANIFEST), list).map_err(|e| Error::io(&self.tmp, e))?;
        std::fs::remove_file(self.tmp.join(MARKER)).map_err(|e| Error::io(&self.tmp, e))?;
        if !self.dir.exists() {
            std::fs::rename(&self.tmp, &self.dir).map_err(|e| Error::io(&self.dir, e))?;
            self.committed = true;
            return Ok(());
        }
        let old = manifest(&self.dir)?;
        let present = files_under(&self.dir)?;
        let foreign: Vec<&String> = present
            .iter()
            .filter(|f| f.as_str() != MANIFEST && !is_lamellas(&self.dir, f, &old))
            .collect();
        if let Some(f) = foreign.iter().find(|f| files.contains(f.as_str())) {
            return Err(foreign_err(&self.dir.join(f)));
        }
        if foreign.is_empty() {
            // Only lamella's files: swap the whole folder.
            let aside = self.tmp.with_file_name(format!(
                "{}-old",
                self.tmp
                    .file_name()
                    .map_or(String::new(), |n| n.to_string_lossy().into_owned())
            ));
            std::fs::rename(&self.dir, &aside).map_err(|e| Error::io(&self.dir, e))?;
            std::fs::rename(&self.tmp, &self.dir).map_err(|e| Error::io(&self.dir, e))?;
            self.committed = true;
            std::fs::remove_dir_all(&aside).map_err(|e| Error::io(&aside, e))?;
            return Ok(());
        }
        // Foreign files stay: replace lamella's files one by one.
        for f in &files {
            let to = self.dir.join(f);
            if let Some(parent) = to.parent() {
                std::fs::create_dir_all(parent).map_err(|e| Error::io(parent, e))?;
            }
            std::fs::rename(self.tmp.join(f), &to).map_err(|e| Error::io(&to, e))?;
        }
        for f in old.difference(&files) {
            let p = self.dir.join(f);
            if p.is_file() {
                std::fs::remove_file(&p).map_err(|e| Error::io(&p, e))?;
            }
        }
        let m = self.dir.join(MANIFEST);
        std::fs::rename(self.tmp.join(MANIFEST), &m).map_err(|e| Error::io(&m, e))?;
        self.committed = true;
        std::fs::remove_dir_all(&self.tmp).map_err(|e| Error::io(&self.tmp, e))?;
        Ok(())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.committed {
            // Only ever lamella's own staging folder.
            let _ = std::fs::remove_dir_all(&self.tmp);
        }
    }
}

/// The files lamella's manifest in `dir` lists.
fn manifest(dir: &Path) -> Result<BTreeSet<String>> {
    let m = dir.join(MANIFEST);
    match std::fs::read_to_string(&m) {
        Ok(text) => Ok(text
            .lines()
            .filter(|l| !l.is_empty())
            .map(String::from)
            .collect()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(BTreeSet::new()),
        Err(e) => Err(Error::io(&m, e)),
    }
}

/// Whether `rel` in `dir` is lamella's: listed, or a lamella plan.json.
fn is_lamellas(dir: &Path, rel: &str, listed: &BTreeSet<String>) -> bool {
    if listed.contains(rel) {
        return true;
    }
    rel == "plan.json"
        && std::fs::read(dir.join(rel)).is_ok_and(|b| {
            let head = String::from_utf8_lossy(&b[..b.len().min(256)]).into_owned();
            head.contains("\"schema\": \"lamella-plan/")
        })
}

/// Every file under `dir`, as `/`-separated relative paths.
fn files_under(dir: &Path) -> Result<Vec<String>> {
    let mut out = Vec::new();
    let mut stack = vec![(dir.to_path_buf(), String::new())];
    while let Some((d, prefix)) = stack.pop() {
        for entry in std::fs::read_dir(&d).map_err(|e| Error::io(&d, e))? {
            let entry = entry.map_err(|e| Error::io(&d, e))?;
            let name = entry.file_name().to_string_lossy().into_owned();
            let rel = format!("{prefix}{name}");
            let ty = entry.file_type().map_err(|e| Error::io(&entry.path(), e))?;
            if ty.is_dir() {
                stack.push((entry.path(), format!("{rel}/")));
            } else {
                out.push(rel);
            }
        }
    }
    out.sort();
    Ok(out)
}

/// Remove staging folders of `name` left by builds that are gone.
fn remove_stale(parent: &Path, name: &str) {
    let prefix = format!(".{name}.lamella-build-");
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    for e in entries.flatten() {
        let file_name = e.file_name().to_string_lossy().into_owned();
        let Some(rest) = file_name.strip_prefix(&prefix) else {
            continue;
        };
        let pid = rest.trim_end_matches("-old");
        let Ok(pid) = pid.parse::<u32>() else {
            continue;
        };
        let path = e.path();
        // Only folders lamella marked (or the old half of a swap).
        let marked = path.join(MARKER).is_file() || rest.ends_with("-old");
        let alive = Path::new("/proc").is_dir() && Path::new(&format!("/proc/{pid}")).exists();
        if marked && !alive && pid != std::process::id() {
            let _ = std::fs::remove_dir_all(&path);
        }
    }
}

fn foreign_err(p: &Path) -> Error {
    Error::output(
        p,
        "exists and was not written by lamella: refusing to overwrite it (move it away or choose another --out)",
    )
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
            "plan.json\nsheets/sheet-001.dxf\n"
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
        s.commit().expect("commit");
        std::fs::write(dir.join("notes.txt"), "mine").expect("foreign");
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
    }

    #[test]
    fn a_foreign_file_in_the_way_is_refused_and_nothing_moves() {
        let root = scratch("refuse");
        let dir = root.join("out");
        std::fs::create_dir_all(dir.join("sheets")).expect("dir");
        std::fs::write(dir.join("sheets/sheet-001.dxf"), "theirs").expect("foreign");
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
}
