//! Network design: from a trace spec to a network of traced curves.
//!
//! Input: a [`TraceSpec`] (surface, scale and placement, seed, spacing, clip,
//! sampling). Output: a [`RawNetwork`] in mm with normals: families A and B
//! (asymptotic, or principal for the façade web) and the cut boundary as
//! `edge` curves. Curves are traced with [`trace`]; the design seeds
//! them at the spacing along the curves through the seed (`central`) or
//! alternately along the last curve of the other family (`alternating`).
//!
//! This module is the driver; the clip regions are in `clip`, the edge
//! curves along the clip in `edges`, the seeding helpers in `seed`.

mod clip;
mod edges;
pub mod mesh;
pub mod mesh_source;
pub mod minimal;
pub mod periodic;
mod seed;
pub mod surface;
pub mod trace;

use crate::error::{Error, Location, Result};
use crate::network::{Family, RawCurve, RawNetwork, Unit};
use crate::spec::{ClipSpec, Design, Net, SurfaceName, TraceSpec};
use glam::{DMat3, DVec2, DVec3};
use std::path::Path;
use std::sync::Arc;
use surface::{Placed, Surface};
use trace::{trace_through, Field, Region, Stop, TraceOptions, Traced};

pub use clip::Clip;
use clip::{validate_clip, AlongFace, Face};
use edges::{near_polyline, trace_edges};
use seed::{crossing_uv, marks, station_of, PointIndex, FILL_GAP, FILL_ROUNDS};

/// The placed analytic surface of a spec. A mesh or film spec (`surface:
/// mesh` or `minimal`) has its surface made by [`prepare_surface`], which
/// reads files and can fail; here it gives an empty mesh.
pub fn placed_surface(spec: &TraceSpec) -> Placed {
    let base: Arc<dyn Surface> = match spec.surface {
        SurfaceName::Enneper => Arc::new(surface::Enneper),
        SurfaceName::Catenoid => Arc::new(surface::Catenoid { c: spec.c }),
        SurfaceName::Helicoid => Arc::new(surface::Helicoid { c: spec.c }),
        SurfaceName::Scherk => Arc::new(surface::Scherk),
        SurfaceName::SchwarzD => Arc::new(surface::SchwarzD),
        SurfaceName::Hypar => Arc::new(surface::Hypar { c: spec.c }),
        SurfaceName::Mesh | SurfaceName::Minimal => Arc::new(
            crate::design::mesh::surface::MeshSurface::new(&Default::default(), Vec::new(), &[]),
        ),
    };
    place(spec, base, spec.scale_mm.unwrap_or(1.0))
}

/// A surface scaled and placed as the spec's `placement` says.
fn place(spec: &TraceSpec, base: Arc<dyn Surface>, scale_mm: f64) -> Placed {
    let [rx, ry, rz] = spec.placement.rotate_deg.map(f64::to_radians);
    Placed {
        surface: base,
        scale_mm,
        rotation: DMat3::from_rotation_z(rz)
            * DMat3::from_rotation_y(ry)
            * DMat3::from_rotation_x(rx),
        translation_mm: DVec3::from_array(spec.placement.translate_mm),
    }
}

/// A spec's surface ready to trace on: placed, with the seed in its
/// parameters and what a designer should know about it (form finding,
/// curvature, singular points).
pub struct Prepared {
    /// The placed surface.
    pub surface: Placed,
    /// The seed in the surface's parameters.
    pub seed_uv: DVec2,
    /// One line each: how the surface was made and what was found on it.
    pub notes: Vec<String>,
    /// Warnings about the surface (synclastic regions).
    pub warnings: Vec<String>,
    /// How far traced curves may stand from the surface's own, mm: a mesh's
    /// (see [`mesh_source`]); 0 on a closed form.
    pub precision_mm: f64,
    /// A mesh's median edge, mm (0 on a closed form).
    pub cell_mm: f64,
}

/// How the design stage reads the mesh file a `surface: mesh` spec names
/// (the pipeline passes `formats::read::mesh::read_mesh`: stages read no
/// files themselves).
pub type ReadMesh<'a> = &'a dyn Fn(&Path) -> Result<crate::geom::mesh::TriMesh>;

/// The surface of a validated spec: analytic, or a mesh read or form-found
/// (see [`mesh_source`]).
pub fn prepare_surface(spec: &TraceSpec, path: &Path, read_mesh: ReadMesh) -> Result<Prepared> {
    if spec.surface.is_mesh() {
        let m = mesh_source::prepare(spec, path, read_mesh)?;
        return Ok(Prepared {
            surface: place(spec, m.surface, 1.0),
            seed_uv: m.seed_uv,
            notes: m.notes,
            warnings: m.warnings,
            precision_mm: m.precision_mm,
            cell_mm: m.cell_mm,
        });
    }
    Ok(Prepared {
        surface: placed_surface(spec),
        seed_uv: DVec2::from_array(spec.seed.unwrap_or_default()),
        notes: Vec::new(),
        warnings: Vec::new(),
        precision_mm: 0.0,
        cell_mm: 0.0,
    })
}

/// Validate a spec before tracing (one-line errors naming the field).
fn validate(spec: &TraceSpec, path: &Path) -> Result<Option<ClipSpec>> {
    let err =
        |field: &str, what: String| Err(Error::input(path, Location::Field(field.into()), what));
    let is_mesh = spec.surface.is_mesh();
    let name = format!("{:?}", spec.surface).to_lowercase();
    let only_for = |field: &str, present: bool, what: &str| -> Result<()> {
        if present {
            return Err(Error::input(
                path,
                Location::Field(field.into()),
                format!("is for {what}, not `surface: {name}`"),
            ));
        }
        Ok(())
    };
    only_for(
        "mesh",
        spec.mesh.is_some() && spec.surface != SurfaceName::Mesh,
        "`surface: mesh`",
    )?;
    only_for(
        "boundaries_mm",
        spec.boundaries_mm.is_some() && spec.surface != SurfaceName::Minimal,
        "`surface: minimal`",
    )?;
    only_for(
        "film_edge_mm",
        spec.film_edge_mm.is_some() && spec.surface != SurfaceName::Minimal,
        "`surface: minimal`",
    )?;
    only_for(
        "seed_mm",
        spec.seed_mm.is_some() && !is_mesh,
        "meshes and films (analytic surfaces take `seed: [u, v]`)",
    )?;
    only_for(
        "seed",
        spec.seed.is_some() && is_mesh,
        "analytic surfaces (a mesh has no parameters: give `seed_mm: [x, y, z]`)",
    )?;
    only_for(
        "scale_mm",
        spec.scale_mm.is_some() && is_mesh,
        "analytic surfaces (meshes and films are in mm)",
    )?;
    match spec.surface {
        SurfaceName::Mesh if spec.mesh.is_none() => {
            return err(
                "mesh",
                "`surface: mesh` needs `mesh: FILE` (an OBJ, PLY or STL triangle mesh in mm)"
                    .into(),
            );
        }
        SurfaceName::Minimal if spec.boundaries_mm.is_none() => {
            return err("boundaries_mm", "`surface: minimal` needs `boundaries_mm`: one or more closed polylines of [x, y, z] points".into());
        }
        _ => {}
    }
    if let Some(e) = spec.film_edge_mm {
        if !(e.is_finite() && e > 0.0) {
            return err("film_edge_mm", format!("must be positive, got {e}"));
        }
    }
    if spec
        .seed_mm
        .is_some_and(|p| p.iter().any(|x| !x.is_finite()))
    {
        return err("seed_mm", "must be three finite numbers".into());
    }
    let scale_mm = match (is_mesh, spec.scale_mm) {
        (true, _) => 1.0,
        (false, Some(s)) => s,
        (false, None) => return err("scale_mm", "required: mm per surface unit".into()),
    };
    if !is_mesh && spec.seed.is_none() {
        return err(
            "seed",
            "required: the seed point [u, v] in the surface's parameters".into(),
        );
    }
    if !(scale_mm.is_finite() && scale_mm > 0.0) {
        return err("scale_mm", format!("must be positive, got {scale_mm}"));
    }
    if !(spec.spacing_mm.is_finite() && spec.spacing_mm > 0.0) {
        return err(
            "spacing_mm",
            format!("must be positive, got {}", spec.spacing_mm),
        );
    }
    if !(spec.c.is_finite() && spec.c != 0.0) {
        return err("c", format!("must be a non-zero number, got {}", spec.c));
    }
    let s = &spec.sampling;
    if !(s.step_mm.is_finite() && (MIN_STEP_MM..=MAX_STEP_MM).contains(&s.step_mm)) {
        return err(
            "sampling.step_mm",
            format!(
                "the largest distance between samples must be {MIN_STEP_MM} to {MAX_STEP_MM} mm, got {}",
                s.step_mm
            ),
        );
    }
    if !(s.tolerance_mm.is_finite() && s.tolerance_mm >= MIN_TOLERANCE_MM) {
        return err(
            "sampling.tolerance_mm",
            format!(
                "the integrator's local error must be at least {MIN_TOLERANCE_MM:e} mm, got {}",
                s.tolerance_mm
            ),
        );
    }
    if s.tolerance_mm > 0.01 * s.step_mm {
        return err(
            "sampling.tolerance_mm",
            format!(
                "{} mm is too coarse for samples {} mm apart (at most 1 % of step_mm)",
                s.tolerance_mm, s.step_mm
            ),
        );
    }
    if spec.seed.is_some_and(|q| q.iter().any(|x| !x.is_finite())) {
        return err("seed", "must be two finite numbers".into());
    }
    if spec.max_curves_per_side == 0 || spec.max_curves_per_side > MAX_CURVES_PER_SIDE {
        return err(
            "max_curves_per_side",
            format!(
                "must be 1 to {MAX_CURVES_PER_SIDE}, got {}",
                spec.max_curves_per_side
            ),
        );
    }
    if spec.spacing_mm < 10.0 * s.step_mm.min(1.0) {
        return err(
            "spacing_mm",
            format!("{} mm is too small a spacing for strips", spec.spacing_mm),
        );
    }
    if scale_mm > 1e7 {
        return err(
            "scale_mm",
            format!("{scale_mm:e} mm per unit is beyond any structure"),
        );
    }
    if scale_mm < 1.0 {
        return err(
            "scale_mm",
            format!("{scale_mm} mm per unit is too small a surface (at least 1)"),
        );
    }
    if spec.spacing_mm > crate::network::MAX_EXTENT_MM {
        return err(
            "spacing_mm",
            format!("{} mm is beyond any structure", spec.spacing_mm),
        );
    }
    let p = &spec.placement;
    if p.rotate_deg
        .iter()
        .chain(&p.translate_mm)
        .any(|x| !x.is_finite())
    {
        return err(
            "placement",
            "rotations and translation must be finite numbers".into(),
        );
    }
    let clip = match &spec.clip {
        None => None,
        Some(c) => Some(c.resolve().map_err(|n| {
            Error::input(
                path,
                Location::Field("clip".into()),
                format!("name exactly one of box, block, plane, polygon, parameters (found {n})"),
            )
        })?),
    };
    if let Some(c) = &clip {
        validate_clip(c, path)?;
    }
    if is_mesh && matches!(clip, Some(ClipSpec::Parameters { .. })) {
        return err(
            "clip",
            "a mesh or film has no parameters of its own: clip it in space (box, block, plane, polygon)".into(),
        );
    }
    if spec.fill && !spec.periodic && !is_mesh {
        return err(
            "fill",
            "filling gaps is for periodic designs (periodic: true) and meshes and films".into(),
        );
    }
    if spec.periodic {
        if spec.surface != SurfaceName::SchwarzD {
            return err(
                "periodic",
                format!(
                    "no periodic patch is known for {:?} (only schwarz_d)",
                    spec.surface
                ),
            );
        }
        if spec.design != Design::Central {
            return err("design", "a periodic network is designed `central`".into());
        }
        if matches!(clip, Some(ClipSpec::Parameters { .. })) {
            return err("clip", "a periodic network is clipped in space (box, block, plane, polygon), not in parameters".into());
        }
        if clip.is_none() {
            return err("clip", "a periodic surface is endless: give a clip".into());
        }
    }
    Ok(clip)
}

/// Smallest and largest `sampling.step_mm`.
pub const MIN_STEP_MM: f64 = 0.1;
/// Largest `sampling.step_mm`.
pub const MAX_STEP_MM: f64 = 1000.0;
/// Smallest `sampling.tolerance_mm`: below, rounding noise in the surface
/// evaluation exceeds it and steps shrink without end.
pub const MIN_TOLERANCE_MM: f64 = 1e-10;

/// What a design produced, besides the network.
#[derive(Debug, Clone, Default)]
pub struct DesignReport {
    /// Number of A curves in the network (after dropping those under 5 % of the spacing).
    pub a_curves: usize,
    /// Number of B curves in the network.
    pub b_curves: usize,
    /// Number of edge curves (the clip boundary traced on the surface).
    pub edges: usize,
    /// (curve id, where its start stopped, where its end stopped).
    pub stops: Vec<(String, Stop, Stop)>,
    /// What a designer should look at (crossings far from 90°, synclastic
    /// regions of a mesh).
    pub warnings: Vec<String>,
    /// How a mesh or film surface was made and what was found on it (form
    /// finding, curvature, singular points), one line each.
    pub notes: Vec<String>,
}

/// Trace the network a spec describes, and check it: it has A and B
/// curves, and it passes the same validation as a network file read back
/// (lamella never writes a network it cannot read). Crossings far from 90°
/// on a minimal surface become warnings in the report.
///
/// The network returned: A curves sorted by their offset from the seed, then
/// B, then edges (`A00…`, `B00…`, `edge00…`); every A/B curve at least 5 % of
/// the spacing long; points in mm, world frame, with surface normals; node
/// tolerance 0.5 mm; at least one A and one B curve, and it passes
/// [`Network::new`](crate::network::Network::new). Fails with a one-line
/// [`Error::Input`] naming the spec and the field (or [`Error::Network`] when
/// the result would not read back).
pub fn design(
    spec: &TraceSpec,
    path: &Path,
    read_mesh: ReadMesh,
) -> Result<(RawNetwork, DesignReport)> {
    let (raw, mut report) = trace_network(spec, path, read_mesh)?;
    let min_len = min_curve_length_mm(spec);
    for (count, family) in [(report.a_curves, "A"), (report.b_curves, "B")] {
        if count == 0 {
            return Err(Error::input(
                path,
                Location::Field("clip".into()),
                format!(
                    "the design has no {family} curve at least {min_len} mm long (5 % of spacing_mm): the clip leaves too little of the surface"
                ),
            ));
        }
    }
    let net = crate::network::Network::new(raw.clone(), path).map_err(|e| {
        let what = match e {
            Error::Input { at, what, .. } => match at {
                Location::File => what,
                at => format!("{at}: {what}"),
            },
            Error::Network { what, .. } => what,
            other => other.to_string(),
        };
        Error::network(
            path,
            format!("the traced network would not read back: {what}"),
        )
    })?;
    report.warnings.extend(crossing_warnings(spec, &net));
    Ok((raw, report))
}

/// Largest deviation from 90° (degrees) of an A×B crossing on a minimal
/// surface (or of any principal net) before it is reported.
pub const RIGHT_ANGLE_SLACK_DEG: f64 = 1.0;

/// On a minimal surface the two asymptotic families cross at right angles
/// everywhere (the principal families do on any surface): an A×B node far
/// from 90° is two sheets of the surface passing through each other (Enneper
/// beyond its self-intersections, a clip that keeps too much), not a
/// crossing of the net.
fn crossing_warnings(spec: &TraceSpec, net: &crate::network::Network) -> Vec<String> {
    if spec.net == Net::Asymptotic && matches!(spec.surface, SurfaceName::Hypar | SurfaceName::Mesh)
    {
        return Vec::new();
    }
    let curves: Vec<crate::geom::curve::SmoothCurve> = net
        .curves
        .iter()
        .map(|c| crate::geom::curve::SmoothCurve::new(&c.points_world_mm))
        .collect();
    let topo = crate::analysis::topology::find_nodes(
        net,
        &curves,
        crate::analysis::topology::NodeOptions::new(net.tolerance_mm),
    );
    let off: Vec<&crate::analysis::topology::Node> = topo
        .nodes
        .iter()
        .filter(|n| {
            net.curves[n.a].family == Family::A
                && net.curves[n.b].family == Family::B
                && (90.0 - n.angle_deg).abs() > RIGHT_ANGLE_SLACK_DEG
        })
        .collect();
    let Some(worst) = off
        .iter()
        .min_by(|x, y| x.angle_deg.total_cmp(&y.angle_deg))
    else {
        return Vec::new();
    };
    let p = worst.position_world_mm;
    let what = format!(
        "{} A×B crossing(s) are not at 90° (the worst {:.1}°, {}×{} at ({:.0}, {:.0}, {:.0}) mm)",
        off.len(),
        worst.angle_deg,
        net.curves[worst.a].id,
        net.curves[worst.b].id,
        p.x,
        p.y,
        p.z,
    );
    let why = if spec.surface.is_mesh() {
        "on a soap film the families cross at right angles, so the film's curvature is estimated poorly there (near its rim the fits are one-sided, or the mesh is too coarse: lower film_edge_mm)".to_string()
    } else {
        format!(
            "the families of a {} net cross at right angles, so the surface passes through itself there; clip it{}",
            if spec.net == Net::Principal { "principal" } else { "minimal surface's asymptotic" },
            if spec.clip.is_none() { " (the spec has no clip)" } else { "" }
        )
    };
    vec![format!("{what}: {why}")]
}

/// Trace the network a spec describes (unchecked).
fn trace_network(
    spec: &TraceSpec,
    path: &Path,
    read_mesh: ReadMesh,
) -> Result<(RawNetwork, DesignReport)> {
    let clip_spec = validate(spec, path)?;
    let Prepared {
        surface,
        seed_uv: seed,
        notes,
        warnings,
        precision_mm,
        cell_mm,
    } = prepare_surface(spec, path, read_mesh)?;
    let clip = Clip::from_spec(clip_spec.as_ref());
    let opts = TraceOptions {
        tolerance_mm: spec.sampling.tolerance_mm,
        max_step_mm: spec.sampling.step_mm,
        boundary_tolerance_mm: (spec.sampling.tolerance_mm).max(1e-9),
        ..TraceOptions::default()
    };
    let seed_err = |what: String| Error::input(path, Location::Field("seed".into()), what);
    if !surface.in_domain(seed) {
        return Err(seed_err(format!(
            "({}, {}) is outside the {:?} surface's domain",
            seed.x, seed.y, spec.surface
        )));
    }
    let seed_field = if spec.surface.is_mesh() {
        "seed_mm"
    } else {
        "seed"
    };
    let seed_err = |what: String| Error::input(path, Location::Field(seed_field.into()), what);
    if !clip.contains(seed, surface.point(seed)) {
        let p = surface.point(seed);
        return Err(Error::input(
            path,
            Location::Field("clip".into()),
            format!(
                "the seed's point ({:.1}, {:.1}, {:.1}) mm lies outside the clip: move the seed or the clip",
                p.x, p.y, p.z
            ),
        ));
    }
    let declare = |(mut raw, report): (RawNetwork, DesignReport)| {
        if cell_mm > 0.0 {
            let rough = raw
                .curves
                .iter()
                .filter(|c| c.family != Family::Edge)
                .map(|c| crate::geom::curve::roughness_mm(&c.points, 2.0 * cell_mm))
                .fold(0.0f64, f64::max);
            let p = precision_mm.max(2.0 * rough);
            raw.precision = Some(p);
        }
        (raw, report)
    };
    if spec.periodic {
        return design_periodic(spec, path, &surface, &clip, opts).map(declare);
    }
    let (fa, fb) = match spec.net {
        Net::Asymptotic => (Field::AsymptoticA, Field::AsymptoticB),
        Net::Principal => (Field::PrincipalMax, Field::PrincipalMin),
    };
    let budget = Budget::new(spec, path);
    let trace = |field: Field, at: DVec2| {
        let t = trace_through(&surface, field, at, &clip, opts);
        if let Ok(t) = &t {
            budget.charge(t.uv.len());
        }
        t
    };
    let a0 = trace(fa, seed)
        .map_err(|s| seed_err(format!("no curve through the seed: {}", s.as_str())))?;
    let b0 = trace(fb, seed)
        .map_err(|s| seed_err(format!("no curve through the seed: {}", s.as_str())))?;
    let (a0, b0) = (orient_seed_curve(a0, seed), orient_seed_curve(b0, seed));
    if a0.length_mm() < spec.sampling.tolerance_mm || b0.length_mm() < spec.sampling.tolerance_mm {
        return Err(Error::input(
            path,
            Location::Field("clip".into()),
            "the clip leaves no curve through the seed",
        ));
    }
    let d = spec.spacing_mm;
    let max_k = spec.max_curves_per_side;
    // (offset index, curve) per family.
    let mut a_curves: Vec<(i64, Traced)> = Vec::new();
    let mut b_curves: Vec<(i64, Traced)> = Vec::new();
    match spec.design {
        Design::Central => {
            let sa = station_of(&a0, seed);
            let sb = station_of(&b0, seed);
            for (k, s) in marks(sa, a0.length_mm(), d, max_k) {
                if let Ok(t) = trace(fb, a0.uv_at(s)) {
                    b_curves.push((k, t));
                }
                budget.check()?;
            }
            for (k, s) in marks(sb, b0.length_mm(), d, max_k) {
                if let Ok(t) = trace(fa, b0.uv_at(s)) {
                    a_curves.push((k, t));
                }
                budget.check()?;
            }
        }
        Design::Alternating => {
            for sign in [1.0, -1.0] {
                let (mut a, mut b, mut x) = (a0.clone(), b0.clone(), seed);
                for k in 1..=max_k as i64 {
                    let (sa, sb) = (station_of(&a, x) + sign * d, station_of(&b, x) + sign * d);
                    if !(0.0..=a.length_mm()).contains(&sa) || !(0.0..=b.length_mm()).contains(&sb)
                    {
                        break;
                    }
                    let (Ok(nb), Ok(na)) = (trace(fb, a.uv_at(sa)), trace(fa, b.uv_at(sb))) else {
                        break;
                    };
                    budget.check()?;
                    let kk = if sign > 0.0 { k } else { -k };
                    a_curves.push((kk, na.clone()));
                    b_curves.push((kk, nb.clone()));
                    match crossing_uv(&na, &nb) {
                        Some(nx) => {
                            x = nx;
                            a = na;
                            b = nb;
                        }
                        None => break,
                    }
                }
            }
        }
    }
    // The families gathered and filled: where the curves through the seed's
    // two curves leave a family out (around a film's flat point, beyond a
    // ring's band), more curves seeded along the other family.
    gather(
        (&mut a_curves, &mut b_curves),
        (a0, b0),
        Fill {
            spec,
            path,
            budget: &budget,
            hint: "raise spacing_mm or max_curves_per_side",
        },
        |parent: &Traced, s| parent.uv_at(s),
        |&at| surface.point(at),
        |family_is_a, _, at| trace(if family_is_a { fa } else { fb }, at).ok(),
    )?;

    // Edges: trace the cut boundary along each face from the curve ends on it.
    let edges = trace_edges(
        &surface,
        &clip,
        a_curves.iter().chain(&b_curves).map(|c| &c.1),
        opts,
        spec.sampling.step_mm,
        &budget,
    )?;

    let finished = |t: Traced| FinishedCurve {
        normals_world: t.uv.iter().map(|&q| surface.normal(q)).collect(),
        points_world_mm: t.points_world_mm,
        stops: (t.stop_start, t.stop_end),
    };
    let (raw, mut report) = assemble(
        spec,
        path,
        a_curves.into_iter().map(|c| finished(c.1)).collect(),
        b_curves.into_iter().map(|c| finished(c.1)).collect(),
        edges.into_iter().map(finished).collect(),
    );
    report.notes = notes;
    report.warnings = warnings;
    Ok(declare((raw, report)))
}

/// The world direction the seed's two curves run along: each is turned so
/// that its tangent at the seed has a positive component along it (+x
/// first; +y for a curve across x; +z for one across both). A fixed world
/// direction, not the surface's parameters or a mesh's vertex order, so
/// the same design traced on a closed form, on its mesh or on a film
/// numbers its curves alike (they are numbered along the seed's curves).
pub const SEED_CURVE_DIRECTION: DVec3 = DVec3::new(
    1.0,
    std::f64::consts::FRAC_1_PI,
    std::f64::consts::FRAC_1_PI * std::f64::consts::FRAC_1_PI,
);

/// A seed curve turned to run along [`SEED_CURVE_DIRECTION`] at the seed.
fn orient_seed_curve(t: Traced, seed: DVec2) -> Traced {
    let n = t.points_world_mm.len();
    if n < 2 {
        return t;
    }
    let s = station_of(&t, seed);
    let k = t.stations_mm.partition_point(|&x| x <= s).clamp(1, n - 1);
    let tangent = t.points_world_mm[k] - t.points_world_mm[k - 1];
    if tangent.dot(SEED_CURVE_DIRECTION) < 0.0 {
        t.reversed()
    } else {
        t
    }
}

/// A traced curve ready for the network file: world points and normals.
struct FinishedCurve {
    points_world_mm: Vec<DVec3>,
    normals_world: Vec<DVec3>,
    stops: (Stop, Stop),
}

/// Name the curves (`A00…`, `B00…`, `edge00…`, three digits past 100) and
/// make the network and the report.
fn assemble(
    spec: &TraceSpec,
    path: &Path,
    a: Vec<FinishedCurve>,
    b: Vec<FinishedCurve>,
    edges: Vec<FinishedCurve>,
) -> (RawNetwork, DesignReport) {
    let mut report = DesignReport {
        a_curves: a.len(),
        b_curves: b.len(),
        edges: edges.len(),
        stops: Vec::new(),
        warnings: Vec::new(),
        notes: Vec::new(),
    };
    let mut curves = Vec::with_capacity(a.len() + b.len() + edges.len());
    for (prefix, family, list) in [
        ("A", Family::A, a),
        ("B", Family::B, b),
        ("edge", Family::Edge, edges),
    ] {
        let width = if list.len() > 100 { 3 } else { 2 };
        for (i, c) in list.into_iter().enumerate() {
            let id = format!("{prefix}{i:0width$}");
            report.stops.push((id.clone(), c.stops.0, c.stops.1));
            curves.push(RawCurve {
                id,
                family,
                points: c.points_world_mm,
                normals: Some(c.normals_world),
            });
        }
    }
    let name = spec.name.clone().unwrap_or_else(|| {
        path.file_stem()
            .map(|s| s.to_string_lossy().trim_end_matches(".trace").to_string())
            .unwrap_or_else(|| "traced".into())
    });
    (
        RawNetwork {
            name,
            unit: Unit::Mm,
            tolerance: Some(0.5),
            precision: None,
            curves,
        },
        report,
    )
}

/// Most sample points a design may trace (all curves and edges together);
/// a quarter of that on Schwarz D, whose points cost a numerical integral
/// each (either takes a few seconds).
pub const MAX_DESIGN_POINTS: usize = 500_000;

/// Curves with their seeding numbers (0 through the seed, ±k beside it).
type Numbered<C> = Vec<(i64, C)>;

/// The shortest A or B curve a design keeps: 5 % of the spacing, at least
/// 1 mm.
fn min_curve_length_mm(spec: &TraceSpec) -> f64 {
    (spec.spacing_mm * 0.05).max(1.0)
}

/// What filling the gaps of a design needs besides its curves.
struct Fill<'a> {
    /// The spec: its spacing, its `max_curves_per_side` (a family holds at
    /// most 2·max_k + 1 curves) and whether to fill at all.
    spec: &'a TraceSpec,
    /// The spec's file, named in errors.
    path: &'a Path,
    budget: &'a Budget<'a>,
    /// What to change when there are too many curves.
    hint: &'a str,
}

/// Both families' curves made whole: the seed's own two (`a0`, `b0`,
/// numbered 0) added, each family in number order, the curves shorter than
/// [`min_curve_length_mm`] or of fewer than two points dropped, and, where
/// the spec asks for it, the gaps filled by [`fill_gaps`] (the same rule
/// keeping the children).
fn gather<C, S>(
    (a_curves, b_curves): (&mut Numbered<C>, &mut Numbered<C>),
    (a0, b0): (C, C),
    fill: Fill,
    seed_at: impl Fn(&C, f64) -> S,
    point_of: impl Fn(&S) -> DVec3,
    child_of: impl Fn(bool, &C, S) -> Option<C>,
) -> Result<()>
where
    C: seed::FillCurve,
{
    a_curves.push((0, a0));
    b_curves.push((0, b0));
    a_curves.sort_by_key(|c| c.0);
    b_curves.sort_by_key(|c| c.0);
    let min_len = min_curve_length_mm(fill.spec);
    let keep = |c: &C| c.length_mm() >= min_len && c.points_world_mm().len() >= 2;
    a_curves.retain(|c| keep(&c.1));
    b_curves.retain(|c| keep(&c.1));
    if fill.spec.fill {
        fill_gaps(
            (a_curves, b_curves),
            fill,
            seed_at,
            point_of,
            child_of,
            keep,
        )?;
    }
    Ok(())
}

/// Fill the gaps a design's curves leave: along every curve of one family,
/// every half spacing, seed a curve of the other family wherever none of
/// that family passes within [`FILL_GAP`] spacings, for up to
/// [`FILL_ROUNDS`] rounds (A first in each). `seed_at(parent, s)` is where
/// a child would start at station `s` of `parent`, `point_of` that seed's
/// world point, `child_of(family_is_a, parent, seed)` the curve traced from
/// it (none where no curve starts), `keep` whether a child is long enough
/// to keep; children are numbered on from `max_k + 1`.
#[allow(clippy::too_many_arguments)]
fn fill_gaps<C, S>(
    (a_curves, b_curves): (&mut Numbered<C>, &mut Numbered<C>),
    fill: Fill,
    seed_at: impl Fn(&C, f64) -> S,
    point_of: impl Fn(&S) -> DVec3,
    child_of: impl Fn(bool, &C, S) -> Option<C>,
    keep: impl Fn(&C) -> bool,
) -> Result<()>
where
    C: seed::FillCurve,
{
    let d = fill.spec.spacing_mm;
    let max_k = fill.spec.max_curves_per_side;
    let limit = 2 * max_k + 1;
    let mut next_k = max_k as i64 + 1;
    for _round in 0..FILL_ROUNDS {
        let mut added = false;
        for family_is_a in [true, false] {
            let (parents, children) = if family_is_a {
                (&*b_curves, &mut *a_curves)
            } else {
                (&*a_curves, &mut *b_curves)
            };
            let mut index = PointIndex::new(children.iter().map(|c| c.1.points_world_mm()));
            let mut born = Vec::new();
            for (_, parent) in parents.iter() {
                let steps = (parent.length_mm() / (0.5 * d)).floor() as usize;
                for i in 1..steps {
                    let seed = seed_at(parent, 0.5 * d * i as f64);
                    if index.nearest_distance(point_of(&seed)) < FILL_GAP * d {
                        continue;
                    }
                    let Some(child) = child_of(family_is_a, parent, seed) else {
                        continue;
                    };
                    fill.budget.check()?;
                    if keep(&child) {
                        index.add(child.points_world_mm());
                        born.push((next_k, child));
                        next_k += 1;
                        if children.len() + born.len() > limit {
                            return Err(Error::input(
                                fill.path,
                                Location::Field("fill".into()),
                                format!(
                                    "filling needs more than {limit} curves of family {} (2 × max_curves_per_side + 1): {}",
                                    if family_is_a { "A" } else { "B" },
                                    fill.hint
                                ),
                            ));
                        }
                    }
                }
            }
            added |= !born.is_empty();
            children.extend(born);
        }
        if !added {
            break;
        }
    }
    Ok(())
}

/// Counts what a design traces and stops it, with an error naming the
/// spec, when it grows beyond [`MAX_DESIGN_POINTS`].
struct Budget<'a> {
    used: std::cell::Cell<usize>,
    max: usize,
    path: &'a Path,
}

impl Budget<'_> {
    fn new<'a>(spec: &TraceSpec, path: &'a Path) -> Budget<'a> {
        Budget {
            used: std::cell::Cell::new(0),
            max: if spec.surface == SurfaceName::SchwarzD {
                MAX_DESIGN_POINTS / 4
            } else {
                MAX_DESIGN_POINTS
            },
            path,
        }
    }
    fn charge(&self, points: usize) {
        self.used.set(self.used.get().saturating_add(points));
    }
    fn check(&self) -> Result<()> {
        if self.used.get() > self.max {
            return Err(Error::input(
                self.path,
                Location::Field("clip".into()),
                format!(
                    "the design grows beyond {} points: shrink the clip or raise spacing_mm or sampling.step_mm",
                    self.max
                ),
            ));
        }
        Ok(())
    }
}

/// Most curves a design may seed on each side of the seed, per family.
pub const MAX_CURVES_PER_SIDE: usize = 1000;

/// The network of a periodic surface: traced on its fundamental patch and
/// unfolded across the patch's edges by the surface's half-turn symmetries.
fn design_periodic(
    spec: &TraceSpec,
    path: &Path,
    surface: &Placed,
    clip: &Clip,
    opts: TraceOptions,
) -> Result<(RawNetwork, DesignReport)> {
    use crate::design::periodic::{
        schwarz_d_patch, unfold_through, Placement, Site, Unfolded, WorldField,
    };
    let edges = schwarz_d_patch(surface);
    let seed_uv = DVec2::from_array(spec.seed.unwrap_or_default());
    let seed_err = |what: String| Error::input(path, Location::Field("seed".into()), what);
    let seed = Site {
        placement: Placement::IDENTITY,
        uv: seed_uv,
    };
    let curvature = surface.curvature(seed_uv);
    let (a_dir, b_dir) = curvature.asymptotic(opts.flat_k_per_mm2).ok_or_else(|| {
        seed_err("the seed is a flat point: no asymptotic curves through it".into())
    })?;
    if spec.net != Net::Asymptotic {
        return Err(Error::input(
            path,
            Location::Field("net".into()),
            "a periodic network is asymptotic",
        ));
    }
    let budget = Budget::new(spec, path);
    let trace = |site: Site, dir: DVec3| {
        let u = unfold_through(
            surface,
            &edges,
            WorldField::Asymptotic,
            site,
            dir,
            clip,
            opts,
        );
        budget.charge(u.points_world_mm.len());
        u
    };
    let a0 = trace(seed, a_dir);
    let b0 = trace(seed, b_dir);
    if a0.length_mm() < 1.0 || b0.length_mm() < 1.0 {
        return Err(Error::input(
            path,
            Location::Field("clip".into()),
            "the clip leaves no curve through the seed",
        ));
    }
    // World tangent of an unfolded curve at a station.
    let tangent = |u: &Unfolded, s: f64| {
        let k = u
            .stations_mm
            .partition_point(|&x| x <= s)
            .clamp(1, u.points_world_mm.len() - 1);
        (u.points_world_mm[k] - u.points_world_mm[k - 1]).normalize_or_zero()
    };
    // The other family's direction at a site: the asymptotic direction most
    // transverse to the parent curve's tangent, in world terms.
    let transverse = |site: &Site, parent: DVec3| -> Option<DVec3> {
        let c = surface.curvature(site.uv);
        let (a, b) = c.asymptotic(opts.flat_k_per_mm2)?;
        let (wa, wb) = (site.placement.vector(a), site.placement.vector(b));
        Some(if wa.dot(parent).abs() < wb.dot(parent).abs() {
            wa
        } else {
            wb
        })
    };
    let d = spec.spacing_mm;
    let max_k = spec.max_curves_per_side;
    let station_of_seed = |u: &Unfolded| u.seed_station_mm;
    let mut a_curves: Vec<(i64, Unfolded)> = Vec::new();
    let mut b_curves: Vec<(i64, Unfolded)> = Vec::new();
    for (k, s) in marks(station_of_seed(&a0), a0.length_mm(), d, max_k) {
        let site = a0.site_at(s);
        if let Some(dir) = transverse(&site, tangent(&a0, s)) {
            b_curves.push((k, trace(site, dir)));
        }
        budget.check()?;
    }
    for (k, s) in marks(station_of_seed(&b0), b0.length_mm(), d, max_k) {
        let site = b0.site_at(s);
        if let Some(dir) = transverse(&site, tangent(&b0, s)) {
            a_curves.push((k, trace(site, dir)));
        }
        budget.check()?;
    }
    // The families gathered and filled: where the central curves left gaps
    // (beyond flat vertices, in the clip's far corners), more curves seeded
    // along the other family.
    gather(
        (&mut a_curves, &mut b_curves),
        (a0, b0),
        Fill {
            spec,
            path,
            budget: &budget,
            hint: "shrink the clip, raise spacing_mm or max_curves_per_side",
        },
        |parent: &Unfolded, s| (parent.site_at(s), s),
        |(site, _)| site.placement.point(surface.point(site.uv)),
        |_, parent, (site, s)| transverse(&site, tangent(parent, s)).map(|dir| trace(site, dir)),
    )?;

    // Edges: the clip's faces on the unfolded surface, from the curve ends on them.
    let mut starts: Vec<(usize, Site, DVec3)> = Vec::new();
    for u in a_curves.iter().chain(&b_curves).map(|c| &c.1) {
        for (stop, i) in [(u.stop_start, 0), (u.stop_end, u.points_world_mm.len() - 1)] {
            if stop != Stop::Clip {
                continue;
            }
            if let Some(f) = clip.face_of(u.sites[i].uv, u.points_world_mm[i]) {
                starts.push((f, u.sites[i], u.points_world_mm[i]));
            }
        }
    }
    starts.sort_by(|a, b| {
        a.0.cmp(&b.0)
            .then(a.2.x.total_cmp(&b.2.x))
            .then(a.2.y.total_cmp(&b.2.y))
            .then(a.2.z.total_cmp(&b.2.z))
    });
    let mut edge_curves: Vec<(usize, Unfolded)> = Vec::new();
    for (face, site, p) in starts {
        if edge_curves
            .iter()
            .any(|(f, e)| *f == face && near_polyline(&e.points_world_mm, p, 0.5))
        {
            continue;
        }
        let Face::Plane { point, normal } = clip.faces[face] else {
            continue;
        };
        let field = WorldField::Level {
            point_mm: point,
            normal,
        };
        let world_normal = site.placement.normal(surface.normal(site.uv));
        let along = world_normal.cross(normal);
        let region = AlongFace { clip, face };
        let Some(dir) = along.try_normalize() else {
            continue;
        };
        let e = unfold_through(surface, &edges, field, site, dir, &region, opts);
        budget.charge(e.points_world_mm.len());
        budget.check()?;
        if e.points_world_mm.len() >= 2 && e.length_mm() > 1.0 {
            edge_curves.push((face, e));
        }
    }
    let finished = |u: Unfolded| FinishedCurve {
        points_world_mm: u.points_world_mm,
        normals_world: u.normals_world,
        stops: (u.stop_start, u.stop_end),
    };
    Ok(assemble(
        spec,
        path,
        a_curves.into_iter().map(|c| finished(c.1)).collect(),
        b_curves.into_iter().map(|c| finished(c.1)).collect(),
        edge_curves.into_iter().map(|c| finished(c.1)).collect(),
    ))
}
