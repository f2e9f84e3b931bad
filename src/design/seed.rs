//! Seeding helpers: stations at the spacing along a curve ([`marks`]), where a
//! parameter point falls on a traced curve ([`station_of`]), the crossing of
//! two traced curves ([`crossing_uv`]) for the alternating design, and the
//! point index and limits of the fill. The seeding loops themselves
//! (central, alternating, fill) stay in the driver, `design/mod.rs`.

use super::trace::Traced;
use glam::{DVec2, DVec3};

/// Rounds of filling gaps in a periodic design.
pub(crate) const FILL_ROUNDS: usize = 6;
/// A gap to fill: no curve of the family within this many spacings.
pub(crate) const FILL_GAP: f64 = 0.75;

/// A traced curve as the fill sees it (`design::fill_gaps`).
pub(crate) trait FillCurve {
    /// Its length, mm.
    fn length_mm(&self) -> f64;
    /// Its samples, world frame, mm.
    fn points_world_mm(&self) -> &Vec<DVec3>;
}

impl FillCurve for Traced {
    fn length_mm(&self) -> f64 {
        Traced::length_mm(self)
    }
    fn points_world_mm(&self) -> &Vec<DVec3> {
        &self.points_world_mm
    }
}

impl FillCurve for super::periodic::Unfolded {
    fn length_mm(&self) -> f64 {
        super::periodic::Unfolded::length_mm(self)
    }
    fn points_world_mm(&self) -> &Vec<DVec3> {
        &self.points_world_mm
    }
}

/// Nearest-sample distance queries over curves' points: R-trees of
/// growing sizes (the logarithmic method), so that adding a curve costs a
/// bulk load of about its own size, amortised, rather than of every point
/// so far (a fill that adds thousands of curves once rebuilt one tree of
/// up to 500,000 points for each: minutes).
pub(crate) struct PointIndex {
    /// Each tree with its points, the largest first; every tree holds
    /// more than twice the points of the next.
    levels: Vec<(Vec<[f64; 3]>, Tree)>,
}

/// One level of a [`PointIndex`].
type Tree = rstar::RTree<[f64; 3]>;

impl PointIndex {
    pub(crate) fn new<'a>(curves: impl Iterator<Item = &'a Vec<DVec3>>) -> PointIndex {
        let mut index = PointIndex { levels: Vec::new() };
        let points: Vec<DVec3> = curves.flatten().copied().collect();
        index.add(&points);
        index
    }
    pub(crate) fn add(&mut self, points: &[DVec3]) {
        // Trees are bulk-loaded rather than inserted into one point at a
        // time: rstar 0.12's insertion panics ("This is a bug in rstar") on
        // some runs of coincident points, which a child traced along an
        // existing curve makes. Non-finite points (none from a sound trace)
        // are left out.
        let mut new: Vec<[f64; 3]> = points
            .iter()
            .filter(|p| p.is_finite())
            .map(|p| p.to_array())
            .collect();
        if new.is_empty() {
            return;
        }
        while self
            .levels
            .last()
            .is_some_and(|(last, _)| last.len() <= 2 * new.len())
        {
            if let Some((mut merged, _)) = self.levels.pop() {
                merged.append(&mut new);
                new = merged;
            }
        }
        self.levels
            .push((new.clone(), rstar::RTree::bulk_load(new)));
    }
    pub(crate) fn nearest_distance(&self, p: DVec3) -> f64 {
        if !p.is_finite() {
            return 0.0;
        }
        self.levels
            .iter()
            .filter_map(|(_, tree)| tree.nearest_neighbor(&p.to_array()))
            .map(|q| p.distance(DVec3::from_array(*q)))
            .fold(f64::INFINITY, f64::min)
    }
}

/// Stations at k·d from `s0` (k = ±1, ±2, …) inside (0, len), with k.
pub(crate) fn marks(s0: f64, len: f64, d: f64, max_k: usize) -> Vec<(i64, f64)> {
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
pub(crate) fn station_of(t: &Traced, q: DVec2) -> f64 {
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
pub(crate) fn crossing_uv(p: &Traced, q: &Traced) -> Option<DVec2> {
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

#[cfg(test)]
mod tests {
    use super::PointIndex;
    use glam::DVec3;

    #[test]
    fn the_index_finds_the_nearest_point_of_every_curve_added() {
        // Curves of 1 to 40 points added one by one: the trees merge, and
        // every query agrees with a scan of all points.
        let point = |i: usize| {
            let t = i as f64;
            DVec3::new((t * 0.37).sin() * 900.0, (t * 0.11).cos() * 700.0, t % 13.0)
        };
        let first: Vec<DVec3> = (0..5).map(point).collect();
        let mut index = PointIndex::new(std::iter::once(&first));
        let mut all = first.clone();
        let mut next = 5;
        for c in 0..60 {
            let curve: Vec<DVec3> = (next..next + 1 + (c * 7) % 40).map(point).collect();
            next += curve.len();
            index.add(&curve);
            all.extend(&curve);
            for q in [DVec3::ZERO, DVec3::new(500.0, -300.0, 4.0), point(next + 3)] {
                let scan = all
                    .iter()
                    .map(|p| p.distance(q))
                    .fold(f64::INFINITY, f64::min);
                assert_eq!(index.nearest_distance(q), scan);
            }
        }
        assert!(index.levels.len() <= 12, "{}", index.levels.len());
        assert_eq!(
            index.levels.iter().map(|l| l.0.len()).sum::<usize>(),
            all.len()
        );
    }
}
