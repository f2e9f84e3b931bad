//! Network design: from a trace spec to a network of traced curves.
//!
//! Input: a [`TraceSpec`] (surface, scale and placement, seed, spacing, clip,
//! sampling). Output: a [`RawNetwork`] in mm with normals: families A and B
//! (asymptotic, or principal for the façade web) and the cut boundary as
//! `edge` curves. Curves are traced with [`trace`]; the design seeds
//! them at the spacing along the curves through the seed (`central`) or
//! alternately along the last curve of the other family (`alternating`).

pub mod periodic;
pub mod surface;
pub mod trace;

use crate::error::{Error, Location, Result};
use crate::io::trace_spec::{ClipSpec, Design, Net, SurfaceName, TraceSpec};
use crate::network::{Family, RawCurve, RawNetwork, Unit};
use glam::{DMat3, DVec2, DVec3};
use std::path::Path;
use std::sync::Arc;
use surface::{Placed, Surface};
use trace::{trace_through, Field, Region, Stop, TraceOptions, Traced};

/// The placed surface of a spec.
pub fn placed_surface(spec: &TraceSpec) -> Placed {
    let base: Arc<dyn Surface> = match spec.surface {
        SurfaceName::Enneper => Arc::new(surface::Enneper),
        SurfaceName::Catenoid => Arc::new(surface::Catenoid { c: spec.c }),
        SurfaceName::Helicoid => Arc::new(surface::Helicoid { c: spec.c }),
        SurfaceName::Scherk => Arc::new(surface::Scherk),
        SurfaceName::SchwarzD => Arc::new(surface::SchwarzD),
        SurfaceName::Hypar => Arc::new(surface::Hypar { c: spec.c }),
    };
    let [rx, ry, rz] = spec.placement.rotate_deg.map(f64::to_radians);
    Placed {
        surface: base,
        scale_mm: spec.scale_mm,
        rotation: DMat3::from_rotation_z(rz)
            * DMat3::from_rotation_y(ry)
            * DMat3::from_rotation_x(rx),
        translation_mm: DVec3::from_array(spec.placement.translate_mm),
    }
}

/// One face of a clip region: a plane in space or a segment in the parameter plane.
#[derive(Debug, Clone, Copy)]
enum Face {
    /// Points with (p − point)·normal ≤ 0 are inside.
    Plane { point: DVec3, normal: DVec3 },
    /// Parameter-plane segment a→b of a counter-clockwise polygon.
    Param { a: DVec2, b: DVec2 },
}

/// A clip region: where traces stay.
pub struct Clip {
    faces: Vec<Face>,
    /// Plan polygon (x, y) for prism clips; faces hold its sides too.
    prism: Option<Vec<DVec2>>,
    /// Parameter polygon for parameter clips.
    param: Option<Vec<DVec2>>,
    slack_mm: f64,
}

impl Clip {
    fn from_spec(spec: Option<&ClipSpec>) -> Clip {
        let mut faces = Vec::new();
        let (mut prism, mut param) = (None, None);
        match spec {
            None => {}
            Some(ClipSpec::Box { min_mm, max_mm }) => {
                for axis in 0..3 {
                    let mut n = DVec3::ZERO;
                    n[axis] = 1.0;
                    faces.push(Face::Plane {
                        point: DVec3::from_array(*max_mm),
                        normal: n,
                    });
                    faces.push(Face::Plane {
                        point: DVec3::from_array(*min_mm),
                        normal: -n,
                    });
                }
            }
            Some(ClipSpec::Plane { point_mm, normal }) => faces.push(Face::Plane {
                point: DVec3::from_array(*point_mm),
                normal: DVec3::from_array(*normal).normalize_or_zero(),
            }),
            Some(ClipSpec::Polygon {
                points_mm,
                z_min_mm,
                z_max_mm,
            }) => {
                let pts = ccw(points_mm.iter().map(|p| DVec2::from_array(*p)).collect());
                for k in 0..pts.len() {
                    let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
                    let out = DVec2::new(b.y - a.y, a.x - b.x).normalize_or_zero();
                    faces.push(Face::Plane {
                        point: a.extend(0.0),
                        normal: out.extend(0.0),
                    });
                }
                if let Some(z) = z_min_mm {
                    faces.push(Face::Plane {
                        point: DVec3::new(0.0, 0.0, *z),
                        normal: -DVec3::Z,
                    });
                }
                if let Some(z) = z_max_mm {
                    faces.push(Face::Plane {
                        point: DVec3::new(0.0, 0.0, *z),
                        normal: DVec3::Z,
                    });
                }
                prism = Some(pts);
            }
            Some(ClipSpec::Block {
                center_mm,
                size_mm,
                rotate_deg,
            }) => {
                let [rx, ry, rz] = rotate_deg.map(f64::to_radians);
                let r = DMat3::from_rotation_z(rz)
                    * DMat3::from_rotation_y(ry)
                    * DMat3::from_rotation_x(rx);
                let c = DVec3::from_array(*center_mm);
                for (axis, size) in size_mm.iter().enumerate() {
                    let n = r.col(axis);
                    let half = 0.5 * size;
                    faces.push(Face::Plane {
                        point: c + n * half,
                        normal: n,
                    });
                    faces.push(Face::Plane {
                        point: c - n * half,
                        normal: -n,
                    });
                }
            }
            Some(ClipSpec::Parameters { polygon }) => {
                let pts = ccw(polygon.iter().map(|p| DVec2::from_array(*p)).collect());
                for k in 0..pts.len() {
                    faces.push(Face::Param {
                        a: pts[k],
                        b: pts[(k + 1) % pts.len()],
                    });
                }
                param = Some(pts);
            }
        }
        Clip {
            faces,
            prism,
            param,
            slack_mm: 1e-6,
        }
    }

    /// Whether a point is inside, ignoring face `skip` (for tracing along it).
    fn contains_except(&self, uv: DVec2, p: DVec3, skip: Option<usize>) -> bool {
        if let Some(poly) = &self.prism {
            if skip.is_none() && !inside_polygon(poly, p.truncate()) {
                return false;
            }
        }
        if let Some(poly) = &self.param {
            if skip.is_none() && !inside_polygon(poly, uv) {
                return false;
            }
        }
        self.faces.iter().enumerate().all(|(i, f)| {
            if Some(i) == skip {
                return true;
            }
            match f {
                Face::Plane { point, normal } => {
                    // Polygon sides are only half-spaces for convex polygons;
                    // the polygon test above decides; here, when skipping a
                    // side, the other sides bound the segment's extent.
                    if self.prism.is_some() && skip.is_none() && normal.z == 0.0 {
                        return true;
                    }
                    (p - *point).dot(*normal) <= self.slack_mm
                }
                Face::Param { a, b } => {
                    if skip.is_none() {
                        return true;
                    }
                    let n = DVec2::new(b.y - a.y, a.x - b.x);
                    (uv - *a).dot(n) <= 1e-12
                }
            }
        })
    }

    /// The face (if any) on which a point lies.
    fn face_of(&self, uv: DVec2, p: DVec3) -> Option<usize> {
        let mut best: Option<(usize, f64)> = None;
        for (i, f) in self.faces.iter().enumerate() {
            let d = match f {
                Face::Plane { point, normal } => ((p - *point).dot(*normal)).abs(),
                Face::Param { a, b } => {
                    let t = ((uv - *a).dot(*b - *a) / (*b - *a).length_squared()).clamp(0.0, 1.0);
                    // In mm-ish terms: parameter distance scaled later by the caller's tolerance.
                    uv.distance(*a + (*b - *a) * t) * 1e3
                }
            };
            if d < 1e-3 && best.is_none_or(|(_, bd)| d < bd) {
                best = Some((i, d));
            }
        }
        best.map(|b| b.0)
    }
}

impl Region for Clip {
    fn contains(&self, uv: DVec2, p: DVec3) -> bool {
        self.contains_except(uv, p, None)
    }
}

/// A region that is the clip without one face (for tracing an edge along it).
struct AlongFace<'a> {
    clip: &'a Clip,
    face: usize,
}

impl Region for AlongFace<'_> {
    fn contains(&self, uv: DVec2, p: DVec3) -> bool {
        self.clip.contains_except(uv, p, Some(self.face))
    }
}

fn ccw(mut pts: Vec<DVec2>) -> Vec<DVec2> {
    let area: f64 = (0..pts.len())
        .map(|k| {
            let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
            a.x * b.y - b.x * a.y
        })
        .sum();
    if area < 0.0 {
        pts.reverse();
    }
    pts
}

fn inside_polygon(poly: &[DVec2], q: DVec2) -> bool {
    let mut inside = false;
    let n = poly.len();
    for k in 0..n {
        let (a, b) = (poly[k], poly[(k + n - 1) % n]);
        if (a.y > q.y) != (b.y > q.y) && q.x < (b.x - a.x) * (q.y - a.y) / (b.y - a.y) + a.x {
            inside = !inside;
        }
    }
    inside
}

/// Validate a spec before tracing (one-line errors naming the field).
fn validate(spec: &TraceSpec, path: &Path) -> Result<Option<ClipSpec>> {
    let err =
        |field: &str, what: String| Err(Error::input(path, Location::Field(field.into()), what));
    if !(spec.scale_mm.is_finite() && spec.scale_mm > 0.0) {
        return err(
            "scale_mm",
            format!("must be positive, got {}", spec.scale_mm),
        );
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
    if spec.seed.iter().any(|x| !x.is_finite()) {
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
    if spec.scale_mm > 1e7 {
        return err(
            "scale_mm",
            format!("{:e} mm per unit is beyond any structure", spec.scale_mm),
        );
    }
    if spec.scale_mm < 1.0 {
        return err(
            "scale_mm",
            format!(
                "{} mm per unit is too small a surface (at least 1)",
                spec.scale_mm
            ),
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
    if spec.fill && !spec.periodic {
        return err(
            "fill",
            "filling gaps is for periodic designs (periodic: true)".into(),
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
pub const MAX_STEP_MM: f64 = 1000.0;
/// Smallest `sampling.tolerance_mm`: below, rounding noise in the surface
/// evaluation exceeds it and steps shrink without end.
pub const MIN_TOLERANCE_MM: f64 = 1e-10;

/// Each clip's own checks: finite numbers, a size, an inside.
fn validate_clip(clip: &ClipSpec, path: &Path) -> Result<()> {
    let err = |field: &str, what: &str| {
        Err(Error::input(
            path,
            Location::Field(format!("clip.{field}")),
            what.to_string(),
        ))
    };
    let finite = |xs: &[f64]| xs.iter().all(|x| x.is_finite() && x.abs() <= 1e9);
    let area = |pts: &[[f64; 2]]| {
        0.5 * (0..pts.len())
            .map(|k| {
                let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
                a[0] * b[1] - b[0] * a[1]
            })
            .sum::<f64>()
            .abs()
    };
    match clip {
        ClipSpec::Box { min_mm, max_mm } => {
            if !finite(min_mm) || !finite(max_mm) {
                return err("box", "min_mm and max_mm must be finite numbers (mm)");
            }
            if (0..3).any(|i| min_mm[i] >= max_mm[i]) {
                return err(
                    "box",
                    "the box is empty: min_mm must be below max_mm on every axis",
                );
            }
        }
        ClipSpec::Block {
            center_mm,
            size_mm,
            rotate_deg,
        } => {
            if !finite(center_mm) || !finite(size_mm) || !finite(rotate_deg) {
                return err(
                    "block",
                    "center_mm, size_mm and rotate_deg must be finite numbers",
                );
            }
            if size_mm.iter().any(|x| *x <= 0.0) {
                return err(
                    "block.size_mm",
                    "the block is degenerate: every size must be above 0",
                );
            }
        }
        ClipSpec::Plane { point_mm, normal } => {
            if !finite(point_mm) || !finite(normal) {
                return err("plane", "point_mm and normal must be finite numbers");
            }
            if DVec3::from_array(*normal).length() < 1e-12 {
                return err("plane.normal", "must not be zero");
            }
        }
        ClipSpec::Polygon {
            points_mm,
            z_min_mm,
            z_max_mm,
        } => {
            if points_mm.len() < 3 {
                return err("polygon.points_mm", "needs at least 3 points");
            }
            if !points_mm.iter().all(|p| finite(p))
                || !z_min_mm.iter().chain(z_max_mm).all(|z| finite(&[*z]))
            {
                return err("polygon", "points_mm and heights must be finite numbers");
            }
            if area(points_mm) < 1e-6 {
                return err(
                    "polygon.points_mm",
                    "the polygon is degenerate: it encloses no area",
                );
            }
            if let (Some(lo), Some(hi)) = (z_min_mm, z_max_mm) {
                if lo >= hi {
                    return err(
                        "polygon",
                        "the prism is empty: z_min_mm must be below z_max_mm",
                    );
                }
            }
        }
        ClipSpec::Parameters { polygon } => {
            if polygon.len() < 3 {
                return err("parameters.polygon", "needs at least 3 points");
            }
            if !polygon.iter().all(|p| finite(p)) {
                return err("parameters.polygon", "must be finite numbers");
            }
            if area(polygon) < 1e-12 {
                return err(
                    "parameters.polygon",
                    "the polygon is degenerate: it encloses no area",
                );
            }
        }
    }
    Ok(())
}

/// What a design produced, besides the network.
#[derive(Debug, Clone, Default)]
pub struct DesignReport {
    pub a_curves: usize,
    pub b_curves: usize,
    pub edges: usize,
    /// (curve id, where its start stopped, where its end stopped).
    pub stops: Vec<(String, Stop, Stop)>,
    /// What a designer should look at (crossings far from 90°).
    pub warnings: Vec<String>,
}

/// Trace the network a spec describes, and check it: it has A and B
/// curves, and it passes the same validation as a network file read back
/// (lamella never writes a network it cannot read). Crossings far from 90°
/// on a minimal surface become warnings in the report.
pub fn design(spec: &TraceSpec, path: &Path) -> Result<(RawNetwork, DesignReport)> {
    let (raw, mut report) = trace_network(spec, path)?;
    let min_len = (spec.spacing_mm * 0.05).max(1.0);
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
    report.warnings = crossing_warnings(spec, &net);
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
    if spec.net == Net::Asymptotic && spec.surface == SurfaceName::Hypar {
        return Vec::new();
    }
    let curves: Vec<crate::geom::curve::SmoothCurve> = net
        .curves
        .iter()
        .map(|c| crate::geom::curve::SmoothCurve::new(&c.points_mm))
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
    let p = worst.position_mm;
    vec![format!(
        "{} A×B crossing(s) are not at 90° (the worst {:.1}°, {}×{} at ({:.0}, {:.0}, {:.0}) mm): the families of a {} net cross at right angles, so the surface passes through itself there; clip it{}",
        off.len(),
        worst.angle_deg,
        net.curves[worst.a].id,
        net.curves[worst.b].id,
        p.x,
        p.y,
        p.z,
        if spec.net == Net::Principal { "principal" } else { "minimal surface's asymptotic" },
        if spec.clip.is_none() { " (the spec has no clip)" } else { "" }
    )]
}

/// Trace the network a spec describes (unchecked).
fn trace_network(spec: &TraceSpec, path: &Path) -> Result<(RawNetwork, DesignReport)> {
    let clip_spec = validate(spec, path)?;
    let surface = placed_surface(spec);
    let clip = Clip::from_spec(clip_spec.as_ref());
    let seed = DVec2::from_array(spec.seed);
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
    if spec.periodic {
        return design_periodic(spec, path, &surface, &clip, opts);
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
    a_curves.push((0, a0));
    b_curves.push((0, b0));
    a_curves.sort_by_key(|c| c.0);
    b_curves.sort_by_key(|c| c.0);
    let min_len = (spec.spacing_mm * 0.05).max(1.0);
    a_curves.retain(|c| c.1.length_mm() >= min_len && c.1.uv.len() >= 2);
    b_curves.retain(|c| c.1.length_mm() >= min_len && c.1.uv.len() >= 2);

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
        normals: t.uv.iter().map(|&q| surface.normal(q)).collect(),
        points: t.points_mm,
        stops: (t.stop_start, t.stop_end),
    };
    Ok(assemble(
        spec,
        path,
        a_curves.into_iter().map(|c| finished(c.1)).collect(),
        b_curves.into_iter().map(|c| finished(c.1)).collect(),
        edges.into_iter().map(finished).collect(),
    ))
}

/// A traced curve ready for the network file: world points and normals.
struct FinishedCurve {
    points: Vec<DVec3>,
    normals: Vec<DVec3>,
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
                points: c.points,
                normals: Some(c.normals),
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
            curves,
        },
        report,
    )
}

/// Most sample points a design may trace (all curves and edges together);
/// a quarter of that on Schwarz D, whose points cost a numerical integral
/// each (either takes a few seconds).
pub const MAX_DESIGN_POINTS: usize = 500_000;

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

/// Rounds of filling gaps in a periodic design.
const FILL_ROUNDS: usize = 6;
/// A gap to fill: no curve of the family within this many spacings.
const FILL_GAP: f64 = 0.75;

/// Nearest-sample distance queries over curves' points (an R-tree).
struct PointIndex {
    tree: rstar::RTree<[f64; 3]>,
}

impl PointIndex {
    fn new<'a>(curves: impl Iterator<Item = &'a Vec<DVec3>>) -> PointIndex {
        PointIndex {
            tree: rstar::RTree::bulk_load(
                curves
                    .flat_map(|c| c.iter().map(|p| p.to_array()))
                    .collect(),
            ),
        }
    }
    fn add(&mut self, points: &[DVec3]) {
        for p in points {
            self.tree.insert(p.to_array());
        }
    }
    fn nearest_distance(&self, p: DVec3) -> f64 {
        self.tree
            .nearest_neighbor(&p.to_array())
            .map_or(f64::INFINITY, |q| p.distance(DVec3::from_array(*q)))
    }
}

/// Stations at k·d from `s0` (k = ±1, ±2, …) inside (0, len), with k.
fn marks(s0: f64, len: f64, d: f64, max_k: usize) -> Vec<(i64, f64)> {
    let mut out = Vec::new();
    for k in 1..=max_k as i64 {
        let s = s0 - k as f64 * d;
        if s <= 0.0 {
            break;
        }
        out.push((-k, s));
    }
    for k in 1..=max_k as i64 {
        let s = s0 + k as f64 * d;
        if s >= len {
            break;
        }
        out.push((k, s));
    }
    out
}

/// Station of the polyline point nearest to a parameter point.
fn station_of(t: &Traced, q: DVec2) -> f64 {
    let mut best = (f64::INFINITY, 0.0);
    for k in 1..t.uv.len() {
        let (a, b) = (t.uv[k - 1], t.uv[k]);
        let ab = b - a;
        let f = if ab.length_squared() > 0.0 {
            ((q - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let d = q.distance(a + ab * f);
        if d < best.0 {
            best = (
                d,
                t.stations_mm[k - 1] + f * (t.stations_mm[k] - t.stations_mm[k - 1]),
            );
        }
    }
    best.1
}

/// The first crossing of two traced curves in the parameter plane.
fn crossing_uv(p: &Traced, q: &Traced) -> Option<DVec2> {
    for i in 1..p.uv.len() {
        let (a0, a1) = (p.uv[i - 1], p.uv[i]);
        for j in 1..q.uv.len() {
            let (b0, b1) = (q.uv[j - 1], q.uv[j]);
            let r = a1 - a0;
            let s = b1 - b0;
            let den = r.perp_dot(s);
            if den.abs() < 1e-300 {
                continue;
            }
            let t = (b0 - a0).perp_dot(s) / den;
            let u = (b0 - a0).perp_dot(r) / den;
            if (0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&u) {
                return Some(a0 + r * t);
            }
        }
    }
    None
}

/// Trace the clip boundary on the surface: along every face, from the curve
/// ends lying on it, both ways until another face or the domain edge. A start
/// point already on a traced edge is skipped.
fn trace_edges<'a>(
    surface: &dyn Surface,
    clip: &Clip,
    curves: impl Iterator<Item = &'a Traced>,
    opts: TraceOptions,
    step_mm: f64,
    budget: &Budget,
) -> Result<Vec<Traced>> {
    let mut starts: Vec<(usize, DVec2)> = Vec::new();
    for t in curves {
        for (stop, q) in [(t.stop_start, t.uv[0]), (t.stop_end, t.uv[t.uv.len() - 1])] {
            if stop != Stop::Clip {
                continue;
            }
            if let Some(f) = clip.face_of(q, surface.point(q)) {
                starts.push((f, q));
            }
        }
    }
    starts.sort_by(|a, b| {
        a.0.cmp(&b.0)
            .then(a.1.x.total_cmp(&b.1.x))
            .then(a.1.y.total_cmp(&b.1.y))
    });
    let mut edges: Vec<(usize, Traced)> = Vec::new();
    for (face, q) in starts {
        let p = surface.point(q);
        // Within the chord sagitta of an edge already traced on this face.
        let covered = edges
            .iter()
            .any(|(f, e)| *f == face && near_polyline(&e.points_mm, p, 0.5));
        if covered {
            continue;
        }
        let traced = match clip.faces[face] {
            Face::Plane { point, normal } => {
                let region = AlongFace { clip, face };
                trace_through(
                    surface,
                    Field::Level {
                        point_mm: point,
                        normal,
                    },
                    q,
                    &region,
                    opts,
                )
                .ok()
            }
            Face::Param { a, b } => param_segment(surface, a, b, step_mm),
        };
        if let Some(t) = traced.filter(|t| t.uv.len() >= 2 && t.length_mm() > 1.0) {
            budget.charge(t.uv.len());
            edges.push((face, t));
        }
        budget.check()?;
    }
    Ok(edges.into_iter().map(|e| e.1).collect())
}

fn near_polyline(pts: &[DVec3], p: DVec3, tol: f64) -> bool {
    pts.windows(2).any(|w| {
        let ab = w[1] - w[0];
        let f = if ab.length_squared() > 0.0 {
            ((p - w[0]).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        p.distance(w[0] + ab * f) < tol
    })
}

/// The image of a parameter-plane segment, sampled about `step_mm` apart
/// (None when it is longer than a design may be).
fn param_segment(surface: &dyn Surface, a: DVec2, b: DVec2, step_mm: f64) -> Option<Traced> {
    let fine = 512;
    let mut len = 0.0;
    let mut prev = surface.point(a);
    for i in 1..=fine {
        let p = surface.point(a.lerp(b, i as f64 / fine as f64));
        len += p.distance(prev);
        prev = p;
    }
    let pieces = (len / step_mm).ceil();
    if !(pieces.is_finite() && pieces <= MAX_DESIGN_POINTS as f64) {
        return None;
    }
    let n = (pieces as usize).max(1) + 1;
    let uv: Vec<DVec2> = (0..n)
        .map(|i| a.lerp(b, i as f64 / (n - 1) as f64))
        .collect();
    let points_mm: Vec<DVec3> = uv.iter().map(|&q| surface.point(q)).collect();
    let mut stations_mm = vec![0.0];
    for w in points_mm.windows(2) {
        let last = *stations_mm.last().unwrap_or(&0.0);
        stations_mm.push(last + w[1].distance(w[0]));
    }
    Some(Traced {
        uv,
        points_mm,
        stations_mm,
        stop_start: Stop::Clip,
        stop_end: Stop::Clip,
    })
}

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
    let seed_uv = DVec2::from_array(spec.seed);
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
        budget.charge(u.points_mm.len());
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
            .clamp(1, u.points_mm.len() - 1);
        (u.points_mm[k] - u.points_mm[k - 1]).normalize_or_zero()
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
    a_curves.push((0, a0));
    b_curves.push((0, b0));
    a_curves.sort_by_key(|c| c.0);
    b_curves.sort_by_key(|c| c.0);
    let min_len = (spec.spacing_mm * 0.05).max(1.0);
    a_curves.retain(|c| c.1.length_mm() >= min_len && c.1.points_mm.len() >= 2);
    b_curves.retain(|c| c.1.length_mm() >= min_len && c.1.points_mm.len() >= 2);

    // Fill: where the central curves left gaps (beyond flat vertices, in the
    // clip's far corners), seed more curves along the other family wherever
    // no curve of this family passes within `FILL_GAP` spacings.
    if spec.fill {
        let mut next_k = max_k as i64 + 1;
        for _round in 0..FILL_ROUNDS {
            let mut added = false;
            for family_is_a in [true, false] {
                let (parents, children) = if family_is_a {
                    (&b_curves, &mut a_curves)
                } else {
                    (&a_curves, &mut b_curves)
                };
                let mut index = PointIndex::new(children.iter().map(|c| &c.1.points_mm));
                let mut born = Vec::new();
                for (_, parent) in parents.iter() {
                    let steps = (parent.length_mm() / (0.5 * d)).floor() as usize;
                    for i in 1..steps {
                        let s = 0.5 * d * i as f64;
                        let site = parent.site_at(s);
                        let p = site.placement.point(surface.point(site.uv));
                        if index.nearest_distance(p) < FILL_GAP * d {
                            continue;
                        }
                        let Some(dir) = transverse(&site, tangent(parent, s)) else {
                            continue;
                        };
                        let child = trace(site, dir);
                        budget.check()?;
                        if child.length_mm() >= min_len && child.points_mm.len() >= 2 {
                            index.add(&child.points_mm);
                            born.push((next_k, child));
                            next_k += 1;
                            if children.len() + born.len() > 2 * max_k + 1 {
                                return Err(Error::input(
                                    path,
                                    Location::Field("fill".into()),
                                    format!(
                                        "filling needs more than {} curves of family {} (2 × max_curves_per_side + 1): shrink the clip, raise spacing_mm or max_curves_per_side",
                                        2 * max_k + 1,
                                        if family_is_a { "A" } else { "B" }
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
    }

    // Edges: the clip's faces on the unfolded surface, from the curve ends on them.
    let mut starts: Vec<(usize, Site, DVec3)> = Vec::new();
    for u in a_curves.iter().chain(&b_curves).map(|c| &c.1) {
        for (stop, i) in [(u.stop_start, 0), (u.stop_end, u.points_mm.len() - 1)] {
            if stop != Stop::Clip {
                continue;
            }
            if let Some(f) = clip.face_of(u.sites[i].uv, u.points_mm[i]) {
                starts.push((f, u.sites[i], u.points_mm[i]));
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
            .any(|(f, e)| *f == face && near_polyline(&e.points_mm, p, 0.5))
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
        budget.charge(e.points_mm.len());
        budget.check()?;
        if e.points_mm.len() >= 2 && e.length_mm() > 1.0 {
            edge_curves.push((face, e));
        }
    }
    let finished = |u: Unfolded| FinishedCurve {
        points: u.points_mm,
        normals: u.normals,
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
