//! The trace spec (YAML): which surface, its scale and placement, the seed,
//! the spacing, the clip and the sampling of a network to trace.

use crate::error::{Error, Location, Result};
use serde::Deserialize;
use std::path::Path;

/// Read a trace spec (one-line errors with line and column).
pub fn load(path: &Path) -> Result<TraceSpec> {
    if !path.exists() {
        return Err(Error::input(path, Location::File, "no such file"));
    }
    let text = crate::io::read_text(path)?;
    if text.trim().is_empty() {
        return Err(Error::input(path, Location::File, "the file is empty"));
    }
    crate::io::yaml_guard::check(&text, path)?;
    serde_yaml::from_str(&text).map_err(|e| {
        let (at, msg) = crate::error::yaml_error_parts(&e);
        Error::input(path, at, msg)
    })
}

#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TraceSpec {
    /// Network name (default: the spec's file stem).
    #[serde(default)]
    pub name: Option<String>,
    pub surface: SurfaceName,
    /// The surface's shape parameter c (catenoid, helicoid, hypar), surface units.
    #[serde(default = "one")]
    pub c: f64,
    /// mm per surface unit.
    pub scale_mm: f64,
    #[serde(default)]
    pub placement: Placement,
    /// Seed point (u, v) in the surface's parameters.
    pub seed: [f64; 2],
    /// Target spacing between neighbouring curves of a family, mm.
    pub spacing_mm: f64,
    #[serde(default)]
    pub net: Net,
    #[serde(default)]
    pub design: Design,
    /// Most curves per family on each side of the seed.
    #[serde(default = "default_max_curves")]
    pub max_curves_per_side: usize,
    #[serde(default)]
    pub clip: Option<ClipFile>,
    /// Trace on the fundamental patch and unfold across its edges by the
    /// surface's symmetries (Schwarz D).
    #[serde(default)]
    pub periodic: bool,
    /// Periodic designs: after the central curves, seed more curves where a
    /// family leaves gaps wider than ¾ of the spacing.
    #[serde(default)]
    pub fill: bool,
    #[serde(default)]
    pub sampling: SamplingSpec,
}

fn one() -> f64 {
    1.0
}
fn default_max_curves() -> usize {
    200
}

#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum SurfaceName {
    Enneper,
    Catenoid,
    Helicoid,
    Scherk,
    SchwarzD,
    Hypar,
}

#[derive(Debug, Clone, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct Placement {
    /// Rotations about x, then y, then z, degrees.
    #[serde(default)]
    pub rotate_deg: [f64; 3],
    #[serde(default)]
    pub translate_mm: [f64; 3],
}

#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum Net {
    /// The two asymptotic families (the strips).
    #[default]
    Asymptotic,
    /// The two principal curvature families (the façade web).
    Principal,
}

#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum Design {
    /// Curves seeded at the spacing along the two curves through the seed.
    #[default]
    Central,
    /// Alternating: each new curve seeded at the spacing along the previous
    /// curve of the other family, from their last crossing, so the cells
    /// along the diagonals stay square.
    Alternating,
}

/// A clip: what part of the surface to keep.
#[derive(Debug, Clone, PartialEq)]
pub enum ClipSpec {
    /// Keep what lies inside an axis-aligned box, mm.
    Box { min_mm: [f64; 3], max_mm: [f64; 3] },
    /// Keep the side of the plane opposite its normal.
    Plane {
        point_mm: [f64; 3],
        normal: [f64; 3],
    },
    /// Keep what lies inside a polygon in plan (x, y), optionally between two heights.
    Polygon {
        points_mm: Vec<[f64; 2]>,
        z_min_mm: Option<f64>,
        z_max_mm: Option<f64>,
    },
    /// Keep what lies inside a polygon in the parameter plane (u, v).
    Parameters { polygon: Vec<[f64; 2]> },
    /// Keep what lies inside a block (a box turned about x, then y, then z
    /// about its centre).
    Block {
        center_mm: [f64; 3],
        size_mm: [f64; 3],
        rotate_deg: [f64; 3],
    },
}

/// The clip as written: exactly one of its keys.
#[derive(Debug, Clone, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct ClipFile {
    #[serde(rename = "box", default)]
    pub box_: Option<BoxClip>,
    #[serde(default)]
    pub plane: Option<PlaneClip>,
    #[serde(default)]
    pub polygon: Option<PolygonClip>,
    #[serde(default)]
    pub parameters: Option<ParameterClip>,
    #[serde(default)]
    pub block: Option<BlockClip>,
}

#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BlockClip {
    pub center_mm: [f64; 3],
    pub size_mm: [f64; 3],
    #[serde(default)]
    pub rotate_deg: [f64; 3],
}

#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BoxClip {
    pub min_mm: [f64; 3],
    pub max_mm: [f64; 3],
}

#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PlaneClip {
    pub point_mm: [f64; 3],
    pub normal: [f64; 3],
}

#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PolygonClip {
    pub points_mm: Vec<[f64; 2]>,
    #[serde(default)]
    pub z_min_mm: Option<f64>,
    #[serde(default)]
    pub z_max_mm: Option<f64>,
}

#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ParameterClip {
    pub polygon: Vec<[f64; 2]>,
}

impl ClipFile {
    /// The one clip it names; Err(count) when it names none or several.
    pub fn resolve(&self) -> std::result::Result<ClipSpec, usize> {
        let mut found = Vec::new();
        if let Some(b) = &self.box_ {
            found.push(ClipSpec::Box {
                min_mm: b.min_mm,
                max_mm: b.max_mm,
            });
        }
        if let Some(p) = &self.plane {
            found.push(ClipSpec::Plane {
                point_mm: p.point_mm,
                normal: p.normal,
            });
        }
        if let Some(p) = &self.polygon {
            found.push(ClipSpec::Polygon {
                points_mm: p.points_mm.clone(),
                z_min_mm: p.z_min_mm,
                z_max_mm: p.z_max_mm,
            });
        }
        if let Some(p) = &self.parameters {
            found.push(ClipSpec::Parameters {
                polygon: p.polygon.clone(),
            });
        }
        if let Some(b) = &self.block {
            found.push(ClipSpec::Block {
                center_mm: b.center_mm,
                size_mm: b.size_mm,
                rotate_deg: b.rotate_deg,
            });
        }
        if found.len() == 1 {
            Ok(found.remove(0))
        } else {
            Err(found.len())
        }
    }
}

#[derive(Debug, Clone, Copy, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SamplingSpec {
    /// Largest distance between samples along a curve, mm.
    #[serde(default = "default_step")]
    pub step_mm: f64,
    /// Local error of the integrator per step, mm.
    #[serde(default = "default_tolerance")]
    pub tolerance_mm: f64,
}

fn default_step() -> f64 {
    25.0
}
fn default_tolerance() -> f64 {
    1e-7
}

impl Default for SamplingSpec {
    fn default() -> Self {
        SamplingSpec {
            step_mm: default_step(),
            tolerance_mm: default_tolerance(),
        }
    }
}
