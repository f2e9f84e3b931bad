//! The trace spec: which surface, its scale and placement, the seed, the
//! spacing, the clip and the sampling of a network to trace — what the
//! design stage takes. Its serde names are the schema of `X.trace.yaml`;
//! reading the file (size, YAML guard, one-line errors) is
//! `formats::read::trace_spec`.

use serde::Deserialize;

/// A trace spec as written (`X.trace.yaml`): what to trace and how finely.
/// Validated by [`design`](crate::design::design), which names the field on error.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TraceSpec {
    /// Network name (default: the spec's file stem).
    #[serde(default)]
    pub name: Option<String>,
    /// `surface:` which surface: an analytic one, `mesh` or `minimal`.
    pub surface: SurfaceName,
    /// `mesh:` the triangle mesh (OBJ, PLY or STL, mm) of `surface: mesh`,
    /// relative to the spec's folder.
    #[serde(default)]
    pub mesh: Option<std::path::PathBuf>,
    /// `boundaries_mm:` the closed boundary polylines (x, y, z points, mm;
    /// the last point joins the first) a soap film spans for `surface: minimal`.
    #[serde(default)]
    pub boundaries_mm: Option<Vec<Vec<[f64; 3]>>>,
    /// `film_edge_mm:` target edge length of the form-found mesh (`surface:
    /// minimal`); default a sixth of `spacing_mm`.
    #[serde(default)]
    pub film_edge_mm: Option<f64>,
    /// The surface's shape parameter c (catenoid, helicoid, hypar), surface units.
    #[serde(default = "one")]
    pub c: f64,
    /// mm per surface unit (analytic surfaces; meshes and films are in mm).
    #[serde(default)]
    pub scale_mm: Option<f64>,
    /// `placement:` rotation and translation of the scaled surface; default none.
    #[serde(default)]
    pub placement: Placement,
    /// Seed point (u, v) in the surface's parameters (analytic surfaces).
    #[serde(default)]
    pub seed: Option<[f64; 2]>,
    /// Seed point (x, y, z) in mm near the mesh or film (`mesh`, `minimal`):
    /// the nearest point of the surface; default the vertex nearest the
    /// centre of its area.
    #[serde(default)]
    pub seed_mm: Option<[f64; 3]>,
    /// Target spacing between neighbouring curves of a family, mm.
    pub spacing_mm: f64,
    /// `net:` asymptotic (default) or principal families.
    #[serde(default)]
    pub net: Net,
    /// `design:` how curves are seeded: `central` (default) or `alternating`.
    #[serde(default)]
    pub design: Design,
    /// Most curves per family on each side of the seed.
    #[serde(default = "default_max_curves")]
    pub max_curves_per_side: usize,
    /// `clip:` what part of the surface to keep; default the whole domain.
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
    /// `sampling:` sample spacing and integrator tolerance.
    #[serde(default)]
    pub sampling: SamplingSpec,
}

fn one() -> f64 {
    1.0
}
fn default_max_curves() -> usize {
    200
}

/// `surface:` the analytic surfaces lamella can trace.
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum SurfaceName {
    /// Enneper's minimal surface (domain |(u, v)| < √3).
    Enneper,
    /// The catenoid of waist radius c.
    Catenoid,
    /// The helicoid of pitch 2π·c.
    Helicoid,
    /// Scherk's doubly periodic minimal surface.
    Scherk,
    /// Schwarz's D surface (triply periodic; one patch, or unfolded with `periodic`).
    SchwarzD,
    /// The hyperbolic paraboloid z = xy/c (anticlastic, not minimal).
    Hypar,
    /// A triangle mesh from a file (`mesh:`), anticlastic, not necessarily minimal.
    Mesh,
    /// The soap film (discrete minimal surface) spanning `boundaries_mm`.
    Minimal,
}

impl SurfaceName {
    /// Whether the surface is a mesh (read or form-found) rather than analytic.
    pub fn is_mesh(self) -> bool {
        matches!(self, SurfaceName::Mesh | SurfaceName::Minimal)
    }
}

/// `placement:` how the scaled surface is placed in the world: X' = R·X + t.
#[derive(Debug, Clone, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct Placement {
    /// Rotations about x, then y, then z, degrees.
    #[serde(default)]
    pub rotate_deg: [f64; 3],
    /// Translation after the rotation, world frame, mm; default zero.
    #[serde(default)]
    pub translate_mm: [f64; 3],
}

/// `net:` which families of curves become A and B.
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum Net {
    /// The two asymptotic families (the strips).
    #[default]
    Asymptotic,
    /// The two principal curvature families (the façade web).
    Principal,
}

/// `design:` how the curves of a family are seeded.
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
    Box {
        /// Lowest corner (x, y, z), world frame, mm.
        min_mm: [f64; 3],
        /// Highest corner (x, y, z), world frame, mm; above `min_mm` on every axis.
        max_mm: [f64; 3],
    },
    /// Keep the side of the plane opposite its normal.
    Plane {
        /// A point of the plane, world frame, mm.
        point_mm: [f64; 3],
        /// The plane's normal, world frame (any non-zero length): it points out of the kept side.
        normal: [f64; 3],
    },
    /// Keep what lies inside a polygon in plan (x, y), optionally between two heights.
    Polygon {
        /// Corners (x, y) of the plan polygon, world frame, mm: at least 3, any orientation.
        points_mm: Vec<[f64; 2]>,
        /// Lowest z kept, mm; none: unbounded below.
        z_min_mm: Option<f64>,
        /// Highest z kept, mm; none: unbounded above.
        z_max_mm: Option<f64>,
    },
    /// Keep what lies inside a polygon in the parameter plane (u, v).
    Parameters {
        /// Corners (u, v) in the surface's parameters: at least 3, any orientation.
        polygon: Vec<[f64; 2]>,
    },
    /// Keep what lies inside a block (a box turned about x, then y, then z
    /// about its centre).
    Block {
        /// Centre of the block, world frame, mm.
        center_mm: [f64; 3],
        /// Edge lengths along the block's own x, y, z, mm; each positive.
        size_mm: [f64; 3],
        /// Rotations about x, then y, then z, degrees.
        rotate_deg: [f64; 3],
    },
}

/// The clip as written: exactly one of its keys.
#[derive(Debug, Clone, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct ClipFile {
    /// `box:` an axis-aligned box.
    #[serde(rename = "box", default)]
    pub box_: Option<BoxClip>,
    /// `plane:` a half-space.
    #[serde(default)]
    pub plane: Option<PlaneClip>,
    /// `polygon:` a vertical prism over a plan polygon.
    #[serde(default)]
    pub polygon: Option<PolygonClip>,
    /// `parameters:` a polygon in the parameter plane.
    #[serde(default)]
    pub parameters: Option<ParameterClip>,
    /// `block:` a rotated box.
    #[serde(default)]
    pub block: Option<BlockClip>,
}

/// `clip.block:` a box turned about its centre.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BlockClip {
    /// Centre, world frame, mm.
    pub center_mm: [f64; 3],
    /// Edge lengths along the block's own axes, mm; each positive.
    pub size_mm: [f64; 3],
    /// Rotations about x, then y, then z, degrees; default none.
    #[serde(default)]
    pub rotate_deg: [f64; 3],
}

/// `clip.box:` an axis-aligned box.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BoxClip {
    /// Lowest corner (x, y, z), world frame, mm.
    pub min_mm: [f64; 3],
    /// Highest corner (x, y, z), world frame, mm.
    pub max_mm: [f64; 3],
}

/// `clip.plane:` keep the side opposite the normal.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PlaneClip {
    /// A point of the plane, world frame, mm.
    pub point_mm: [f64; 3],
    /// Normal pointing out of the kept side, world frame (non-zero, any length).
    pub normal: [f64; 3],
}

/// `clip.polygon:` a vertical prism over a plan polygon.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PolygonClip {
    /// Corners (x, y), world frame, mm: at least 3, enclosing an area.
    pub points_mm: Vec<[f64; 2]>,
    /// Lowest z kept, mm; optional.
    #[serde(default)]
    pub z_min_mm: Option<f64>,
    /// Highest z kept, mm; optional.
    #[serde(default)]
    pub z_max_mm: Option<f64>,
}

/// `clip.parameters:` a polygon in the parameter plane.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ParameterClip {
    /// Corners (u, v) in the surface's parameters: at least 3, enclosing an area.
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

/// `sampling:` how finely curves are traced and sampled.
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
