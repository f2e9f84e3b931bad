//! Lattice blocks: many copies of one four-armed star (the star washers,
//! two per node, most of a steel kit's pieces) packed with their arms
//! interleaved instead of box by box.
//!
//! A star of two bars (width w, tips L from the centre, along e₁ = (1, 0)
//! and e₂ = (cos φ, sin φ)) fills about a fifth of its bounding box, so
//! boxes waste most of the stock. Translated copies on a lattice
//! a·u + b·v interleave: u puts the copy's e₂-bar beside the original's
//! (α = (w + g)/sin φ along e₁) and its e₁-bar just past the original's
//! e₂-tip (β along e₂, with β sin φ = L sin φ + (w/2)(1 + |cos φ|) + g),
//! and v is u mirrored. At φ = 90° that is u = (w + g, L + w/2 + g),
//! v = (−(L + w/2 + g), w + g), a cell of (w + g)² + (L + w/2 + g)²: for
//! the steel washer (w = 9.6, L = 45, g = 3.2) 2973 mm² against 8686 mm²
//! by boxes, 2.9 times denser.
//!
//! The formula is only a candidate: [`star_lattice`] accepts a lattice
//! only once the true outlines of every neighbour that could come near
//! keep at least the gap (plus 1 µm, so plan.json's
//! rounding of the placements cannot close it), by the same
//! polygon-to-polygon distance `check_nest` uses. A [`Block`] is the
//! copies of the lattice whose boxes fit a rectangle; the nest places
//! blocks by their box like any other part and spreads the copies out.
//! Deterministic: no search over floating-point ties, copies in (y, x)
//! order.

use super::model::{bbox, bounds};
use super::stock::Size;
use crate::fabricate::part::{Part, PartKind};
use crate::geom::plane;
use kurbo::{Point, Vec2};

/// Extra clearance beyond the gap, mm: plan.json rounds placements to
/// 0.1 µm, which must never bring two copies closer than the gap.
const SAFETY_MM: f64 = 1e-3;

/// A star is worth a lattice only where it beats boxes by this factor.
const MIN_GAIN: f64 = 1.2;

/// Two lattice vectors, part frame, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lattice {
    /// First basis vector, mm.
    pub u_mm: Vec2,
    /// Second basis vector, mm.
    pub v_mm: Vec2,
}

impl Lattice {
    /// The area of one cell, mm².
    pub fn cell_mm2(&self) -> f64 {
        self.u_mm.cross(self.v_mm).abs()
    }

    /// Lattice coordinates (a, b) of a point p = a·u + b·v, mm in.
    fn coords(&self, p_mm: Vec2) -> (f64, f64) {
        let det = self.u_mm.cross(self.v_mm);
        (p_mm.cross(self.v_mm) / det, self.u_mm.cross(p_mm) / det)
    }
}

/// Copies of one part in a rectangle: the lower-left corners of their
/// bounding boxes relative to the block's lower left, in (y, x) order.
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// The corners, mm.
    pub corners_mm: Vec<Point>,
    /// The part's bounding box width (along x), mm.
    pub part_w_mm: f64,
    /// The part's bounding box height (along y), mm.
    pub part_h_mm: f64,
}

impl Block {
    /// The box of the first `n` copies, mm (width along x, height along y).
    pub fn extent_mm(&self, n: usize) -> (f64, f64) {
        self.corners_mm[..n.min(self.corners_mm.len())]
            .iter()
            .fold((0.0f64, 0.0f64), |(w, h), c| {
                (w.max(c.x + self.part_w_mm), h.max(c.y + self.part_h_mm))
            })
    }

    /// Copies in the block.
    pub fn len(&self) -> usize {
        self.corners_mm.len()
    }

    /// Whether the block holds no copy.
    pub fn is_empty(&self) -> bool {
        self.corners_mm.is_empty()
    }
}

/// The star's arms read off its outline: (the two arm directions, arm
/// width, centre-to-tip length), or `None` when the outline is not a
/// centrally symmetric four-armed star with square tips.
fn star_arms(outline: &[Point]) -> Option<(Vec2, Vec2, f64, f64)> {
    let n = outline.len();
    if n != 12 {
        return None;
    }
    let (x0, y0, x1, y1) = bounds(outline);
    let c = Point::new(0.5 * (x0 + x1), 0.5 * (y0 + y1));
    // Edges by their midpoints' distance from the centre: the four
    // farthest are the tips.
    let mut edges: Vec<(f64, Point, f64)> = (0..n)
        .map(|i| {
            let (a, b) = (outline[i], outline[(i + 1) % n]);
            let mid = a.midpoint(b);
            ((mid - c).hypot(), mid, (b - a).hypot())
        })
        .collect();
    edges.sort_by(|p, q| q.0.total_cmp(&p.0));
    let tips = &edges[..4];
    let (l, w) = (tips[0].0, tips[0].2);
    if tips
        .iter()
        .any(|t| (t.0 - l).abs() > 1e-6 * l.max(1.0) || (t.2 - w).abs() > 1e-6 * w.max(1.0))
        || w <= 0.0
        || l <= w
    {
        return None;
    }
    let dirs: Vec<Vec2> = tips.iter().map(|t| (t.1 - c) / t.0).collect();
    // Two opposite pairs; e1 the direction nearest +x, e2 the other with y > 0.
    let e1 = *dirs
        .iter()
        .max_by(|a, b| a.x.total_cmp(&b.x).then(b.y.abs().total_cmp(&a.y.abs())))?;
    let e2 = dirs
        .iter()
        .copied()
        .filter(|d| d.dot(e1).abs() < 1.0 - 1e-9)
        .max_by(|a, b| a.y.total_cmp(&b.y))?;
    if dirs.iter().any(|d| {
        (*d - e1).hypot() > 1e-6
            && (*d + e1).hypot() > 1e-6
            && (*d - e2).hypot() > 1e-6
            && (*d + e2).hypot() > 1e-6
    }) {
        return None;
    }
    Some((e1, e2, w, l))
}

/// Whether copies of `outline` on lattice `lat` keep `gap` from each other:
/// every neighbour a·u + b·v whose box comes within the gap of the
/// original's is held to the true outlines' distance. Those neighbours lie
/// in the rectangle |x| < w + gap, |y| < h + gap (w × h the part's box),
/// whose lattice coordinates are bounded by its corners', so the range
/// below holds them all, however skewed the lattice.
pub fn lattice_clear(outline: &[Point], lat: &Lattice, gap_mm: f64) -> bool {
    let (x0, y0, x1, y1) = bounds(outline);
    let (rx, ry) = (x1 - x0 + gap_mm, y1 - y0 + gap_mm);
    if lat.cell_mm2() < 1e-9 {
        return false;
    }
    let (mut a_max, mut b_max) = (0.0f64, 0.0f64);
    for c in [Vec2::new(rx, ry), Vec2::new(rx, -ry)] {
        let (a, b) = lat.coords(c);
        a_max = a_max.max(a.abs());
        b_max = b_max.max(b.abs());
    }
    let (na, nb) = (a_max.ceil() as i64, b_max.ceil() as i64);
    if na > 64 || nb > 64 {
        return false;
    }
    for a in -na..=na {
        for b in -nb..=nb {
            if (a, b) == (0, 0) {
                continue;
            }
            let t = lat.u_mm * a as f64 + lat.v_mm * b as f64;
            if t.x.abs() >= rx || t.y.abs() >= ry {
                continue;
            }
            let moved: Vec<Point> = outline.iter().map(|&q| q + t).collect();
            if plane::polygon_distance(outline, &moved, gap_mm) < gap_mm {
                return false;
            }
        }
    }
    true
}

/// The interleaved lattice of a four-armed star `outline` (part frame)
/// whose copies keep `gap` apart, when it is valid and packs at least
/// [`MIN_GAIN`] times denser than boxes `gap` apart; else `None`.
pub fn star_lattice(outline: &[Point], gap_mm: f64) -> Option<Lattice> {
    let (e1, e2, w, l) = star_arms(outline)?;
    let sin = e1.cross(e2).abs();
    let cos = e1.dot(e2).abs();
    if sin < 0.5 {
        return None;
    }
    let g = gap_mm + SAFETY_MM;
    let alpha = (w + g) / sin;
    let beta = (l * sin + 0.5 * w * (1.0 + cos) + g) / sin;
    let (x0, y0, x1, y1) = bounds(outline);
    let box_cell = (x1 - x0 + gap_mm) * (y1 - y0 + gap_mm);
    // The formula's lattice, then with a little slack should a corner of
    // an oblique star come closer than the bars' model says.
    for slack in [0.0, 0.25, 0.5, 1.0, 2.0] {
        let u = e1 * (alpha + slack) + e2 * (beta + slack);
        let v = e2 * (alpha + slack) - e1 * (beta + slack);
        let lat = Lattice { u_mm: u, v_mm: v };
        if lat.cell_mm2() * MIN_GAIN > box_cell {
            return None;
        }
        // Held to half the safety: the formula's contacts are at exactly g.
        if lattice_clear(outline, &lat, gap_mm + 0.5 * SAFETY_MM) {
            return Some(lat);
        }
    }
    None
}

/// The copies of a part (bounding box `part_w_mm` × `part_h_mm`, lower left
/// at the lattice point) on `lat` whose boxes fit a `w_mm` × `h_mm` rectangle, for
/// the lattice offset (of 16 tried) that fits the most.
pub fn block(lat: &Lattice, part_w_mm: f64, part_h_mm: f64, w_mm: f64, h_mm: f64) -> Block {
    // The lattice points' room: the rectangle less one part's box.
    let (xs, ys) = (w_mm - part_w_mm, h_mm - part_h_mm);
    let mut best: Vec<Point> = Vec::new();
    if xs < 0.0 || ys < 0.0 {
        return Block {
            corners_mm: best,
            part_w_mm,
            part_h_mm,
        };
    }
    let corners = [
        Vec2::new(0.0, 0.0),
        Vec2::new(xs, 0.0),
        Vec2::new(0.0, ys),
        Vec2::new(xs, ys),
    ];
    let (mut a0, mut a1, mut b0, mut b1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for c in corners {
        let (a, b) = lat.coords(c);
        (a0, a1, b0, b1) = (a0.min(a), a1.max(a), b0.min(b), b1.max(b));
    }
    const K: i32 = 4;
    for i in 0..K {
        for j in 0..K {
            let o =
                lat.u_mm * (f64::from(i) / f64::from(K)) + lat.v_mm * (f64::from(j) / f64::from(K));
            let mut pts: Vec<Point> = Vec::new();
            for a in (a0.floor() as i64 - 1)..=(a1.ceil() as i64 + 1) {
                for b in (b0.floor() as i64 - 1)..=(b1.ceil() as i64 + 1) {
                    let p = o + lat.u_mm * a as f64 + lat.v_mm * b as f64;
                    if p.x >= -1e-9 && p.y >= -1e-9 && p.x <= xs + 1e-9 && p.y <= ys + 1e-9 {
                        pts.push(Point::new(p.x.max(0.0), p.y.max(0.0)));
                    }
                }
            }
            if pts.len() > best.len() {
                best = pts;
            }
        }
    }
    // Pushed to the block's lower left, then in (y, x) order so that a
    // prefix is the lowest rows.
    let (mx, my) = best
        .iter()
        .fold((f64::INFINITY, f64::INFINITY), |(x, y), p| {
            (x.min(p.x), y.min(p.y))
        });
    let mut corners_mm: Vec<Point> = best
        .into_iter()
        .map(|p| Point::new(p.x - mx, p.y - my))
        .collect();
    corners_mm.sort_by(|p, q| p.y.total_cmp(&q.y).then(p.x.total_cmp(&q.x)));
    Block {
        corners_mm,
        part_w_mm,
        part_h_mm,
    }
}

/// Lattice blocks tried, width (along the sheet) × height, mm: squares big enough to pack densely on bare stock, and long low
/// blocks for the lamella sheets' lane tails (a strip of height H holds
/// about (H − 90)/2973 washers per mm by the lattice against 1/93.2 by
/// boxes, so from about 125 mm up the lattice wins there too).
const BLOCKS_MM: [(f64, f64); 8] = [
    (400.0, 400.0),
    (800.0, 200.0),
    (800.0, 150.0),
    (300.0, 300.0),
    (400.0, 200.0),
    (400.0, 150.0),
    (200.0, 200.0),
    (150.0, 150.0),
];

/// Fewest copies of a star washer worth packing in lattice blocks.
const MIN_BLOCK_COPIES: u32 = 4;

/// Lattice blocks of part `p`'s copies: only for star
/// washers with enough copies, where the profile allows them unturned
/// and the lattice beats boxes ([`star_lattice`]).
pub(super) fn lattice_blocks(p: &Part, gap: f64, rotations: &[u32], sizes: &[Size]) -> Vec<Block> {
    if p.kind != PartKind::Washer || p.count < MIN_BLOCK_COPIES || !rotations.contains(&0) {
        return Vec::new();
    }
    let Some(lat) = star_lattice(&p.outline_part_mm, gap) else {
        return Vec::new();
    };
    let (x0, y0, x1, y1) = bbox(p);
    let (w, h) = (x1 - x0, y1 - y0);
    // Every block fits every size's usable sheet.
    let (room_x, room_y) = sizes
        .iter()
        .fold((f64::INFINITY, f64::INFINITY), |(x, y), z| {
            (x.min(z.lu), y.min(z.wu))
        });
    BLOCKS_MM
        .iter()
        .filter(|&&(bw, bh)| bw <= room_x && bh <= room_y)
        .map(|&(bw, bh)| block(&lat, w, h, bw, bh))
        // A block must hold more than boxes would in its square.
        .filter(|b| {
            let (bw, bh) = b.extent_mm(b.len());
            let by_boxes =
                (((bw + gap) / (w + gap)).floor() * ((bh + gap) / (h + gap)).floor()) as usize;
            b.len() > by_boxes
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fabricate::washer::star_outline;

    fn moved(outline: &[Point], t: Vec2) -> Vec<Point> {
        outline.iter().map(|&q| q + t).collect()
    }

    /// The right-angled steel washer: the lattice is the closed form
    /// u = (w + g, L + w/2 + g), v = (−(L + w/2 + g), w + g), g the gap
    /// plus the 1 µm safety, and its neighbours keep the gap.
    #[test]
    fn right_angled_star_gets_the_closed_form_lattice() {
        let star = star_outline(90.0, 45.0, 9.6);
        let gap = 3.2;
        let lat = star_lattice(&star, gap).expect("a lattice");
        let g = gap + SAFETY_MM;
        let (a, b) = (9.6 + g, 45.0 + 4.8 + g);
        assert!(
            (lat.u_mm - Vec2::new(a, b)).hypot() < 1e-9,
            "{:?}",
            lat.u_mm
        );
        assert!(
            (lat.v_mm - Vec2::new(-b, a)).hypot() < 1e-9,
            "{:?}",
            lat.v_mm
        );
        assert!((lat.cell_mm2() - (a * a + b * b)).abs() < 1e-6);
        // By hand: the copy at u has its bottom arm tip w/2 + g above the
        // original's horizontal bar, i.e. exactly g clear of it.
        let d = plane::polygon_distance(&star, &moved(&star, lat.u_mm), 10.0);
        assert!((d - g).abs() < 1e-9, "{d}");
        // Half a millimetre closer along u and they collide or come too near.
        let closer = lat.u_mm * (1.0 - 0.5 / lat.u_mm.hypot());
        assert!(plane::polygon_distance(&star, &moved(&star, closer), 10.0) < gap);
    }

    /// Oblique classes (hyperbolic paraboloids have 82°–90° nodes) get a
    /// lattice whose every near neighbour keeps the gap, checked here by
    /// brute force over a wider ring of neighbours than the search uses.
    #[test]
    fn oblique_stars_get_clear_lattices() {
        for angle in [89.5, 87.5, 85.0, 82.0, 75.0] {
            let star = star_outline(angle, 45.0, 9.6);
            let gap = 3.2;
            let lat = star_lattice(&star, gap).unwrap_or_else(|| panic!("{angle}°: none"));
            for a in -5i32..=5 {
                for b in -5i32..=5 {
                    if (a, b) == (0, 0) {
                        continue;
                    }
                    let t = lat.u_mm * f64::from(a) + lat.v_mm * f64::from(b);
                    let d = plane::polygon_distance(&star, &moved(&star, t), gap);
                    assert!(d >= gap, "{angle}°: ({a}, {b}) at {d}");
                }
            }
            let (x0, y0, x1, y1) = bounds(&star);
            let boxes = (x1 - x0 + gap) * (y1 - y0 + gap);
            assert!(lat.cell_mm2() * 2.0 < boxes, "{angle}°: {}", lat.cell_mm2());
        }
    }

    /// A rectangle (a shear block) is no star; neither is a triangle.
    #[test]
    fn non_stars_get_no_lattice() {
        let rect = vec![
            Point::new(0.0, 0.0),
            Point::new(30.0, 0.0),
            Point::new(30.0, 10.0),
            Point::new(0.0, 10.0),
        ];
        assert!(star_lattice(&rect, 3.2).is_none());
    }

    /// A block's copies lie inside its rectangle, in (y, x) order, and fit
    /// about as many as the area over the cell says (within its rim).
    #[test]
    fn block_fills_its_rectangle() {
        let star = star_outline(90.0, 45.0, 9.6);
        let lat = star_lattice(&star, 3.2).expect("lattice");
        let b = block(&lat, 90.0, 90.0, 400.0, 400.0);
        let (w, h) = b.extent_mm(b.len());
        assert!(w <= 400.0 + 1e-9 && h <= 400.0 + 1e-9, "{w} × {h}");
        let inner = (400.0f64 - 90.0).powi(2) / lat.cell_mm2();
        assert!(
            b.len() as f64 >= inner && (b.len() as f64) < 400.0 * 400.0 / lat.cell_mm2(),
            "{} copies",
            b.len()
        );
        // By boxes 93.2 mm apart: 4 × 4 = 16.
        assert!(b.len() >= 2 * 16, "{} copies", b.len());
        for k in 1..b.len() {
            let (p, q) = (b.corners_mm[k - 1], b.corners_mm[k]);
            assert!(p.y < q.y || (p.y == q.y && p.x < q.x));
        }
        // A prefix's box is no larger than the whole.
        let (w3, h3) = b.extent_mm(3);
        assert!(w3 <= w && h3 <= h);
    }
}
