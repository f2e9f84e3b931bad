//! Trace spec files (`X.trace.yaml`) into a [`TraceSpec`].

use crate::error::{Error, Location, Result};
use crate::spec::TraceSpec;
use std::path::Path;

/// Read a trace spec (one-line errors with line and column).
pub fn load(path: &Path) -> Result<TraceSpec> {
    if !path.exists() {
        return Err(Error::input(path, Location::File, "no such file"));
    }
    let text = super::read_text(path)?;
    if text.trim().is_empty() {
        return Err(Error::input(path, Location::File, "the file is empty"));
    }
    super::yaml_guard::check(&text, path)?;
    serde_yaml::from_str(&text).map_err(|e| {
        let (at, msg) = crate::error::yaml_error_parts(&e);
        Error::input(path, at, msg)
    })
}
