//! The surfaces of `surface: mesh` and `surface: minimal` specs: a triangle
//! mesh read from a file, or the soap film form-found over boundary
//! polylines ([`crate::design::minimal`]), checked (manifold, not degenerate),
//! charted ([`crate::design::mesh::chart`]), its curvature tensors estimated
//! ([`crate::design::mesh::curvature`]) while the chart's patches are
//! fitted, checked again (anticlastic somewhere), its singular points found
//! ([`crate::design::mesh::singular`]) and wrapped as a [`MeshSurface`] for
//! the tracer. A mesh that can be neither charted nor traced (no
//! anticlastic region) is refused for its chart first.

use crate::design::mesh::chart::{make_chart, ChartError, ChartKind};
use crate::design::mesh::surface::{ChartPatches, MeshSurface, PATCH_MIN_NEIGHBOURS};
use crate::design::mesh::TriMesh;
use crate::error::{Error, Location, Result};
use crate::spec::{SurfaceName, TraceSpec};
use glam::{DVec2, DVec3};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A mesh surface ready to trace on.
pub struct MeshSource {
    /// The surface.
    pub surface: Arc<MeshSurface>,
    /// The seed in its chart.
    pub seed_uv: DVec2,
    /// What was made and found, one line each.
    pub notes: Vec<String>,
    /// Synclastic regions and other things to look at.
    pub warnings: Vec<String>,
    /// How far curves traced on it may stand from the smooth surface the
    /// mesh samples, mm ([`mesh_precision_mm`]).
    pub precision_mm: f64,
    /// The median edge length, mm: the scale of the traced curves' wiggles.
    pub cell_mm: f64,
}

/// A film's curvature tensors are fitted over at least this many vertices
/// (about five rings; a mesh's over 16, two rings). A form-found film is a
/// discrete minimal surface: its vertices lie 0.01–0.15 mm off the smooth
/// film at the triangles' scale (measured against Enneper's surface over
/// its own boundary), so two-ring fits turn that noise into principal
/// directions wrong by up to 3° and crossings up to 3.5° off 90° (the
/// shipped films); 120-vertex fits average it to within 0.32°. The fits
/// are a minimal surface's quartic jets
/// ([`crate::design::mesh::curvature::vertex_jets_minimal`]: 9 unknowns
/// against a general quartic's 15), fitted at one vertex in six or seven
/// and blended at every vertex: at the rim of the film over Enneper's
/// boundary general cubics bent the traced lines near their ends by up to
/// 2.5e-5 /mm (a straight line read a 26 m radius, rim strips 5–11 % too
/// much).
pub const FILM_JET_POINTS: usize = 120;

/// A film's surface patches are fitted to at least this many neighbours
/// (a mesh's to 15), for the same reason.
pub const FILM_PATCH_NEIGHBOURS: usize = 30;

/// The mesh file of a `surface: mesh` spec, relative to the spec's folder.
pub fn mesh_path(spec: &TraceSpec, spec_path: &Path) -> Option<PathBuf> {
    let m = spec.mesh.as_ref()?;
    Some(if m.is_absolute() {
        m.clone()
    } else {
        spec_path.parent().unwrap_or(Path::new(".")).join(m)
    })
}

/// Read or form-find the mesh of a validated spec and make it a surface.
pub fn prepare(
    spec: &TraceSpec,
    spec_path: &Path,
    read_mesh: super::ReadMesh,
) -> Result<MeshSource> {
    let mut notes = Vec::new();
    let (mesh, chart_uv, named) = match spec.surface {
        SurfaceName::Minimal => {
            let boundaries: Vec<Vec<DVec3>> = spec
                .boundaries_mm
                .iter()
                .flatten()
                .map(|l| l.iter().map(|p| DVec3::from_array(*p)).collect())
                .collect();
            let opts = crate::design::minimal::FormFindOptions {
                target_edge_mm: spec.film_edge_mm.unwrap_or(spec.spacing_mm / 6.0),
                ..Default::default()
            };
            let found = crate::design::minimal::form_find(&boundaries, &opts, spec_path)?;
            let r = &found.report;
            notes.push(format!(
                "film: {} triangles, {} iterations{}, area {:.3} m², mean-curvature residual {:.2e}/mm mean, {:.2e}/mm max, smallest angle {:.1}°",
                found.mesh.triangles.len(),
                r.iterations,
                if r.converged { "" } else { " (not converged)" },
                r.area_mm2 * 1e-6,
                r.mean_mean_curvature_per_mm,
                r.max_mean_curvature_per_mm,
                r.min_angle_deg,
            ));
            (found.mesh, Some(found.chart_uv), spec_path.to_path_buf())
        }
        _ => {
            let file = mesh_path(spec, spec_path).unwrap_or_default();
            if !file.exists() {
                return Err(Error::input(
                    spec_path,
                    Location::Field("mesh".into()),
                    format!("no such file {}", file.display()),
                ));
            }
            (read_mesh(&file)?, None, file)
        }
    };
    let mut source = surface_of(spec, spec_path, mesh, chart_uv, &named)?;
    // The mesh's note first (`surface_of` puts it there), then the film's.
    source.notes.splice(1..1, notes);
    Ok(source)
}

/// The surface step of [`prepare`]: the mesh (`named` in errors) validated,
/// charted (by `chart_uv` where that is a film's plan and the film's own
/// projection folds), its curvature estimated and the chart's patches
/// fitted, the mesh surface made and the spec's seed put on it.
pub fn surface_of(
    spec: &TraceSpec,
    spec_path: &Path,
    mesh: TriMesh,
    chart_uv: Option<Vec<DVec2>>,
    named: &Path,
) -> Result<MeshSource> {
    let mut notes = Vec::new();
    let topo = crate::design::mesh::topology::Topology::build(&mesh, named)?;
    let mesh = topo.mesh().clone();
    let film = spec.surface == SurfaceName::Minimal;
    // A film's chart is per vertex of the film; cleaning keeps a film's
    // vertices (it has none unreferenced), which the count confirms.
    let chart_uv = chart_uv.filter(|uv| uv.len() == mesh.positions_mm.len());
    // A film's own plan is where its vertices started: form finding moved
    // them along their normals, so the map from the plan to the film is
    // rough at the triangles' scale. The projection of the film itself onto
    // its best-fit plane is exact: it is the chart wherever it does not fold.
    let projected = chart_uv.as_ref().and_then(|_| {
        crate::design::mesh::chart::unfolded_projection(&mesh, topo.boundary_loops())
    });
    let (uv, kind) = match (projected, chart_uv) {
        (Some(uv), _) => (uv, "its best-fit plane"),
        (None, Some(uv)) => (uv, "the film's plan"),
        (None, None) => {
            let chart = make_chart(&mesh, topo.boundary_loops()).map_err(|e| match e {
                ChartError::Topology { loops } => Error::input(
                    named,
                    Location::File,
                    format!(
                        "the mesh folds over in every plan and has {loops} boundary loops: lamella charts such meshes only as disks (one loop) or rings (two)"
                    ),
                ),
                ChartError::Folded { triangle } => {
                    let t = mesh.triangles[triangle];
                    let p = mesh.positions_mm[t[0] as usize];
                    Error::input(
                        named,
                        Location::Element(format!(
                            "triangle {triangle} at ({:.3}, {:.3}, {:.3}) mm",
                            p.x, p.y, p.z
                        )),
                        "the mesh cannot be flattened into a chart without folding here",
                    )
                }
            })?;
            let kind = match chart.kind {
                ChartKind::Projection => "its best-fit plane",
                ChartKind::Embedding => "a mean-value embedding",
            };
            (chart.uv, kind)
        }
    };
    // The curvature tensors and the chart's patches side by side: the
    // patches need only the chart.
    let patch_neighbours = if film {
        FILM_PATCH_NEIGHBOURS
    } else {
        PATCH_MIN_NEIGHBOURS
    };
    let (jets, patches) = rayon::join(
        || {
            if film {
                crate::design::mesh::curvature::vertex_jets_minimal(&mesh, &topo, FILM_JET_POINTS)
            } else {
                crate::design::mesh::curvature::vertex_jets(&mesh, &topo)
            }
        },
        || ChartPatches::fit(&mesh, uv, patch_neighbours),
    );
    let report = crate::design::mesh::singular::anticlastic_report(&topo, &jets);
    crate::design::mesh::singular::require_anticlastic(&report, named)?;
    // Singular points are notes (with their index), the rest warnings.
    let warnings: Vec<String> = report
        .warnings()
        .into_iter()
        .filter(|w| !w.starts_with("flat point") && !w.starts_with("umbilic"))
        .chain(topo.warnings())
        .collect();
    for s in &report.singularities {
        let kind = match s.kind {
            crate::design::mesh::singular::SingularKind::FlatPoint => "flat point",
            crate::design::mesh::singular::SingularKind::Umbilic => "umbilic",
        };
        notes.push(format!(
            "singular point ({kind}, index {}) at ({:.1}, {:.1}, {:.1}) mm: the net changes valence there",
            half_integer(s.index),
            s.position_mm.x,
            s.position_mm.y,
            s.position_mm.z
        ));
    }
    let mut curvatures: Vec<crate::geom::surface::Curvature> =
        jets.iter().map(|j| j.curvature).collect();
    if film {
        // A film is minimal by construction (its mean-curvature residual is
        // reported above): the mean curvature an estimated tensor shows is
        // estimation error, and dropping it makes the asymptotic directions
        // cross at 90° wherever the film is anticlastic.
        for c in &mut curvatures {
            *c = traceless(*c);
        }
    }
    notes.insert(
        0,
        format!(
            "mesh: {} vertices, {} triangles, charted by {kind}; K < 0 at {} of {} vertices",
            mesh.positions_mm.len(),
            mesh.triangles.len(),
            report.anticlastic,
            mesh.positions_mm.len()
        ),
    );
    let cell_mm = median_edge_mm(&mesh);
    let precision_mm = mesh_precision_mm(&mesh);
    let surface = MeshSurface::with_patches(&mesh, &curvatures, patches);
    let seed_uv = match spec.seed_mm {
        Some(p) => {
            let p = DVec3::from_array(p);
            let (q, d) = surface.nearest_uv(p).ok_or_else(|| {
                Error::input(
                    spec_path,
                    Location::Field("seed_mm".into()),
                    "the mesh is empty",
                )
            })?;
            if d > spec.spacing_mm {
                return Err(Error::input(
                    spec_path,
                    Location::Field("seed_mm".into()),
                    format!(
                        "({:.1}, {:.1}, {:.1}) mm is {d:.1} mm from the surface, more than spacing_mm: put the seed on it",
                        p.x, p.y, p.z
                    ),
                ));
            }
            q
        }
        None => surface.chart()[centre_vertex(&mesh)],
    };
    Ok(MeshSource {
        surface: Arc::new(surface),
        seed_uv,
        notes,
        warnings,
        precision_mm,
        cell_mm,
    })
}

/// The precision of curves traced on a mesh, mm, before they are traced:
/// the coordinates' rounding step. The design raises it to twice the
/// traced curves' own roughness at the mesh's scale where that is larger
/// ([`crate::geom::curve::roughness_mm`] over ±2 cells, `crate::design`).
///
/// The surface the tracer walks is the blend of cubic patches fitted to
/// the vertices (`mesh::surface`): it lies O(h⁴·κ³) from the smooth surface
/// the vertices sample (h the spacing, κ the curvature), a smooth error at
/// the surface's own scale that moves a traced curve but does not bend it
/// from sample to sample, so no smoothing could or should take it out.
/// What does bend it is the curvature tensor field, which varies linearly
/// across each triangle and kinks at its edges: the traced curves wiggle at
/// the mesh's scale. That roughness is measured on the traced curves and
/// declared as the network's precision, so that `nodes` and `check` smooth
/// the wiggles away like the rounding of an export, and no wider. (Declared
/// as h⁴·κ³ instead, about 14 times twice the roughness measured on
/// 100 mm Delaunay meshes of the catenoid, the smoothing windows spanned
/// whole strips there, and a degree-4 fit evaluated at the edge of its
/// window read the catenoid's fast-twisting lines 7 % too curved at their
/// ends.) Measured on Delaunay meshes of Enneper's surface, the catenoid
/// and the helicoid (`tests/it/mesh_truth.rs`, README "Accuracy by
/// input"): 40–100 mm cells jittered by 15–35 % give every strip's smallest
/// bending radius within 5 % and largest twist within 3 % of the closed
/// form's.
pub fn mesh_precision_mm(mesh: &TriMesh) -> f64 {
    crate::design::mesh::curvature::coordinate_step_mm(mesh)
}

/// The median edge length of a mesh, mm (0 for none).
pub fn median_edge_mm(mesh: &TriMesh) -> f64 {
    let mut edges: Vec<f64> = mesh
        .triangles
        .iter()
        .flat_map(|t| {
            (0..3).map(move |k| {
                mesh.positions_mm[t[k] as usize]
                    .distance(mesh.positions_mm[t[(k + 1) % 3] as usize])
            })
        })
        .collect();
    if edges.is_empty() {
        return 0.0;
    }
    let mid = edges.len() / 2;
    *edges.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// A curvature with its mean part removed: principal curvatures
/// ±(k1 − k2)/2, the same principal directions.
pub fn traceless(mut c: crate::geom::surface::Curvature) -> crate::geom::surface::Curvature {
    let k = 0.5 * (c.k1 - c.k2);
    c.k1 = k;
    c.k2 = -k;
    c.second = [k, 0.0, -k];
    c
}

/// `-1/2`, `1`, `3/2`: an index in halves.
fn half_integer(x: f64) -> String {
    let h = (2.0 * x).round() as i64;
    if h % 2 == 0 {
        format!("{}", h / 2)
    } else {
        format!("{h}/2")
    }
}

/// The vertex nearest the area centroid of the mesh.
fn centre_vertex(mesh: &TriMesh) -> usize {
    let (mut c, mut area) = (DVec3::ZERO, 0.0);
    for t in &mesh.triangles {
        let [a, b, cc] = t.map(|i| mesh.positions_mm[i as usize]);
        let w = 0.5 * (b - a).cross(cc - a).length();
        c += (a + b + cc) / 3.0 * w;
        area += w;
    }
    let c = if area > 0.0 { c / area } else { DVec3::ZERO };
    (0..mesh.positions_mm.len())
        .min_by(|&i, &j| {
            mesh.positions_mm[i]
                .distance_squared(c)
                .total_cmp(&mesh.positions_mm[j].distance_squared(c))
        })
        .unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_integers_print_as_fractions() {
        assert_eq!(half_integer(-0.5), "-1/2");
        assert_eq!(half_integer(1.0), "1");
        assert_eq!(half_integer(-1.5), "-3/2");
    }

    #[test]
    fn a_traceless_curvature_has_orthogonal_asymptotic_directions() {
        use glam::DVec3;
        let c = crate::geom::surface::Curvature {
            normal: DVec3::Z,
            first: [1.0, 0.0, 1.0],
            second: [0.003, 0.0, -0.001],
            k1: 0.003,
            k2: -0.001,
            d1: DVec3::X,
            d2: DVec3::Y,
        };
        // Before: tan²θ = −k1/k2 = 3, θ = 60°: the families cross at 60°.
        let (a, b) = c.asymptotic(0.0).unwrap();
        assert!((a.dot(b).abs() - 0.5).abs() < 1e-12);
        let t = traceless(c);
        assert_eq!((t.k1, t.k2), (0.002, -0.002));
        assert_eq!(t.mean(), 0.0);
        let (a, b) = t.asymptotic(0.0).unwrap();
        assert!(a.dot(b).abs() < 1e-12);
        assert_eq!((t.d1, t.d2, t.normal), (c.d1, c.d2, c.normal));
    }
}
