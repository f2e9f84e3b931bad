//! The one way lamella writes files: a kit's folder is staged beside the
//! output and moved into place once complete ([`staging`]); a single file
//! (a command's plan.json, flat.svg, a traced network) is written beside
//! its target and renamed over it ([`write_atomic`]); either way the bytes
//! go through [`direct::write_file`] (big files past the page cache).

pub mod direct;
pub mod staging;

use crate::error::{Error, Result};
use std::path::Path;

/// Write `contents` to `path` atomically: a temporary file beside it, then a
/// rename, so a failure never leaves half a file.
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
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = dir.join(format!(".{name}.lamella-tmp"));
    direct::write_file(&tmp, contents).map_err(|e| Error::io(&tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        Error::io(path, e)
    })
}
