//! Periodic surfaces: trace on one fundamental patch and unfold across its
//! edges by the surface's symmetries.
//!
//! Schwarz D is tiled by copies of one skew quadrilateral (four edges of a
//! regular tetrahedron), each edge a straight line on the surface and the
//! axis of a 180° rotation that maps the surface to itself. A curve traced on
//! the patch that reaches an edge continues on the neighbouring copy: in the
//! patch's own parameters it restarts at the same point in the rotated
//! direction, and the copy's world placement is the old one composed with
//! the rotation. Asymptotic curves stay asymptotic (the rotation is an
//! isometry) and keep their family across the edge (chosen by direction).

use crate::design::surface::{
    curvature_of, Placed, Surface, SCHWARZ_D_EDGE_MIDPOINT, SCHWARZ_D_RADIUS,
};
use crate::design::trace::{pieces, trace_from, Field, Region, Stop, TraceOptions};
use glam::{DMat3, DVec2, DVec3};

/// A rigid motion of a patch copy: world = rotation · local + translation.
/// `flipped` when the copy's normals point against the patch's own.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// Rotation from the patch's frame to the world (proper, orthonormal).
    pub rotation: DMat3,
    /// Translation after the rotation, world frame, mm.
    pub translation: DVec3,
    /// The copy's normals point against the patch's own (an odd number of half-turns).
    pub flipped: bool,
}

impl Placement {
    /// The fundamental patch itself: no rotation, no translation, not flipped.
    pub const IDENTITY: Placement = Placement {
        rotation: DMat3::IDENTITY,
        translation: DVec3::ZERO,
        flipped: false,
    };
    /// The world point (mm) of a point `p` in the patch's frame (mm).
    pub fn point(&self, p: DVec3) -> DVec3 {
        self.rotation * p + self.translation
    }
    /// The world direction of a direction `v` in the patch's frame (rotation only).
    pub fn vector(&self, v: DVec3) -> DVec3 {
        self.rotation * v
    }
    /// The world normal of a local normal, oriented continuously across copies.
    pub fn normal(&self, n: DVec3) -> DVec3 {
        let w = self.rotation * n;
        if self.flipped {
            -w
        } else {
            w
        }
    }
    /// This placement composed with a local half-turn about `edge`.
    fn across(&self, edge: &Edge) -> Placement {
        let r = edge.half_turn();
        // local ↦ R·(p − m) + m, then this placement.
        Placement {
            rotation: self.rotation * r,
            translation: self.rotation * (edge.point - r * edge.point) + self.translation,
            flipped: !self.flipped,
        }
    }
    /// Local coordinates of a world point / vector.
    fn local_point(&self, p: DVec3) -> DVec3 {
        self.rotation.transpose() * (p - self.translation)
    }
    fn local_vector(&self, v: DVec3) -> DVec3 {
        self.rotation.transpose() * v
    }
}

/// A straight edge of the fundamental patch: a line through `point` along
/// unit `dir`, with the side of the patch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Edge {
    /// A point of the edge line (the edge's midpoint), in the placed surface's frame, mm.
    pub point: DVec3,
    /// Unit direction of the edge line, in the placed surface's frame.
    pub dir: DVec3,
    inside_sign: f64,
}

impl Edge {
    /// Signed side of a surface point (with its normal): ((p − m) × l)·n,
    /// positive inside the patch, zero on the edge line.
    fn side(&self, p: DVec3, n: DVec3) -> f64 {
        self.inside_sign * (p - self.point).cross(self.dir).dot(n)
    }
    /// The 180° rotation about the edge's direction (linear part).
    fn half_turn(&self) -> DMat3 {
        let l = self.dir;
        DMat3::from_cols(l * (2.0 * l.x), l * (2.0 * l.y), l * (2.0 * l.z)) - DMat3::IDENTITY
    }
}

/// The fundamental skew quadrilateral of a placed Schwarz D surface: its four
/// straight edges through z = (√2 − 1)·e^{i(π/4 + kπ/2)}, perpendicular there
/// to the straight diagonals through the centre.
pub fn schwarz_d_patch(surface: &Placed) -> Vec<Edge> {
    let centre = surface.point(DVec2::ZERO);
    let n_centre = surface.normal(DVec2::ZERO);
    (0..4)
        .map(|k| {
            let ang = std::f64::consts::FRAC_PI_4 + k as f64 * std::f64::consts::FRAC_PI_2;
            let ray = DVec2::new(ang.cos(), ang.sin());
            let uv = ray * SCHWARZ_D_EDGE_MIDPOINT;
            let j = surface.derivatives(uv);
            let along = (j.pu * ray.x + j.pv * ray.y).normalize();
            let n = curvature_of(&j).normal;
            let dir = n.cross(along).normalize();
            let point = surface.point(uv);
            let mut e = Edge {
                point,
                dir,
                inside_sign: 1.0,
            };
            if e.side(centre, n_centre) < 0.0 {
                e.inside_sign = -1.0;
            }
            e
        })
        .collect()
}

/// Inside the patch (all edges) and, placed in the world, inside the clip.
struct PatchRegion<'a> {
    surface: &'a Placed,
    edges: &'a [Edge],
    placement: Placement,
    clip: &'a dyn Region,
}

impl Region for PatchRegion<'_> {
    fn contains(&self, uv: DVec2, p: DVec3) -> bool {
        if uv.length() >= SCHWARZ_D_RADIUS {
            return false;
        }
        let n = self.surface.normal(uv);
        self.edges.iter().all(|e| e.side(p, n) >= -1e-9)
            && self.clip.contains(uv, self.placement.point(p))
    }
}

/// What a curve follows across copies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WorldField {
    /// An asymptotic family, told apart by direction at each edge.
    Asymptotic,
    /// The level set of a world plane (point, unit normal): a clip edge.
    Level {
        /// A point of the plane, world frame, mm.
        point_mm: DVec3,
        /// Unit normal of the plane, world frame.
        normal: DVec3,
    },
}

/// A point of an unfolded curve: which copy and where in the patch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Site {
    /// Which copy of the patch.
    pub placement: Placement,
    /// Parameters (u, v) in the fundamental patch, |(u, v)| < the Schwarz D domain radius.
    pub uv: DVec2,
}

/// A curve traced across copies of the patch.
///
/// Guarantees (from [`unfold_through`]): samples at equal arc length, at most
/// `max_step_mm` apart (more where the curve turns tightly); `sites`,
/// `points_world_mm`, `normals_world` and `stations_mm` index-aligned; the
/// ends exactly where the trace stopped.
#[derive(Debug, Clone, PartialEq)]
pub struct Unfolded {
    /// Copy and patch parameters of every sample, index-aligned with the points.
    pub sites: Vec<Site>,
    /// Samples at equal arc length, world frame, mm; at least one.
    pub points_world_mm: Vec<DVec3>,
    /// Unit surface normal at every sample, world frame, oriented continuously across copies.
    pub normals_world: Vec<DVec3>,
    /// Arc length of every sample from the first, mm (ascending, 0 first).
    pub stations_mm: Vec<f64>,
    /// Why the curve ended at its first sample.
    pub stop_start: Stop,
    /// Why the curve ended at its last sample.
    pub stop_end: Stop,
    /// Station of the site the curve was traced through.
    pub seed_station_mm: f64,
}

impl Unfolded {
    /// Arc length of the curve, mm (0 for a single point).
    pub fn length_mm(&self) -> f64 {
        *self.stations_mm.last().unwrap_or(&0.0)
    }
    /// The site at a station (linear in the patch parameters within a step).
    pub fn site_at(&self, station_mm: f64) -> Site {
        let k = self
            .stations_mm
            .partition_point(|&s| s <= station_mm)
            .clamp(1, self.sites.len() - 1);
        let (a, b) = (self.sites[k - 1], self.sites[k]);
        let (s0, s1) = (self.stations_mm[k - 1], self.stations_mm[k]);
        let t = if s1 > s0 {
            ((station_mm - s0) / (s1 - s0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        if a.placement != b.placement {
            return if t < 0.5 { a } else { b };
        }
        Site {
            placement: a.placement,
            uv: a.uv.lerp(b.uv, t),
        }
    }
}

/// Most copies one curve may cross.
const MAX_UNFOLDS: usize = 2000;

/// The local field at a site whose world direction should be close to `world_dir`.
fn local_field(
    surface: &Placed,
    field: WorldField,
    site: &Site,
    world_dir: DVec3,
    flat: f64,
) -> Option<(Field, DVec3)> {
    let local_dir = site.placement.local_vector(world_dir);
    match field {
        WorldField::Asymptotic => {
            let c = curvature_of(&surface.derivatives(site.uv));
            let (a, b) = c.asymptotic(flat)?;
            Some(if a.dot(local_dir).abs() >= b.dot(local_dir).abs() {
                (Field::AsymptoticA, a * a.dot(local_dir).signum())
            } else {
                (Field::AsymptoticB, b * b.dot(local_dir).signum())
            })
        }
        WorldField::Level { point_mm, normal } => {
            let f = Field::Level {
                point_mm: site.placement.local_point(point_mm),
                normal: site.placement.local_vector(normal),
            };
            let d = f.direction(surface, site.uv, flat).ok()?;
            Some((f, d * d.dot(local_dir).signum()))
        }
    }
}

/// One segment of an unfolded one-way trace: the local field and its local
/// direction at the segment's start (None for the zero-length hop between
/// copies and the segment that closes a loop).
type Segment = Option<(Field, DVec3)>;

/// One direction of an unfolded trace: sites, stations, and per segment
/// what to integrate it with.
struct OneWay {
    sites: Vec<Site>,
    stations: Vec<f64>,
    segments: Vec<Segment>,
    stop: Stop,
}

impl OneWay {
    fn length_mm(&self) -> f64 {
        *self.stations.last().unwrap_or(&0.0)
    }
    /// The site at station `s` (integrated from its segment's start).
    fn site_at(&self, surface: &Placed, opts: TraceOptions, s: f64) -> Site {
        let n = self.sites.len();
        if n < 2 || s <= 0.0 {
            return self.sites[0];
        }
        if s >= self.length_mm() {
            return self.sites[n - 1];
        }
        let k = (self.stations.partition_point(|&x| x <= s) - 1).min(n - 2);
        let a = self.sites[k];
        let delta = s - self.stations[k];
        match self.segments[k] {
            Some((field, dir)) if delta > 0.0 => {
                let run = crate::design::trace::Run {
                    uv: vec![a.uv, self.sites[k + 1].uv],
                    stations_mm: vec![0.0, self.stations[k + 1] - self.stations[k]],
                    dirs: vec![dir],
                    stop: Stop::Clip,
                };
                Site {
                    placement: a.placement,
                    uv: run.uv_at(surface, field, opts, delta),
                }
            }
            _ => a,
        }
    }
}

/// Trace one way from a site in the world direction `dir`, unfolding across
/// the patch's edges; stops where the world clip (or a singularity) stops it.
fn unfold_one_way(
    surface: &Placed,
    edges: &[Edge],
    field: WorldField,
    start: Site,
    dir: DVec3,
    clip: &dyn Region,
    opts: TraceOptions,
) -> OneWay {
    let mut w = OneWay {
        sites: vec![start],
        stations: vec![0.0],
        segments: Vec::new(),
        stop: Stop::MaxLength,
    };
    let mut site = start;
    let mut world_dir = dir;
    let mut short = 0;
    let done = |mut w: OneWay, stop: Stop| {
        w.stop = stop;
        w
    };
    for _ in 0..MAX_UNFOLDS {
        let Some((local, local_dir)) =
            local_field(surface, field, &site, world_dir, opts.flat_k_per_mm2)
        else {
            return done(w, Stop::FlatPoint);
        };
        let region = PatchRegion {
            surface,
            edges,
            placement: site.placement,
            clip,
        };
        // The length limit holds for the whole curve, across copies.
        let travelled = w.length_mm();
        if travelled >= opts.max_length_mm {
            return done(w, Stop::MaxLength);
        }
        let piece_opts = TraceOptions {
            max_length_mm: opts.max_length_mm - travelled,
            ..opts
        };
        let run = trace_from(surface, local, site.uv, local_dir, &region, piece_opts);
        let base = travelled;
        let start_world = start.placement.point(surface.point(start.uv));
        for (k, (q, s)) in run.uv.iter().zip(&run.stations_mm).enumerate().skip(1) {
            w.sites.push(Site {
                placement: site.placement,
                uv: *q,
            });
            w.stations.push(base + s);
            w.segments.push(Some((local, run.dirs[k - 1])));
            // Back at the start after going some way, in any copy: a loop.
            let gap = site
                .placement
                .point(surface.point(*q))
                .distance(start_world);
            if base + s > 4.0 * opts.max_step_mm && gap < 0.5 * opts.max_step_mm {
                w.sites.push(start);
                w.stations.push(base + s + gap);
                w.segments.push(None);
                return done(w, Stop::ClosedLoop);
            }
        }
        let uv = &run.uv;
        let st = &run.stations_mm;
        let stop = run.stop;
        let end = *uv.last().unwrap_or(&site.uv);
        if stop != Stop::Clip {
            return done(w, stop);
        }
        // Which boundary: the world clip ends the curve, a patch edge unfolds it.
        let p = surface.point(end);
        let n = surface.normal(end);
        let world_p = site.placement.point(p);
        let (k, dist) = edges
            .iter()
            .enumerate()
            .map(|(k, e)| (k, e.side(p, n).abs()))
            .fold(
                (usize::MAX, f64::INFINITY),
                |a, b| if b.1 < a.1 { b } else { a },
            );
        if dist > 1e-4 || !clip.contains(end, world_p) {
            return done(w, Stop::Clip);
        }
        short = if st.last().copied().unwrap_or(0.0) < 1e-6 {
            short + 1
        } else {
            0
        };
        if short >= 2 {
            return done(w, Stop::StepTooSmall);
        }
        // The direction of arrival, turned by the half-turn about the edge.
        let j = surface.derivatives(end);
        let arrive_local = {
            let k2 = uv.len();
            let prev = if k2 >= 2 { uv[k2 - 2] } else { site.uv };
            let d = end - prev;
            (j.pu * d.x + j.pv * d.y)
                .try_normalize()
                .unwrap_or(local_dir)
        };
        let edge = &edges[k];
        let next = site.placement.across(edge);
        // In the copy, the curve continues from the same local point along
        // R·(arrival); in world terms that is the arrival direction itself.
        world_dir = site.placement.vector(arrive_local);
        site = Site {
            placement: next,
            uv: end,
        };
        w.sites.push(site);
        w.stations.push(w.length_mm());
        w.segments.push(None);
    }
    done(w, Stop::MaxLength)
}

/// Trace a curve through a site both ways, unfolding across edges, and
/// sample it uniformly: n = ⌈length / max_step_mm⌉ equal pieces of arc
/// length (more where it turns more than [`crate::design::trace::MAX_SAMPLE_TURN_RAD`] between samples),
/// each point integrated to from the trace's own steps, the ends
/// exactly where the trace stopped.
pub fn unfold_through(
    surface: &Placed,
    edges: &[Edge],
    field: WorldField,
    seed: Site,
    world_dir: DVec3,
    clip: &dyn Region,
    opts: TraceOptions,
) -> Unfolded {
    let fwd = unfold_one_way(surface, edges, field, seed, world_dir, clip, opts);
    let bwd = unfold_one_way(surface, edges, field, seed, -world_dir, clip, opts);
    let back = bwd.length_mm();
    let total = back + fwd.length_mm();
    let sample = |n: usize| {
        let mut out = Unfolded {
            sites: Vec::with_capacity(n + 1),
            points_world_mm: Vec::with_capacity(n + 1),
            normals_world: Vec::with_capacity(n + 1),
            stations_mm: Vec::with_capacity(n + 1),
            stop_start: bwd.stop,
            stop_end: fwd.stop,
            seed_station_mm: back,
        };
        for i in 0..=n {
            let s = total * i as f64 / n as f64;
            let site = if i == 0 {
                *bwd.sites.last().unwrap_or(&seed)
            } else if i == n {
                *fwd.sites.last().unwrap_or(&seed)
            } else if s < back {
                bwd.site_at(surface, opts, back - s)
            } else {
                fwd.site_at(surface, opts, s - back)
            };
            let p = site.placement.point(surface.point(site.uv));
            // A curve shorter than a nanometre is one point.
            if out
                .points_world_mm
                .last()
                .is_some_and(|q: &DVec3| q.distance(p) < 1e-6)
            {
                continue;
            }
            out.normals_world
                .push(site.placement.normal(surface.normal(site.uv)));
            out.points_world_mm.push(p);
            out.sites.push(site);
            out.stations_mm.push(s);
        }
        out
    };
    let mut n = pieces(total, opts.max_step_mm);
    let mut out = sample(n);
    while let Some(finer) = crate::design::trace::finer_pieces(&out.points_world_mm, n, total) {
        n = finer;
        out = sample(n);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::surface::SchwarzD;
    use std::sync::Arc;

    fn placed() -> Placed {
        Placed {
            surface: Arc::new(SchwarzD),
            scale_mm: 1000.0,
            rotation: DMat3::IDENTITY,
            translation_mm: DVec3::ZERO,
        }
    }

    #[test]
    fn patch_edges_form_a_regular_tetrahedron_quadrilateral() {
        let s = placed();
        let edges = schwarz_d_patch(&s);
        // Opposite edges perpendicular, adjacent edges at 60° (tetrahedron).
        for k in 0..4 {
            let (a, b, c) = (edges[k].dir, edges[(k + 1) % 4].dir, edges[(k + 2) % 4].dir);
            assert!(a.dot(c).abs() < 1e-9, "opposite edges perpendicular");
            assert!(
                (a.dot(b).abs() - 0.5).abs() < 1e-9,
                "adjacent edges at 60°: {}",
                a.dot(b)
            );
        }
        // The half-turn about an edge maps the surface to itself: a point of
        // the patch near the edge goes to a point on the surface's copy, which
        // the unfolded trace reaches; here check R is a proper rotation.
        let r = edges[0].half_turn();
        assert!((r.determinant() - 1.0).abs() < 1e-12);
        assert!((r * edges[0].dir - edges[0].dir).length() < 1e-12);
    }

    #[test]
    fn the_straight_diagonal_continues_straight_across_the_edge() {
        let s = placed();
        let edges = schwarz_d_patch(&s);
        let clip = crate::design::trace::Everywhere;
        let seed = Site {
            placement: Placement::IDENTITY,
            uv: DVec2::ZERO,
        };
        let dir = DVec3::new(1.0, -1.0, 0.0).normalize();
        let opts = TraceOptions {
            max_length_mm: 3000.0,
            ..TraceOptions::default()
        };
        let u = unfold_through(&s, &edges, WorldField::Asymptotic, seed, dir, &clip, opts);
        assert!(
            (u.length_mm() - 6000.0).abs() < 1e-6,
            "3 m each way: {}",
            u.length_mm()
        );
        // The line through the centre is straight in every copy it crosses.
        let (p0, p1) = (
            u.points_world_mm[0],
            u.points_world_mm[u.points_world_mm.len() - 1],
        );
        let axis = (p1 - p0).normalize();
        for p in &u.points_world_mm {
            assert!(
                (*p - p0).cross(axis).length() < 1e-6,
                "off the line by {}",
                (*p - p0).cross(axis).length()
            );
        }
        assert!(
            u.length_mm() > 2000.0,
            "crosses several copies: {}",
            u.length_mm()
        );
        assert!(u.sites.iter().any(|s| s.placement != Placement::IDENTITY));
    }
}
