//! The network file (README, "Input: the network"), as YAML or JSON (the same
//! fields).

use crate::error::{Error, Location, Result};
use crate::network::{Family, Network, RawCurve, RawNetwork, Unit};
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::Path;

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct NetworkFile {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    name: Option<String>,
    units: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    tolerance: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    precision: Option<f64>,
    /// Free-form metadata (e.g. the trace spec a network came from); ignored.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    meta: Option<serde_yaml::Value>,
    curves: Vec<CurveFile>,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct CurveFile {
    id: String,
    family: String,
    points: Vec<[f64; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    normals: Option<Vec<[f64; 3]>>,
}

/// Which text syntax a network file uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Syntax {
    /// YAML (`.yaml`, `.yml`).
    Yaml,
    /// JSON (`.json`).
    Json,
}

/// Parse network file text (YAML or JSON) into a raw network.
pub fn parse(text: &str, syntax: Syntax, path: &Path) -> Result<RawNetwork> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if text.trim().is_empty() {
        return Err(Error::input(path, Location::File, "the file is empty"));
    }
    if syntax == Syntax::Yaml {
        crate::formats::read::yaml_guard::check(text, path)?;
    }
    let file: NetworkFile = match syntax {
        Syntax::Yaml => serde_yaml::from_str(text).map_err(|e| {
            let (at, msg) = crate::error::yaml_error_parts(&e);
            Error::input(path, at, format!("invalid YAML: {msg}"))
        })?,
        Syntax::Json => serde_json::from_str(text).map_err(|e| {
            Error::input(
                path,
                Location::LineColumn {
                    line: e.line(),
                    column: e.column(),
                },
                format!(
                    "invalid JSON: {}",
                    crate::error::strip_serde_location(&e.to_string())
                ),
            )
        })?,
    };
    let unit = Unit::parse(&file.units).ok_or_else(|| {
        Error::input(
            path,
            Location::Field("units".into()),
            format!("unknown unit '{}' (use mm, cm, m, in or ft)", file.units),
        )
    })?;
    let mut curves = Vec::with_capacity(file.curves.len());
    for (index, c) in file.curves.into_iter().enumerate() {
        let family = Family::parse(&c.family).ok_or_else(|| {
            let at = if c.id.is_empty() {
                Location::Field(format!("curves[{index}].family"))
            } else {
                Location::Curve(c.id.clone())
            };
            Error::input(
                path,
                at,
                format!("unknown family '{}' (use A, B or edge)", c.family),
            )
        })?;
        curves.push(RawCurve {
            id: c.id,
            family,
            points: c.points.into_iter().map(DVec3::from_array).collect(),
            normals: c
                .normals
                .map(|n| n.into_iter().map(DVec3::from_array).collect()),
        });
    }
    let name = file
        .name
        .unwrap_or_else(|| crate::formats::read::default_name(path));
    Ok(RawNetwork {
        name,
        unit,
        tolerance: file.tolerance,
        precision: file.precision,
        curves,
    })
}

/// Digits after the point of a declared precision.
const PRECISION_DECIMALS: usize = 6;

/// Write a network as YAML in the file format, coordinates with `decimals`
/// digits after the point, in the network's own unit. Deterministic.
pub fn to_yaml(net: &RawNetwork, decimals: usize, meta_comment: &str) -> String {
    let mut out = String::with_capacity(net.curves.iter().map(|c| c.points.len() * 40).sum());
    for line in meta_comment.lines() {
        let _ = writeln!(out, "# {line}");
    }
    let _ = writeln!(out, "name: {}", yaml_str(&net.name));
    let _ = writeln!(out, "units: {}", net.unit.as_str());
    if let Some(t) = net.tolerance {
        let _ = writeln!(out, "tolerance: {}", fmt_num(t, decimals));
    }
    if let Some(p) = net.precision {
        let _ = writeln!(out, "precision: {}", fmt_num(p, PRECISION_DECIMALS));
    }
    out.push_str("curves:\n");
    for c in &net.curves {
        let _ = writeln!(out, "  - id: {}", yaml_str(&c.id));
        let _ = writeln!(out, "    family: {}", c.family.as_str());
        out.push_str("    points:\n");
        write_yaml_triples(&mut out, &c.points, decimals);
        if let Some(ns) = &c.normals {
            out.push_str("    normals:\n");
            write_yaml_triples(&mut out, ns, 7);
        }
    }
    out
}

/// Write a network as JSON in the file format (compact, deterministic).
pub fn to_json(net: &RawNetwork, decimals: usize) -> String {
    let mut out = String::with_capacity(net.curves.iter().map(|c| c.points.len() * 40).sum());
    let _ = write!(
        out,
        "{{\"name\":{},\"units\":\"{}\"",
        serde_json::Value::String(net.name.clone()),
        net.unit.as_str()
    );
    if let Some(t) = net.tolerance {
        let _ = write!(out, ",\"tolerance\":{}", fmt_num(t, decimals));
    }
    if let Some(p) = net.precision {
        let _ = write!(out, ",\"precision\":{}", fmt_num(p, PRECISION_DECIMALS));
    }
    out.push_str(",\"curves\":[");
    for (i, c) in net.curves.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        let _ = write!(
            out,
            "\n{{\"id\":{},\"family\":\"{}\",\"points\":[",
            serde_json::Value::String(c.id.clone()),
            c.family.as_str()
        );
        write_triples(&mut out, &c.points, decimals);
        out.push(']');
        if let Some(ns) = &c.normals {
            out.push_str(",\"normals\":[");
            write_triples(&mut out, ns, 7);
            out.push(']');
        }
        out.push('}');
    }
    out.push_str("]}\n");
    out
}

/// The coordinates of `p` by [`fmt_num`].
fn fmt_xyz(p: DVec3, decimals: usize) -> [String; 3] {
    p.to_array().map(|x| fmt_num(x, decimals))
}

/// Each of `v` as a YAML list item `      - [x, y, z]` on its own line.
fn write_yaml_triples(out: &mut String, v: &[DVec3], decimals: usize) {
    for &p in v {
        let [x, y, z] = fmt_xyz(p, decimals);
        let _ = writeln!(out, "      - [{x}, {y}, {z}]");
    }
}

/// `v` as JSON arrays `[x,y,z]`, comma-separated.
fn write_triples(out: &mut String, v: &[DVec3], decimals: usize) {
    for (k, &p) in v.iter().enumerate() {
        if k > 0 {
            out.push(',');
        }
        let [x, y, z] = fmt_xyz(p, decimals);
        let _ = write!(out, "[{x},{y},{z}]");
    }
}

/// Fixed-precision number without a negative zero.
pub fn fmt_num(x: f64, decimals: usize) -> String {
    let s = format!("{x:.decimals$}");
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        s.trim_start_matches('-').to_string()
    } else {
        s
    }
}

fn yaml_str(s: &str) -> String {
    if !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_' || c == '.')
        && !s
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_digit() || c == '-' || c == '.')
    {
        s.to_string()
    } else {
        serde_json::Value::String(s.to_string()).to_string()
    }
}

/// Convert a validated network back to a raw one in mm (for writing).
pub fn raw_from_network(net: &Network) -> RawNetwork {
    RawNetwork {
        name: net.name.clone(),
        unit: Unit::Mm,
        tolerance: Some(net.tolerance_mm),
        precision: None,
        curves: net
            .curves
            .iter()
            .map(|c| RawCurve {
                id: c.id.clone(),
                family: c.family,
                points: c.points_world_mm.clone(),
                normals: c.normals_world.clone(),
            })
            .collect(),
    }
}
