//! The one way lamella writes files: a kit's folder is staged beside the
//! output and moved into place once complete ([`staging`]); a single file
//! (a command's plan.json, flat.svg, a traced network) is written beside
//! its target and renamed over it ([`write_atomic`]); either way the bytes
//! go through [`direct::write_file`] (big files past the page cache).
//!
//! What lamella may write over or remove is decided in one place
//! ([`manifest`]). An output the user names (`--out`, `--export-instance`)
//! that is a symbolic link is followed: lamella writes where it points and
//! the link stays ([`output_dir`], [`output_file`]). A path lamella
//! writes is a regular file or a new path, never a device, a FIFO, a
//! folder or a link it would replace.

pub mod direct;
pub mod manifest;
pub mod staging;

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// Where an output the user named goes: the path itself, or, when it is a
/// symbolic link, the path it points to (followed, never replaced).
fn follow(path: &Path) -> Result<PathBuf> {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => path.canonicalize().map_err(|_| {
            Error::output(
                path,
                "is a symbolic link to a path that does not exist: refusing to follow it",
            )
        }),
        _ => Ok(path.to_path_buf()),
    }
}

/// The folder to write for `--out DIR`: DIR, or where it points when it
/// is a link. Refuses a DIR that is there and is not a folder.
pub fn output_dir(dir: &Path) -> Result<PathBuf> {
    let real = follow(dir)?;
    if real.exists() && !real.is_dir() {
        return Err(Error::output(
            dir,
            "is a file, not a directory: choose another output directory",
        ));
    }
    Ok(real)
}

/// The file to write for an output file the user named: the path, or
/// where it points when it is a link. Refuses a folder, a device, a FIFO
/// or a socket: lamella writes only regular files or new paths.
pub fn output_file(path: &Path) -> Result<PathBuf> {
    let real = follow(path)?;
    match std::fs::symlink_metadata(&real) {
        Ok(m) if m.is_dir() => Err(Error::output(path, "is a directory: name a file to write")),
        Ok(m) if !m.is_file() => Err(Error::output(
            path,
            "is not a regular file (a device, FIFO or socket): lamella writes only to regular files or new paths; choose another path",
        )),
        _ => Ok(real),
    }
}

/// Write `contents` to `path` atomically: a temporary file beside it, then a
/// rename, so a failure never leaves half a file. `path` must be a regular
/// file or a new path (a link, a folder or a device there is refused, not
/// replaced).
pub fn write_atomic(path: &Path, contents: &[u8]) -> Result<()> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if dir.exists() && !dir.is_dir() {
        return Err(Error::io(
            dir,
            std::io::Error::other("is a file, not a directory: choose another output directory"),
        ));
    }
    if let Ok(meta) = std::fs::symlink_metadata(path) {
        if !meta.is_file() {
            return Err(manifest::in_the_way(path, &meta));
        }
    }
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = dir.join(format!(".{name}.lamella-tmp"));
    if let Ok(meta) = std::fs::symlink_metadata(&tmp) {
        if !meta.is_file() {
            return Err(manifest::in_the_way(&tmp, &meta));
        }
    }
    direct::write_file(&tmp, contents).map_err(|e| Error::io(&tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        Error::io(path, e)
    })
}
