//! File formats, kept apart from the working types: network files (YAML,
//! JSON, OBJ, DXF) in, plan.json out. Each reader returns a [`RawNetwork`]
//! in file units; [`read_network`] validates it into a [`Network`] in mm.

pub mod dxf;
pub mod loads_file;
pub mod mesh;
pub mod network_file;
pub mod obj;
pub mod profile_file;
pub mod trace_spec;
pub mod yaml_guard;

use crate::error::{Error, Location, Result};
use crate::network::{Network, RawNetwork, Unit};
use std::path::Path;

/// Options of the read stage.
#[derive(Debug, Clone, Copy, Default)]
pub struct ReadOptions {
    /// Unit for formats that carry none (OBJ, unitless DXF), or to override
    /// a DXF's `$INSUNITS`. Network files always say their unit.
    pub unit: Option<Unit>,
    /// Replace the file's node tolerance (mm).
    pub tolerance_mm: Option<f64>,
    /// Replace the coordinate precision implied by the file's decimals (mm).
    pub precision_mm: Option<f64>,
}

/// Read and validate a network file; the format follows the extension
/// (`.yaml`/`.yml`, `.json`, `.obj`, `.dxf`).
pub fn read_network(path: &Path, opts: ReadOptions) -> Result<Network> {
    let raw = read_raw(path, opts)?;
    let mut net = Network::new(raw, path)?;
    if let Some(t) = opts.tolerance_mm {
        if !(t.is_finite() && t > 0.0 && t <= crate::network::MAX_TOLERANCE_MM) {
            return Err(Error::input(
                path,
                Location::Field("tolerance".into()),
                format!(
                    "tolerance must be positive and at most {} mm",
                    crate::network::MAX_TOLERANCE_MM
                ),
            ));
        }
        net.tolerance_mm = t;
    }
    if let Some(p) = opts.precision_mm {
        net.precision_mm = p;
    }
    Ok(net)
}

/// Read a network file into its raw form, in file units.
pub fn read_raw(path: &Path, opts: ReadOptions) -> Result<RawNetwork> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    if !path.exists() {
        return Err(Error::input(path, Location::File, "no such file"));
    }
    match ext.as_str() {
        "yaml" | "yml" => {
            let text = read_text_limited(path, yaml_guard::MAX_NETWORK_FILE_BYTES)?;
            network_file::parse(&text, network_file::Syntax::Yaml, path)
        }
        "json" => {
            let text = read_text_limited(path, yaml_guard::MAX_NETWORK_FILE_BYTES)?;
            network_file::parse(&text, network_file::Syntax::Json, path)
        }
        "obj" => {
            let text = read_text_limited(path, yaml_guard::MAX_NETWORK_FILE_BYTES)?;
            obj::parse(&text, opts.unit.unwrap_or(crate::network::Unit::Mm), path)
        }
        "dxf" => dxf::read(path, opts.unit),
        _ => Err(Error::input(
            path,
            Location::File,
            format!("unknown network format '.{ext}' (use .yaml, .yml, .json, .obj or .dxf)"),
        )),
    }
}

/// A network's default name: the file stem (`samples/x.yaml` → `x`).
pub fn default_name(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "network".into())
}

/// Read a whole text file (a trace spec or a profile: at most
/// [`yaml_guard::MAX_SMALL_FILE_BYTES`]), with a one-line error on failure or
/// bad UTF-8; a leading UTF-8 byte-order mark is dropped.
pub fn read_text(path: &Path) -> Result<String> {
    read_text_limited(path, yaml_guard::MAX_SMALL_FILE_BYTES)
}

/// [`read_text`] with a size limit in bytes.
pub fn read_text_limited(path: &Path, max_bytes: u64) -> Result<String> {
    let mut bytes = read_limited(path, max_bytes, "such a file")?;
    if bytes.starts_with(b"\xEF\xBB\xBF") {
        bytes.drain(..3);
    }
    String::from_utf8(bytes).map_err(|e| {
        Error::input(
            path,
            Location::File,
            format!("not UTF-8 text (byte {})", e.utf8_error().valid_up_to()),
        )
    })
}

/// A file's bytes, at most `max_bytes` of them: a larger file is refused
/// (`what` names the kind of file in the message). The size the file system
/// reports is checked first, and the read itself stops one byte past the
/// limit, so a device or a pipe behind the name (`/dev/zero`) is refused
/// too instead of being read until memory runs out.
pub fn read_limited(path: &Path, max_bytes: u64, what: &str) -> Result<Vec<u8>> {
    use std::io::Read;
    let too_big = |len: String| {
        Error::input(
            path,
            Location::File,
            format!(
                "{len} is more than the {} MiB lamella reads in {what}",
                max_bytes >> 20
            ),
        )
    };
    let len = std::fs::metadata(path)
        .map_err(|e| Error::io(path, e))?
        .len();
    if len > max_bytes {
        return Err(too_big(format!("{len} bytes")));
    }
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let mut bytes = Vec::with_capacity(len as usize);
    file.take(max_bytes + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| Error::io(path, e))?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_big(format!("a stream of over {max_bytes} bytes")));
    }
    Ok(bytes)
}

/// Whether two paths name the same existing file: the same canonical path,
/// or (on Unix) the same device and inode, so hard links count too.
pub fn same_file(a: &Path, b: &Path) -> bool {
    let (Ok(ca), Ok(cb)) = (a.canonicalize(), b.canonicalize()) else {
        return false;
    };
    if ca == cb {
        return true;
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(ma), Ok(mb)) = (std::fs::metadata(&ca), std::fs::metadata(&cb)) {
            return ma.dev() == mb.dev() && ma.ino() == mb.ino();
        }
    }
    false
}
