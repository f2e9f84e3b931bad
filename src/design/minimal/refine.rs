//! 1 → 4 refinement: every triangle split at its edge midpoints.

use super::Film;
use std::collections::HashMap;

/// Split every triangle into four at its edge midpoints, in 3D and in the
/// chart. A boundary edge (one triangle) lies on one straight segment of
/// its boundary polyline (the polyline's corners are vertices of the
/// coarsest mesh already), so its midpoint lies on the polyline: it is a
/// fixed vertex. New vertices are numbered in order of the triangles.
pub fn split(film: &Film) -> Film {
    let mut uses: HashMap<(u32, u32), u32> = HashMap::with_capacity(film.triangles.len() * 2);
    for t in &film.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *uses.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    let mut out = Film {
        positions: film.positions.clone(),
        chart: film.chart.clone(),
        triangles: Vec::with_capacity(film.triangles.len() * 4),
        fixed: film.fixed.clone(),
    };
    let mut mid: HashMap<(u32, u32), u32> = HashMap::with_capacity(uses.len());
    for t in &film.triangles {
        let mut m = [0u32; 3];
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let key = (a.min(b), a.max(b));
            m[k] = *mid.entry(key).or_insert_with(|| {
                let (a, b) = (a as usize, b as usize);
                out.positions
                    .push(0.5 * (film.positions[a] + film.positions[b]));
                out.chart.push(0.5 * (film.chart[a] + film.chart[b]));
                out.fixed.push(uses[&key] == 1);
                (out.positions.len() - 1) as u32
            });
        }
        out.triangles.push([t[0], m[0], m[2]]);
        out.triangles.push([m[0], t[1], m[1]]);
        out.triangles.push([m[2], m[1], t[2]]);
        out.triangles.push([m[0], m[1], m[2]]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};

    #[test]
    fn a_square_of_two_triangles_splits_into_eight_with_five_new_vertices() {
        let film = Film {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            chart: vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            fixed: vec![true; 4],
        };
        let r = split(&film);
        assert_eq!(r.triangles.len(), 8);
        assert_eq!(r.positions.len(), 9);
        // The diagonal's midpoint is the only free vertex.
        let free: Vec<usize> = (0..9).filter(|&v| !r.fixed[v]).collect();
        assert_eq!(free.len(), 1);
        assert_eq!(r.positions[free[0]], DVec3::new(0.5, 0.5, 0.0));
        for t in &r.triangles {
            let [a, b, c] = t.map(|v| r.chart[v as usize]);
            assert!((b - a).perp_dot(c - a) > 0.0);
        }
    }
}
