//! The kit as a strip-packing instance for sparrow (jagua-rs 0.7 JSON), as
//! [`crate::plan::sparrow`] makes it: pretty JSON.

use crate::plan::sparrow::Instance;

/// The instance as pretty JSON (no trailing newline).
pub fn to_json(instance: &Instance) -> Result<String, String> {
    serde_json::to_string_pretty(instance).map_err(|e| e.to_string())
}
