//! Clip regions: where traced curves stay. A clip is a set of faces, each a
//! plane in space (box, block, plane, the sides and caps of a polygon prism)
//! or a segment in the parameter plane (parameter polygon); built from the
//! spec's [`ClipSpec`] after [`validate_clip`] has checked it. [`Clip`] is the
//! [`Region`] curves are traced in; [`AlongFace`] is the clip without one face,
//! the region an edge is traced in along that face. Coordinates are in the
//! placed surface's frame (the world), mm.

use super::trace::Region;
use crate::error::{Error, Location, Result};
use crate::spec::ClipSpec;
use glam::{DMat3, DVec2, DVec3};
use std::path::Path;

/// One face of a clip region: a plane in space or a segment in the parameter plane.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Face {
    /// Points with (p − point)·normal ≤ 0 are inside.
    Plane { point: DVec3, normal: DVec3 },
    /// Parameter-plane segment a→b of a counter-clockwise polygon.
    Param { a: DVec2, b: DVec2 },
}

/// A clip region: where traces stay.
pub struct Clip {
    pub(crate) faces: Vec<Face>,
    /// Plan polygon (x, y) for prism clips; faces hold its sides too.
    prism: Option<Vec<DVec2>>,
    /// Parameter polygon for parameter clips.
    param: Option<Vec<DVec2>>,
    slack_mm: f64,
}

impl Clip {
    pub(crate) fn from_spec(spec: Option<&ClipSpec>) -> Clip {
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
    pub(crate) fn face_of(&self, uv: DVec2, p: DVec3) -> Option<usize> {
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
pub(crate) struct AlongFace<'a> {
    pub(crate) clip: &'a Clip,
    pub(crate) face: usize,
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

/// Each clip's own checks: finite numbers, a size, an inside.
pub(crate) fn validate_clip(clip: &ClipSpec, path: &Path) -> Result<()> {
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
