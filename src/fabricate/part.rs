//! The parts model: flat parts in their own 2D frame, as a cutter needs them.
//!
//! Coordinates of a part are part-local millimetres (`_part` in names): for
//! a lamella, x runs along its own line from its start and y across its
//! height from the bottom edge (the top edge on the +normal side). Outlines
//! are closed polylines (the last point joins the first, not repeated),
//! counter-clockwise; holes clockwise and inside the outline; engraving is
//! texts and marks set in the single-stroke font ([`Engraving`]), each
//! drawn as open polylines.

use kurbo::Point;

/// What a part is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PartKind {
    /// A flat, straight lamella (one of a strip's one or two).
    Lamella,
    /// A block coupling the two lamellas of a doubled strip.
    ShearBlock,
    /// A star washer at a node.
    Washer,
    /// A square stud joining the two levels of a two-level grid.
    Stud,
    /// A plate joining two pieces of a spliced lamella.
    SplicePlate,
    /// A boundary band, unrolled flat.
    EdgeStrip,
    /// A plate under a node bolt that a bracing cable is pinned to.
    EyePlate,
}

impl PartKind {
    /// The name used in plan.json.
    pub fn as_str(self) -> &'static str {
        match self {
            PartKind::Lamella => "lamella",
            PartKind::ShearBlock => "shear_block",
            PartKind::Washer => "washer",
            PartKind::Stud => "stud",
            PartKind::SplicePlate => "splice_plate",
            PartKind::EdgeStrip => "edge_strip",
            PartKind::EyePlate => "eye_plate",
        }
    }
}

impl PartKind {
    /// What the stock sees it as: which stock group it is cut from
    /// ([`crate::profile::Profile::stock_groups`]).
    pub fn piece(self) -> crate::profile::Piece {
        use crate::profile::Piece;
        match self {
            PartKind::Lamella => Piece::Lamella,
            PartKind::ShearBlock => Piece::ShearBlock,
            PartKind::Washer => Piece::Washer,
            PartKind::Stud => Piece::Stud,
            PartKind::SplicePlate => Piece::SplicePlate,
            PartKind::EdgeStrip => Piece::EdgeBand,
            PartKind::EyePlate => Piece::EyePlate,
        }
    }
}

/// Which edge of a lamella a slot opens to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SlotEdge {
    /// The edge on the surface normal's side (family A's slots).
    Top,
    /// The other edge (family B's slots).
    Bottom,
    /// An end of the lamella (the nearer to the slot's centre): the end
    /// slot an edge strip runs through. Its `width_mm` is its opening
    /// across y, its `depth_mm` its reach along x from that end.
    End,
}

impl SlotEdge {
    /// The name used in plan.json.
    pub fn as_str(self) -> &'static str {
        match self {
            SlotEdge::Top => "top",
            SlotEdge::Bottom => "bottom",
            SlotEdge::End => "end",
        }
    }
}

/// What a feature is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FeatureKind {
    /// A notch from a long edge.
    Slot,
    /// A round hole.
    Hole,
}

impl FeatureKind {
    /// The name used in plan.json.
    pub fn as_str(self) -> &'static str {
        match self {
            FeatureKind::Slot => "slot",
            FeatureKind::Hole => "hole",
        }
    }
}

/// Why a hole is there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HoleUse {
    /// The node bolt, or a stud fastener at a node.
    Node,
    /// A shear block's bolt.
    ShearBlock,
    /// A splice plate's bolt.
    Splice,
    /// Where a lamella ends on an edge strip.
    EdgeNode,
    /// An eye plate's hole for a cable terminal's pin.
    CablePin,
}

/// A slot or hole of a part, located in the part's frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Feature {
    /// Slot or hole.
    pub kind: FeatureKind,
    /// For holes: what they are for.
    pub hole_use: Option<HoleUse>,
    /// The node it belongs to (index into the topology's nodes), if any.
    pub node: Option<usize>,
    /// Id of the crossing strip at that node, if any.
    pub crossing: Option<String>,
    /// Centre in the part frame, mm: a slot's centre line at the middle of
    /// its depth; a hole's centre.
    pub center_part_mm: Point,
    /// Along the part's x: a slot's width, a hole's diameter, mm.
    pub width_mm: f64,
    /// A slot's depth from its edge, mm (0 for holes).
    pub depth_mm: f64,
    /// The edge a slot opens to.
    pub edge: Option<SlotEdge>,
    /// The crossing angles a slot was swept over, degrees (signed, from this
    /// lamella's direction to the crossing one's about the node normal).
    pub angle_range_deg: Option<(f64, f64)>,
    /// Station of the feature's centre on this lamella's own line, mm
    /// (`station_start_mm` + x), where the part has a line.
    pub station_mm: Option<f64>,
}

/// One part to cut (or, for studs, to saw), `count` times.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// Unique id, also engraved: strip, lamella, piece (`A05-1`, `A05-1.2`),
    /// or kind and class (`SB`, `W90`, `ST`, `SP`).
    pub id: String,
    /// What it is.
    pub kind: PartKind,
    /// The strip it belongs to, if any.
    pub strip: Option<String>,
    /// Lamella number within the strip (1 on −y, 2 on +y), if any.
    pub lamella: Option<u32>,
    /// How many identical parts.
    pub count: u32,
    /// Extent along the part's x, mm.
    pub length_mm: f64,
    /// Extent along the part's y, mm.
    pub height_mm: f64,
    /// For lamellas and edge strips: the station on the part's own line at
    /// x = 0, mm (negative by the end allowance).
    pub station_start_mm: Option<f64>,
    /// Closed outline, counter-clockwise, part frame, mm.
    pub outline_part_mm: Vec<Point>,
    /// Closed holes other than the round ones, clockwise, inside the
    /// outline, part frame, mm. A round hole is only its `hole` feature
    /// (centre and diameter): [`Part::round_holes`], and as polygons
    /// [`Part::hole_polygons`].
    pub holes_part_mm: Vec<Vec<Point>>,
    /// What is engraved, in the order it was placed (its strokes:
    /// [`Part::engraving_strokes`]).
    pub engraving: Vec<Engraving>,
    /// Slots and holes, by x.
    pub features: Vec<Feature>,
}

impl Part {
    /// The round holes, (centre, radius) in feature order: one per `hole`
    /// feature, except that features on the same circle (centres and radii
    /// within [`ROUND_HOLE_MM`] together: an edge strip's nodes that share
    /// a hole) are one hole, the first's.
    pub fn round_holes(&self) -> Vec<(Point, f64)> {
        let mut out: Vec<(Point, f64)> = Vec::new();
        for f in &self.features {
            if f.kind != FeatureKind::Hole {
                continue;
            }
            let (c, r) = (f.center_part_mm, 0.5 * f.width_mm);
            if !out
                .iter()
                .any(|&(c0, r0)| c0.distance(c) + (r0 - r).abs() <= ROUND_HOLE_MM)
            {
                out.push((c, r));
            }
        }
        out
    }

    /// Every hole as a closed clockwise polygon, part frame, mm: the round
    /// holes ([`Part::round_holes`]) as [`circle_cw`] at
    /// [`ARC_TOLERANCE_MM`] (each size's trigonometry taken once), then
    /// [`Part::holes_part_mm`]. Built on demand, for the checks and the
    /// engraving placement of the few parts that need them.
    pub fn hole_polygons(&self) -> Vec<Vec<Point>> {
        let mut circles: Vec<CircleCw> = Vec::new();
        let mut out: Vec<Vec<Point>> = self
            .round_holes()
            .into_iter()
            .map(|(c, r)| {
                let k = match circles.iter().position(|s| s.radius_mm == r) {
                    Some(k) => k,
                    None => {
                        circles.push(CircleCw::new(r, ARC_TOLERANCE_MM));
                        circles.len() - 1
                    }
                };
                circles[k].at(c)
            })
            .collect();
        out.extend(self.holes_part_mm.iter().cloned());
        out
    }

    /// Every engraving's open single-stroke polylines, part frame, mm.
    pub fn engraving_strokes(&self) -> Vec<Vec<Point>> {
        self.engraving.iter().flat_map(Engraving::strokes).collect()
    }
}

/// What an engraving draws.
#[derive(Debug, Clone, PartialEq)]
pub enum Engraved {
    /// A text in the single-stroke font ([`super::font`]).
    Text(String),
    /// The orientation mark ([`super::font::orientation_mark_strokes`]).
    OrientationMark,
}

/// One engraving on a part: a text or the orientation mark at a height,
/// its box's lower left at `at_part_mm`. Its strokes are the font's (or the
/// mark's) at that height moved there: `at + (x, y)` for every stroke
/// point (x, y) drawn at the height with the box's lower left at the origin.
#[derive(Debug, Clone, PartialEq)]
pub struct Engraving {
    /// A text or the mark.
    pub what: Engraved,
    /// The lower left of its box (the text's baseline start), part frame, mm.
    pub at_part_mm: Point,
    /// Cap height of a text, whole height of the mark, mm.
    pub height_mm: f64,
}

impl Engraving {
    /// The strokes at the origin (box from (0, 0)), mm.
    pub fn strokes_at_origin(&self) -> Vec<Vec<Point>> {
        match &self.what {
            Engraved::Text(t) => super::font::text_strokes(t, self.height_mm),
            Engraved::OrientationMark => super::font::orientation_mark_strokes(self.height_mm),
        }
    }

    /// The open polylines, part frame, mm.
    pub fn strokes(&self) -> Vec<Vec<Point>> {
        let o = self.at_part_mm.to_vec2();
        self.strokes_at_origin()
            .into_iter()
            .map(|s| s.into_iter().map(|q| q + o).collect())
            .collect()
    }
}

/// The `hole` feature whose circle `hole` (a polygon of `part`) lies on,
/// every vertex within [`ROUND_HOLE_MM`]: the round hole it stands for.
pub fn round_hole<'a>(part: &'a Part, hole: &[Point]) -> Option<&'a Feature> {
    part.features.iter().find(|f| {
        let r = 0.5 * f.width_mm;
        f.kind == FeatureKind::Hole
            && hole
                .iter()
                .all(|q| (q.distance(f.center_part_mm) - r).abs() <= ROUND_HOLE_MM)
    })
}

/// How far a round hole's polygon vertices may stray from the circle, mm
/// ([`circle_cw`] puts them on it).
pub const ROUND_HOLE_MM: f64 = 1e-6;

/// Points on a circle, clockwise, so that no chord strays more than
/// `tolerance_mm` from the arc (at least 8).
pub fn circle_cw(center: Point, radius_mm: f64, tolerance_mm: f64) -> Vec<Point> {
    CircleCw::new(radius_mm, tolerance_mm).at(center)
}

/// [`circle_cw`] for one radius and tolerance, its trigonometry taken once
/// for every circle of that size: the points' offsets from the centre.
#[derive(Debug, Clone, PartialEq)]
pub struct CircleCw {
    /// The radius, mm.
    pub radius_mm: f64,
    /// r·(cos a, sin a) for every point, clockwise from a = 0, mm.
    offsets_mm: Vec<(f64, f64)>,
}

impl CircleCw {
    /// The circle of `radius_mm` whose chords stray at most `tolerance_mm`
    /// from the arc (at least 8 points).
    pub fn new(radius_mm: f64, tolerance_mm: f64) -> Self {
        let half_angle = (1.0 - (tolerance_mm / radius_mm).min(1.0)).acos();
        let n = ((std::f64::consts::PI / half_angle.max(1e-6)).ceil() as usize).clamp(8, 720);
        let offsets_mm = (0..n)
            .map(|k| {
                let a = -std::f64::consts::TAU * k as f64 / n as f64;
                (radius_mm * a.cos(), radius_mm * a.sin())
            })
            .collect();
        Self {
            radius_mm,
            offsets_mm,
        }
    }

    /// The points around `center`: exactly [`circle_cw`]'s (centre plus
    /// the same offset, rounded once).
    pub fn at(&self, center: Point) -> Vec<Point> {
        self.offsets_mm
            .iter()
            .map(|&(dx, dy)| Point::new(center.x + dx, center.y + dy))
            .collect()
    }
}

/// Largest distance a circle's polyline strays from the arc, mm.
pub const ARC_TOLERANCE_MM: f64 = 0.01;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::plane::signed_area_mm2;

    #[test]
    fn circles_are_clockwise_and_within_tolerance() {
        let c = circle_cw(Point::new(3.0, 4.0), 4.5, ARC_TOLERANCE_MM);
        assert!(signed_area_mm2(&c) < 0.0);
        // The sagitta r(1 − cos(π/n)) is within the tolerance.
        let n = c.len() as f64;
        assert!(4.5 * (1.0 - (std::f64::consts::PI / n).cos()) <= ARC_TOLERANCE_MM);
        for p in &c {
            assert!((p.distance(Point::new(3.0, 4.0)) - 4.5).abs() < 1e-12);
        }
    }

    #[test]
    fn a_shared_circle_gives_the_direct_points() {
        // The offsets taken once, added to each centre: bit for bit the
        // points computed directly, r·cos a added to the centre.
        for r in [0.5, 3.0, 3.5, 4.5, 6.5, 40.0] {
            let shared = CircleCw::new(r, ARC_TOLERANCE_MM);
            for centre in [
                Point::new(0.0, 0.0),
                Point::new(1234.567, 25.0),
                Point::new(-3.1, 7.7),
            ] {
                let got = shared.at(centre);
                let n = got.len();
                for (k, q) in got.iter().enumerate() {
                    let a = -std::f64::consts::TAU * k as f64 / n as f64;
                    assert_eq!(q.x.to_bits(), (centre.x + r * a.cos()).to_bits());
                    assert_eq!(q.y.to_bits(), (centre.y + r * a.sin()).to_bits());
                }
                assert_eq!(got, circle_cw(centre, r, ARC_TOLERANCE_MM));
            }
        }
    }
}
