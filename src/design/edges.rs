//! Edge curves: the clip boundary traced on the surface. From every curve end
//! that stopped on a clip face, the face's level curve on the surface is
//! traced both ways (a plane face) or its parameter segment sampled (a
//! parameter face); a start already on a traced edge is skipped.

use super::clip::{AlongFace, Clip, Face};
use super::surface::Surface;
use super::trace::{trace_through, Field, Stop, TraceOptions, Traced};
use super::{Budget, MAX_DESIGN_POINTS};
use crate::error::Result;
use glam::{DVec2, DVec3};

/// Trace the clip boundary on the surface: along every face, from the curve
/// ends lying on it, both ways until another face or the domain edge. A start
/// point already on a traced edge is skipped.
pub(crate) fn trace_edges<'a>(
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
            .any(|(f, e)| *f == face && near_polyline(&e.points_world_mm, p, 0.5));
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

pub(crate) fn near_polyline(pts: &[DVec3], p: DVec3, tol: f64) -> bool {
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
    let points_world_mm: Vec<DVec3> = uv.iter().map(|&q| surface.point(q)).collect();
    let mut stations_mm = vec![0.0];
    for w in points_world_mm.windows(2) {
        let last = *stations_mm.last().unwrap_or(&0.0);
        stations_mm.push(last + w[1].distance(w[0]));
    }
    Some(Traced {
        uv,
        points_world_mm,
        stations_mm,
        stop_start: Stop::Clip,
        stop_end: Stop::Clip,
    })
}
