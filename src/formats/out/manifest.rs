//! What lamella may touch in an output folder: the names it writes, the
//! manifest of what it wrote (`DIR/.lamella-manifest`) and whether a file
//! found there is still the one it wrote.
//!
//! The manifest is an input like any other file in DIR: it vouches for a
//! file only when the file has a name lamella writes
//! ([`is_lamella_name`]: `plan.json`, `takeoff.csv`, `takeoff.json`,
//! `setting-out.csv`, `assembly.pdf`, `flat.svg`, `sheets/sheet-NNN.dxf|svg`), is a regular
//! file reached without a symbolic link, and has the size and CRC-32 the
//! manifest recorded for it ([`vouched`]): a line naming anything else
//! (`../victim.txt`, an absolute path), and a file changed since lamella
//! wrote it, are the user's. Besides, a `plan.json` of schema
//! `lamella-plan/…` and a flat layout `flat.svg` say in their first lines
//! that lamella wrote them, and lamella may write over them
//! ([`replaceable`]); it removes a file only when the manifest vouches
//! for it.

use crate::error::{Error, Result};
use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The manifest of what lamella wrote into a folder.
pub const MANIFEST: &str = ".lamella-manifest";

/// The manifest's first line (the format: one file a line, its size in
/// bytes, its CRC-32 in hex and its path inside DIR).
const HEADER: &str = "# lamella manifest 2: bytes, CRC-32, path";

/// The folder the cutting sheets go to.
pub const SHEETS: &str = "sheets";

/// The folder the per-part cutting files go to.
pub const PARTS: &str = "parts";

/// The folder the frame model's files go to (`opensees.py`, `model.json`).
pub const STRUCTURE: &str = "structure";

/// The folders of a kit: lamella's files in them are replaced, other
/// files kept, like at the top.
pub const FOLDERS: [&str; 3] = [SHEETS, PARTS, STRUCTURE];

/// The files lamella writes at the top of an output folder.
pub const TOP_FILES: [&str; 8] = [
    "plan.json",
    "takeoff.csv",
    "takeoff.json",
    "setting-out.csv",
    "assembly.pdf",
    "flat.svg",
    "model.glb",
    "view.html",
];

/// The frame model's files lamella writes in [`STRUCTURE`] (with `lamella
/// frame` and `lamella build --loads`): the runnable OpenSeesPy script and
/// the plain JSON of the model.
pub const STRUCTURE_FILES: [&str; 2] = ["structure/opensees.py", "structure/model.json"];

/// Whether lamella writes files named `rel` (`/`-separated, inside DIR):
/// one of [`TOP_FILES`] or [`STRUCTURE_FILES`], `sheets/sheet-NNN.dxf|svg` or
/// `sheets/GROUP-sheet-NNN.dxf|svg` (three digits or more; a stock group's
/// name of letters, digits, `-`, `_` and `.`), `parts/parts.csv` or `parts/ID.dxf|svg` (an id of letters,
/// digits, `-`, `_` and `.`). Nothing else in DIR is ever lamella's to
/// replace or remove.
pub fn is_lamella_name(rel: &str) -> bool {
    if TOP_FILES.contains(&rel) || STRUCTURE_FILES.contains(&rel) {
        return true;
    }
    if let Some(file) = rel.strip_prefix("parts/") {
        // `parts.csv`, and a part's DXF and SVG: its id, with any
        // character but letters, digits, `-`, `_` and `.` as `_`.
        let stem = file
            .strip_suffix(".dxf")
            .or_else(|| file.strip_suffix(".svg"));
        return file == "parts.csv"
            || stem.is_some_and(|s| {
                !s.is_empty()
                    && !s.starts_with('.')
                    && s.bytes()
                        .all(|b| b.is_ascii_alphanumeric() || matches!(b, b'-' | b'_' | b'.'))
            });
    }
    let Some(file) = rel.strip_prefix("sheets/") else {
        return false;
    };
    let Some(stem) = file
        .strip_suffix(".dxf")
        .or_else(|| file.strip_suffix(".svg"))
    else {
        return false;
    };
    // `sheet-NNN`, or a stock group's `GROUP-sheet-NNN` (a group name of
    // letters, digits, `-`, `_` and `.`, not starting with `.`).
    let Some(at) = stem.rfind("sheet-") else {
        return false;
    };
    let (group, n) = (&stem[..at], &stem[at + "sheet-".len()..]);
    let group_ok = group.is_empty()
        || (group.len() > 1
            && group.ends_with('-')
            && !group.starts_with('.')
            && group
                .bytes()
                .all(|b| b.is_ascii_alphanumeric() || matches!(b, b'-' | b'_' | b'.')));
    group_ok && n.len() >= 3 && n.bytes().all(|b| b.is_ascii_digit())
}

/// What the manifest records of one file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Entry {
    /// Its size, bytes.
    pub bytes: u64,
    /// The CRC-32 of its bytes.
    pub crc32: u32,
}

/// The files of a manifest by their path inside DIR.
pub type Manifest = BTreeMap<String, Entry>;

/// The manifest's text: the header, then one line per file.
pub fn to_text(manifest: &Manifest) -> String {
    let mut s = format!("{HEADER}\n");
    for (rel, e) in manifest {
        s.push_str(&format!("{} {:08x} {rel}\n", e.bytes, e.crc32));
    }
    s
}

/// The entries of a manifest's text that can vouch for anything: lines of
/// size, CRC-32 and a name lamella writes. Any other line (an earlier
/// format's bare names, a path outside DIR) is ignored.
pub fn parse(text: &str) -> Manifest {
    let mut m = Manifest::new();
    for line in text.lines() {
        let mut fields = line.splitn(3, ' ');
        let (Some(bytes), Some(crc), Some(rel)) = (fields.next(), fields.next(), fields.next())
        else {
            continue;
        };
        let (Ok(bytes), Ok(crc32)) = (bytes.parse::<u64>(), u32::from_str_radix(crc, 16)) else {
            continue;
        };
        if crc.len() == 8 && is_lamella_name(rel) {
            m.insert(rel.to_string(), Entry { bytes, crc32 });
        }
    }
    m
}

/// The manifest in `dir`: empty when there is none, or when
/// `.lamella-manifest` is not a regular file (a link is not followed).
pub fn read(dir: &Path) -> Result<Manifest> {
    let p = dir.join(MANIFEST);
    match std::fs::symlink_metadata(&p) {
        Ok(meta) if meta.is_file() => {}
        Ok(_) => return Ok(Manifest::new()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Manifest::new()),
        Err(e) => return Err(Error::io(&p, e)),
    }
    let text = std::fs::read(&p).map_err(|e| Error::io(&p, e))?;
    Ok(parse(&String::from_utf8_lossy(&text)))
}

/// `dir/rel` when it is a regular file reached without a symbolic link
/// below `dir` (`sheets` a real folder), with its metadata.
pub fn regular_in(dir: &Path, rel: &str) -> Option<(PathBuf, std::fs::Metadata)> {
    let mut path = dir.to_path_buf();
    let mut parts = rel.split('/').peekable();
    while let Some(part) = parts.next() {
        if part.is_empty() || part == "." || part == ".." {
            return None;
        }
        path.push(part);
        let meta = std::fs::symlink_metadata(&path).ok()?;
        if parts.peek().is_some() {
            if !meta.is_dir() {
                return None;
            }
        } else if meta.is_file() {
            return Some((path, meta));
        }
    }
    None
}

/// Whether the manifest vouches for `dir/rel`: a name lamella writes, a
/// regular file (no link on the way), of the size and CRC-32 recorded.
/// Only such a file may lamella remove.
pub fn vouched(dir: &Path, rel: &str, manifest: &Manifest) -> bool {
    let Some(entry) = manifest.get(rel) else {
        return false;
    };
    if !is_lamella_name(rel) {
        return false;
    }
    let Some((path, meta)) = regular_in(dir, rel) else {
        return false;
    };
    meta.len() == entry.bytes && crc_of(&path, &meta).is_ok_and(|c| c == entry.crc32)
}

/// Whether lamella may write over `dir/rel`: the manifest vouches for it,
/// or it is a `plan.json` of schema `lamella-plan/…` or a lamella flat
/// layout `flat.svg` (by their first lines).
pub fn replaceable(dir: &Path, rel: &str, manifest: &Manifest) -> bool {
    // The first lines before the whole file's checksum.
    let says_so = regular_in(dir, rel).is_some_and(|(path, _)| match rel {
        "plan.json" => head(&path, 256).is_some_and(|h| is_plan_head(&h)),
        "flat.svg" => head(&path, 1024).is_some_and(|h| is_flat_svg_head(&h)),
        "model.glb" => head(&path, 256).is_some_and(|h| is_model_head(&h)),
        "view.html" => head(&path, 256).is_some_and(|h| is_view_head(&h)),
        "structure/opensees.py" => {
            head(&path, 256).is_some_and(|h| h.contains("\"\"\"A lamella frame model in OpenSees"))
        }
        "structure/model.json" => {
            head(&path, 64).is_some_and(|h| h.contains("\"$schema\": \"lamella-frame-model/"))
        }
        _ => false,
    });
    says_so || vouched(dir, rel, manifest)
}

/// Refuse to write `dir/name` for each of `names` that is there and is
/// not lamella's to replace: not a regular file (a link, a folder, a
/// device), or a file lamella did not write ([`replaceable`]). `sheets`
/// stands for the sheets' folder: it must be a real folder if it is there.
pub fn check_names(dir: &Path, names: &[&str]) -> Result<()> {
    if !dir.is_dir() {
        return Ok(());
    }
    let manifest = read(dir)?;
    for name in names {
        let p = dir.join(name);
        let Ok(meta) = std::fs::symlink_metadata(&p) else {
            continue;
        };
        if FOLDERS.contains(name) {
            if !meta.is_dir() {
                return Err(in_the_way(&p, &meta));
            }
        } else if !meta.is_file() {
            return Err(in_the_way(&p, &meta));
        } else if !replaceable(dir, name, &manifest) {
            return Err(foreign(&p));
        }
    }
    Ok(())
}

/// A file lamella did not write, where it would write one.
pub fn foreign(p: &Path) -> Error {
    Error::output(
        p,
        "exists and was not written by lamella: refusing to overwrite it (move it away or choose another --out)",
    )
}

/// Something other than a regular file (a link, a folder, a device) where
/// lamella would write a file, or other than a folder where it would
/// write its sheets.
pub fn in_the_way(p: &Path, meta: &std::fs::Metadata) -> Error {
    let what = if meta.file_type().is_symlink() {
        "is a symbolic link lamella did not make: refusing to write through it or replace it"
    } else if meta.is_dir() {
        "is a folder lamella did not make: refusing to replace it"
    } else if meta.is_file() {
        "is a file lamella did not write: refusing to replace it"
    } else {
        "is not a regular file (a device, FIFO or socket): lamella writes only to regular files or new paths"
    };
    Error::output(p, format!("{what} (move it away or choose another --out)"))
}

/// The first `n` bytes of `path` (fewer when shorter).
fn head(path: &Path, n: u64) -> Option<String> {
    let mut buf = Vec::new();
    std::fs::File::open(path)
        .ok()?
        .take(n)
        .read_to_end(&mut buf)
        .ok()?;
    Some(String::from_utf8_lossy(&buf).into_owned())
}

/// Whether a JSON text begins `{ "schema": "lamella-plan/` (any white
/// space between).
fn is_plan_head(text: &str) -> bool {
    let rest = text.trim_start();
    let Some(rest) = rest.strip_prefix('{') else {
        return false;
    };
    let Some(rest) = rest.trim_start().strip_prefix("\"schema\"") else {
        return false;
    };
    let Some(rest) = rest.trim_start().strip_prefix(':') else {
        return false;
    };
    rest.trim_start().starts_with("\"lamella-plan/")
}

/// Whether an SVG text begins as lamella's flat layout does: the XML
/// declaration, the `svg` element, then a title `… — flat assembly layout
/// (…), mm`.
fn is_flat_svg_head(text: &str) -> bool {
    let mut lines = text.lines();
    lines
        .next()
        .is_some_and(|l| l.starts_with("<?xml version=\"1.0\""))
        && lines
            .next()
            .is_some_and(|l| l.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""))
        && lines.next().is_some_and(|l| {
            l.starts_with("<title>")
                && l.contains(" — flat assembly layout (")
                && l.ends_with("), mm</title>")
        })
}

/// Whether a GLB begins as lamella's model does: the magic `glTF`, and
/// the JSON chunk's asset first, generator `lamella …`.
fn is_model_head(text: &str) -> bool {
    text.starts_with("glTF") && text.contains("\"generator\":\"lamella ")
}

/// Whether an HTML page begins as lamella's view does: the doctype, then
/// the marker comment.
fn is_view_head(text: &str) -> bool {
    let mut lines = text.lines();
    lines.next() == Some("<!DOCTYPE html>")
        && lines.next() == Some("<!-- lamella view: a 3D model of a grid -->")
}

/// A file's identity while it is unchanged: device, inode, size and the
/// modification and change times (size and modification time elsewhere).
type Identity = (u64, u64, u64, i64, i64, i64, i64);

fn identity(meta: &std::fs::Metadata) -> Identity {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        (
            meta.dev(),
            meta.ino(),
            meta.size(),
            meta.mtime(),
            meta.mtime_nsec(),
            meta.ctime(),
            meta.ctime_nsec(),
        )
    }
    #[cfg(not(unix))]
    {
        let t = meta
            .modified()
            .ok()
            .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
            .unwrap_or_default();
        (
            0,
            0,
            meta.len(),
            t.as_secs() as i64,
            t.subsec_nanos() as i64,
            0,
            0,
        )
    }
}

/// CRC-32s computed in this process, by the identity of the file read: the
/// check before the work and the commit read each earlier file once. (A
/// file rewritten in place, to the same size, within one tick of the file
/// system's clock after it was read would pass for unchanged: in one
/// build, between its check and its commit.)
static CRCS: Mutex<BTreeMap<Identity, u32>> = Mutex::new(BTreeMap::new());

/// The CRC-32 of the file at `path` (whose metadata is `meta`).
pub fn crc_of(path: &Path, meta: &std::fs::Metadata) -> std::io::Result<u32> {
    let id = identity(meta);
    if let Some(c) = CRCS.lock().ok().and_then(|m| m.get(&id).copied()) {
        return Ok(c);
    }
    let mut f = std::fs::File::open(path)?;
    let mut hasher = crc32fast::Hasher::new();
    let mut buf = vec![0u8; 1 << 20];
    loop {
        let n = f.read(&mut buf)?;
        if n == 0 {
            break;
        }
        hasher.update(&buf[..n]);
    }
    let c = hasher.finalize();
    if let Ok(mut m) = CRCS.lock() {
        m.insert(id, c);
    }
    Ok(c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_model_and_a_view_are_known_by_their_first_bytes() {
        assert!(is_model_head(
            "glTF\u{2}\0\0\0xxxxyyyyJSON{\"asset\":{\"generator\":\"lamella 0.1.0\""
        ));
        assert!(!is_model_head(
            "glTF....{\"asset\":{\"generator\":\"Blender\""
        ));
        assert!(!is_model_head("{\"generator\":\"lamella 0.1.0\""));
        assert!(is_view_head(
            "<!DOCTYPE html>\n<!-- lamella view: a 3D model of a grid -->\n<html>"
        ));
        assert!(!is_view_head("<!DOCTYPE html>\n<html>"));
    }

    #[test]
    fn only_the_names_lamella_writes() {
        for ok in [
            "plan.json",
            "takeoff.csv",
            "takeoff.json",
            "assembly.pdf",
            "flat.svg",
            "model.glb",
            "view.html",
            "sheets/sheet-001.dxf",
            "sheets/sheet-1234.svg",
        ] {
            assert!(is_lamella_name(ok), "{ok}");
        }
        for no in [
            "../victim.txt",
            "/etc/passwd",
            "sheets/../plan.json",
            "sheets/sheet-01.dxf",
            "sheets/sheet-001.dxf.bak",
            "sheets/sheet-0a1.svg",
            "sheets/extra.dxf",
            "sheets/sub/sheet-001.dxf",
            "notes.txt",
            "./plan.json",
            "plan.json/",
            MANIFEST,
            "",
        ] {
            assert!(!is_lamella_name(no), "{no}");
        }
    }

    #[test]
    fn the_manifest_vouches_only_for_lamella_names_by_size_and_crc() {
        let text = "# lamella manifest 2: bytes, CRC-32, path\n\
                    3 352441c2 plan.json\n\
                    3 352441c2 ../victim.txt\n\
                    3 352441c2 /tmp/victim.txt\n\
                    3 352441c2 sheets/../../victim.txt\n\
                    takeoff.csv\n\
                    x 352441c2 takeoff.json\n\
                    3 3524 assembly.pdf\n";
        let m = parse(text);
        assert_eq!(m.keys().collect::<Vec<_>>(), ["plan.json"]);
        assert_eq!(parse(&to_text(&m)), m);
        let dir = std::env::temp_dir().join(format!("lamella-manifest-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("plan.json"), "abc").unwrap();
        assert_eq!(crc32fast::hash(b"abc"), 0x3524_41c2);
        assert!(vouched(&dir, "plan.json", &m));
        // Changed since (same size): the user's. (Written aside and
        // renamed: a file rewritten in place within one tick of the file
        // system's clock would look unchanged to this process's cache.)
        std::fs::write(dir.join("new"), "abd").unwrap();
        std::fs::rename(dir.join("new"), dir.join("plan.json")).unwrap();
        assert!(!vouched(&dir, "plan.json", &m));
        assert!(!replaceable(&dir, "plan.json", &m));
        // Lamella's plan by its schema: may be replaced, not removed.
        std::fs::write(
            dir.join("plan.json"),
            "{\n  \"schema\": \"lamella-plan/3\",\n  \"x\": 1}",
        )
        .unwrap();
        assert!(replaceable(&dir, "plan.json", &m));
        assert!(!vouched(&dir, "plan.json", &m));
        std::fs::write(
            dir.join("plan.json"),
            "{\"x\": \"schema\": \"lamella-plan/3\"}",
        )
        .unwrap();
        assert!(!replaceable(&dir, "plan.json", &m));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_file_through_a_link_is_never_vouched() {
        let dir =
            std::env::temp_dir().join(format!("lamella-manifest-link-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("elsewhere")).unwrap();
        std::fs::write(dir.join("elsewhere/sheet-001.dxf"), "abc").unwrap();
        let kit = dir.join("kit");
        std::fs::create_dir_all(&kit).unwrap();
        #[cfg(unix)]
        std::os::unix::fs::symlink("../elsewhere", kit.join("sheets")).unwrap();
        let m = parse("3 352441c2 sheets/sheet-001.dxf\n");
        assert!(!vouched(&kit, "sheets/sheet-001.dxf", &m));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
