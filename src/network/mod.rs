//! The validated in-memory network: the output of the read stage.
//!
//! Guarantees after [`Network::new`] succeeds:
//! * every coordinate is finite and in millimetres (`_mm`);
//! * curve ids are unique and non-empty;
//! * every curve has at least two distinct points, consecutive duplicates removed,
//!   and a positive length;
//! * normals, where present, have one per point, are finite and non-zero;
//! * curves keep the order and orientation of the file.

use crate::error::{Error, Location, Result};
use glam::DVec3;
use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};

/// Default node tolerance when a file gives none: largest gap (mm) between
/// two curves that still makes a node.
pub const DEFAULT_TOLERANCE_MM: f64 = 0.5;

/// Largest turn (degrees) between consecutive chords of a curve: more is a
/// fold or a kink, not samples of a smooth strip.
pub const MAX_TURN_DEG: f64 = 120.0;

/// Points closer than this (mm) are the same sample.
pub const DUPLICATE_POINT_MM: f64 = 1e-9;

/// Largest |coordinate| (mm, after unit conversion): 10 km from the origin.
pub const MAX_COORDINATE_MM: f64 = 1e7;

/// Largest extent of a network's bounding box along any axis (mm): 1 km.
pub const MAX_EXTENT_MM: f64 = 1e6;

/// Longest curve (mm): 10 km.
pub const MAX_CURVE_LENGTH_MM: f64 = 1e7;

/// Most curve length in one network (mm): 100 km.
pub const MAX_TOTAL_LENGTH_MM: f64 = 1e8;

/// Largest node tolerance (mm): a gap wider than this is no joint.
pub const MAX_TOLERANCE_MM: f64 = 1000.0;

/// Most points in one network: 4,000,000 (about 35 s and 5 GB of analysis
/// on a 2-core machine; a network sampled every 25 mm has 4,000 per 100 m
/// of curve).
pub const MAX_POINTS: usize = 4_000_000;

/// The two asymptotic families and the boundary.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Family {
    /// The first asymptotic (or principal) family.
    A,
    /// The second family, crossing A.
    B,
    /// The cut boundary: crosses A and B, never checked as a lamella.
    Edge,
}

impl Family {
    /// Parse a family name as written in a network file (`A`, `B`, `edge`).
    pub fn parse(name: &str) -> Option<Family> {
        match name.trim() {
            "A" | "a" => Some(Family::A),
            "B" | "b" => Some(Family::B),
            s if s.eq_ignore_ascii_case("edge") => Some(Family::Edge),
            _ => None,
        }
    }
    /// Family from a layer or object name: `A`, `B` or `edge` (any case),
    /// alone or followed by a digit, `-`, `_`, `.` or a space (`A03`, `B-12`,
    /// `edge north`). Other names (`Annotations`, `Boundary`, `0`) give None.
    pub fn from_prefix(name: &str) -> Option<Family> {
        let n = name.trim();
        let rest_ok = |rest: &str| {
            rest.chars()
                .next()
                .is_none_or(|c| c.is_ascii_digit() || matches!(c, '-' | '_' | '.' | ' '))
        };
        let lower = n.to_ascii_lowercase();
        if let Some(rest) = lower.strip_prefix("edge") {
            return rest_ok(rest).then_some(Family::Edge);
        }
        if let Some(rest) = lower.strip_prefix('a') {
            return rest_ok(rest).then_some(Family::A);
        }
        if let Some(rest) = lower.strip_prefix('b') {
            return rest_ok(rest).then_some(Family::B);
        }
        None
    }
    /// The name in files and messages: `A`, `B` or `edge`.
    pub fn as_str(self) -> &'static str {
        match self {
            Family::A => "A",
            Family::B => "B",
            Family::Edge => "edge",
        }
    }
    /// Whether curves of these families meet in nodes (A×B, A×edge, B×edge).
    pub fn crosses(self, other: Family) -> bool {
        self != other
    }
}

impl fmt::Display for Family {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Length units a file may be written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unit {
    /// Millimetres.
    Mm,
    /// Centimetres (10 mm).
    Cm,
    /// Metres (1000 mm).
    M,
    /// Inches (25.4 mm).
    In,
    /// Feet (304.8 mm).
    Ft,
}

impl Unit {
    /// Parse a unit as written in a file (`mm`, `cm`, `m`, `in`, `ft`; surrounding
    /// spaces ignored); None for anything else.
    pub fn parse(name: &str) -> Option<Unit> {
        match name.trim() {
            "mm" => Some(Unit::Mm),
            "cm" => Some(Unit::Cm),
            "m" => Some(Unit::M),
            "in" => Some(Unit::In),
            "ft" => Some(Unit::Ft),
            _ => None,
        }
    }
    /// Millimetres per unit.
    pub fn mm_per_unit(self) -> f64 {
        match self {
            Unit::Mm => 1.0,
            Unit::Cm => 10.0,
            Unit::M => 1000.0,
            Unit::In => 25.4,
            Unit::Ft => 304.8,
        }
    }
    /// The unit's name as files write it (`mm`, `cm`, `m`, `in`, `ft`).
    pub fn as_str(self) -> &'static str {
        match self {
            Unit::Mm => "mm",
            Unit::Cm => "cm",
            Unit::M => "m",
            Unit::In => "in",
            Unit::Ft => "ft",
        }
    }
}

/// A curve as read, before validation, in file units.
#[derive(Debug, Clone, PartialEq)]
pub struct RawCurve {
    /// The curve's id (unique in a valid network; the design names `A00`, `B00`, `edge00`).
    pub id: String,
    /// The curve's family.
    pub family: Family,
    /// Sample points in file units, world frame, in file order.
    pub points: Vec<DVec3>,
    /// Surface normals at the points (world frame, any length), if the file gives them.
    pub normals: Option<Vec<DVec3>>,
}

/// A network as read from any format, before validation, in file units.
#[derive(Debug, Clone, PartialEq)]
pub struct RawNetwork {
    /// The network's name (from the file, else its stem).
    pub name: String,
    /// The length unit of the points and the tolerance.
    pub unit: Unit,
    /// Node tolerance in file units, if the file gives one.
    pub tolerance: Option<f64>,
    /// How far the points may lie from the smooth curves they stand for,
    /// in file units, if the file says (a network traced on a mesh or a
    /// film): curves are smoothed to the larger of it and the grid the
    /// coordinates are rounded to.
    pub precision: Option<f64>,
    /// The curves in file order.
    pub curves: Vec<RawCurve>,
}

/// One validated curve, in millimetres, world frame (see [`Network`] for
/// what validation guarantees).
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// The curve's id, unique and non-empty.
    pub id: String,
    /// The curve's family.
    pub family: Family,
    /// Sample points, world frame, mm: at least 2, no two consecutive closer than
    /// [`DUPLICATE_POINT_MM`], in file order.
    pub points_world_mm: Vec<DVec3>,
    /// Unit surface normals, one per point, if the file gave them.
    pub normals_world: Option<Vec<DVec3>>,
}

/// The largest precision a network file may declare, mm.
pub const MAX_PRECISION_MM: f64 = 10.0;

/// A validated network, in millimetres, world frame.
///
/// Guarantees after [`Network::new`]: every coordinate finite, in mm and
/// within ±[`MAX_COORDINATE_MM`]; the bounding box at most [`MAX_EXTENT_MM`]
/// along each axis, each curve at most [`MAX_CURVE_LENGTH_MM`] long, all
/// curves together at most [`MAX_TOTAL_LENGTH_MM`], at most [`MAX_POINTS`]
/// points in all; node tolerance in
/// (0, [`MAX_TOLERANCE_MM`]] mm; ids unique and non-empty; every curve has at
/// least 2 distinct points (consecutive duplicates dropped) and a positive
/// length; normals, where present, one per point, unit length, one
/// orientation along the curve; no curve turns more than [`MAX_TURN_DEG`]
/// between consecutive chords; at least one A and one B curve; curves keep
/// file order and direction.
#[derive(Debug, Clone, PartialEq)]
pub struct Network {
    /// The network's name (from the file, else its stem).
    pub name: String,
    /// The file it was read from (for messages).
    pub source: PathBuf,
    /// The unit the file was written in (lengths here are already mm).
    pub file_unit: Unit,
    /// Node tolerance: the largest gap between two curves that is a node, mm, in
    /// (0, [`MAX_TOLERANCE_MM`]].
    pub tolerance_mm: f64,
    /// The grid the file's coordinates are rounded to, mm (0: unrounded).
    /// Curves are smoothed to it (see `curve`).
    pub precision_mm: f64,
    /// The curves in file order (the index is the curve's index everywhere else).
    pub curves: Vec<Curve>,
}

impl Network {
    /// Validate a raw network and convert it to millimetres.
    pub fn new(raw: RawNetwork, source: &Path) -> Result<Network> {
        let scale = raw.unit.mm_per_unit();
        let tolerance_mm = match raw.tolerance {
            None => DEFAULT_TOLERANCE_MM,
            Some(t) if t.is_finite() && t > 0.0 && t * scale <= MAX_TOLERANCE_MM => t * scale,
            Some(t) if t.is_finite() && t > 0.0 => {
                return Err(Error::input(
                    source,
                    Location::Field("tolerance".into()),
                    format!(
                        "{t} {} is wider than any joint (at most {MAX_TOLERANCE_MM} mm)",
                        raw.unit.as_str()
                    ),
                ))
            }
            Some(t) => {
                return Err(Error::input(
                    source,
                    Location::Field("tolerance".into()),
                    format!("tolerance must be a positive number, got {t}"),
                ))
            }
        };
        if raw.curves.is_empty() {
            return Err(Error::input(
                source,
                Location::File,
                "the network has no curves",
            ));
        }
        let points: usize = raw.curves.iter().map(|c| c.points.len()).sum();
        if points > MAX_POINTS {
            return Err(Error::network(
                source,
                format!(
                    "{points} points; lamella reads networks of up to {MAX_POINTS} points (about 35 s and 5 GB of analysis at the limit): export the curves sampled more coarsely"
                ),
            ));
        }
        let declared_mm = match raw.precision {
            None => 0.0,
            Some(p) if p.is_finite() && p >= 0.0 && p * scale <= MAX_PRECISION_MM => p * scale,
            Some(p) => {
                return Err(Error::input(
                    source,
                    Location::Field("precision".into()),
                    format!(
                        "precision must be a number from 0 to {MAX_PRECISION_MM} mm, got {p} {}",
                        raw.unit.as_str()
                    ),
                ))
            }
        };
        let precision_mm = coordinate_precision(&raw.curves)
            .map_or(0.0, |q| q * scale)
            .max(declared_mm);
        let mut seen: HashMap<String, usize> = HashMap::with_capacity(raw.curves.len());
        let mut curves = Vec::with_capacity(raw.curves.len());
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        let mut total_mm = 0.0;
        for (index, c) in raw.curves.into_iter().enumerate() {
            let at = || {
                if c.id.trim().is_empty() {
                    Location::Field(format!("curves[{index}].id"))
                } else {
                    Location::Curve(c.id.clone())
                }
            };
            if c.id.trim().is_empty() {
                return Err(Error::input(source, at(), "empty curve id"));
            }
            if let Some(first) = seen.insert(c.id.clone(), index) {
                return Err(Error::input(
                    source,
                    at(),
                    format!(
                        "duplicate curve id: curves[{first}] and curves[{index}] are both {} (ids must be unique)",
                        c.id
                    ),
                ));
            }
            if c.points.len() < 2 {
                return Err(Error::input(
                    source,
                    at(),
                    format!("has {} point(s); a curve needs at least 2", c.points.len()),
                ));
            }
            if let Some(k) = c.points.iter().position(|p| !p.is_finite()) {
                return Err(Error::input(
                    source,
                    at(),
                    format!("point {k} has a NaN or infinite coordinate"),
                ));
            }
            if let Some(n) = &c.normals {
                if n.len() != c.points.len() {
                    return Err(Error::input(
                        source,
                        at(),
                        format!("{} normals for {} points", n.len(), c.points.len()),
                    ));
                }
                if let Some(k) = n.iter().position(|v| !v.is_finite()) {
                    return Err(Error::input(
                        source,
                        at(),
                        format!("normal {k} has a NaN or infinite coordinate"),
                    ));
                }
                if let Some(k) = n.iter().position(|v| v.length() < 1e-12) {
                    return Err(Error::input(
                        source,
                        at(),
                        format!("normal {k} has zero length"),
                    ));
                }
            }
            // Scale to mm and drop consecutive duplicate points.
            let mut points_world_mm = Vec::with_capacity(c.points.len());
            let mut normals = c
                .normals
                .as_ref()
                .map(|_| Vec::with_capacity(c.points.len()));
            for (k, p) in c.points.iter().enumerate() {
                let p_mm = *p * scale;
                if let Some(last) = points_world_mm.last() {
                    if p_mm.distance(*last) <= DUPLICATE_POINT_MM {
                        continue;
                    }
                }
                points_world_mm.push(p_mm);
                if let (Some(out), Some(src)) = (normals.as_mut(), c.normals.as_ref()) {
                    out.push(src[k].normalize());
                }
            }
            if points_world_mm.len() < 2 {
                return Err(Error::input(
                    source,
                    at(),
                    "zero-length curve (all points coincide)",
                ));
            }
            if let Some(k) = points_world_mm.iter().position(|p| !p.is_finite()) {
                return Err(Error::input(
                    source,
                    at(),
                    format!("point {k} overflows when converted to mm"),
                ));
            }
            if let Some(k) = c
                .points
                .iter()
                .position(|p| (*p * scale).abs().max_element() > MAX_COORDINATE_MM)
            {
                return Err(Error::input(
                    source,
                    at(),
                    format!(
                        "point {k} lies {:.3e} mm from the origin; coordinates must be within ±{MAX_COORDINATE_MM:e} mm (10 km)",
                        (c.points[k] * scale).abs().max_element()
                    ),
                ));
            }
            let length_mm: f64 = points_world_mm
                .windows(2)
                .map(|w| w[1].distance(w[0]))
                .sum();
            if length_mm > MAX_CURVE_LENGTH_MM {
                return Err(Error::input(
                    source,
                    at(),
                    format!(
                        "{:.3e} mm long; a curve may be at most {MAX_CURVE_LENGTH_MM:e} mm (10 km)",
                        length_mm
                    ),
                ));
            }
            total_mm += length_mm;
            for p in &points_world_mm {
                lo = lo.min(*p);
                hi = hi.max(*p);
            }
            // A strip cannot turn back on itself between two samples.
            for (k, w) in points_world_mm.windows(3).enumerate() {
                let (d1, d2) = (w[1] - w[0], w[2] - w[1]);
                let turn = d1.angle_between(d2).to_degrees();
                if turn > MAX_TURN_DEG {
                    return Err(Error::input(
                        source,
                        at(),
                        format!(
                            "turns back on itself at point {} ({turn:.0}° between chords)",
                            k + 1
                        ),
                    ));
                }
            }
            if let Some(ns) = &normals {
                if let Some(k) = ns.windows(2).position(|w| w[0].dot(w[1]) < 0.0) {
                    return Err(Error::input(
                        source,
                        at(),
                        format!("normal {} points the other way from normal {k}: normals must be oriented consistently", k + 1),
                    ));
                }
            }
            curves.push(Curve {
                id: c.id,
                family: c.family,
                points_world_mm,
                normals_world: normals,
            });
        }
        let extent = hi - lo;
        if extent.max_element() > MAX_EXTENT_MM {
            return Err(Error::network(
                source,
                format!(
                    "the network spans {:.0} × {:.0} × {:.0} mm; lamella reads networks up to {MAX_EXTENT_MM:e} mm (1 km) along each axis",
                    extent.x, extent.y, extent.z
                ),
            ));
        }
        if total_mm > MAX_TOTAL_LENGTH_MM {
            return Err(Error::network(
                source,
                format!(
                    "{:.3e} mm of curves; lamella reads networks up to {MAX_TOTAL_LENGTH_MM:e} mm (100 km) of curves",
                    total_mm
                ),
            ));
        }
        let has_a = curves.iter().any(|c| c.family == Family::A);
        let has_b = curves.iter().any(|c| c.family == Family::B);
        if !has_a || !has_b {
            let missing = if !has_a { "A" } else { "B" };
            return Err(Error::network(
                source,
                format!("no curve of family {missing}: a network needs A×B crossings"),
            ));
        }
        Ok(Network {
            name: raw.name,
            source: source.to_path_buf(),
            file_unit: raw.unit,
            tolerance_mm,
            precision_mm,
            curves,
        })
    }

    /// Index of the curve with this id, if any.
    pub fn curve_index(&self, id: &str) -> Option<usize> {
        self.curves.iter().position(|c| c.id == id)
    }

    /// Total number of sample points.
    pub fn point_count(&self) -> usize {
        self.curves.iter().map(|c| c.points_world_mm.len()).sum()
    }
}

/// Finest decimal places looked for in coordinates.
const MAX_DECIMALS: i32 = 9;

/// The coarsest decimal grid (10^−d file units, d = 0…9) that every
/// coordinate lies on: 0.001 for a Rhino export rounded to three decimals.
/// `None` when the coordinates are finer than 1e−9 (unrounded doubles).
pub fn coordinate_precision(curves: &[RawCurve]) -> Option<f64> {
    let mut d = 0;
    let on_grid = |x: f64, d: i32| {
        let y = x * 10f64.powi(d);
        (y - y.round()).abs() <= 1e-6f64.max(y.abs() * 1e-14)
    };
    for x in curves
        .iter()
        .flat_map(|c| c.points.iter())
        .flat_map(|p| [p.x, p.y, p.z])
        .filter(|x| x.is_finite())
    {
        while d <= MAX_DECIMALS && !on_grid(x, d) {
            d += 1;
        }
        if d > MAX_DECIMALS {
            return None;
        }
    }
    Some(10f64.powi(-d))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn curve(points: Vec<DVec3>) -> RawCurve {
        RawCurve {
            id: "A".into(),
            family: Family::A,
            points,
            normals: None,
        }
    }

    #[test]
    fn more_points_than_the_limit_are_refused_before_any_is_checked() {
        let step = DVec3::new(0.01, 0.0, 0.0);
        let a = curve((0..=MAX_POINTS).map(|i| step * i as f64).collect());
        let raw = RawNetwork {
            name: "big".into(),
            unit: Unit::Mm,
            tolerance: None,
            precision: None,
            curves: vec![a],
        };
        let e = Network::new(raw, Path::new("big.yaml")).expect_err("refused");
        let text = e.to_string();
        assert!(
            text.contains("big.yaml") && text.contains("4000001 points") && !text.contains('\n'),
            "{text}"
        );
    }

    #[test]
    fn precision_is_the_grid_of_the_decimals() {
        let rhino = curve(vec![
            DVec3::new(1234.567, -0.001, 12.5),
            DVec3::new(-98765.432, 3.0, 0.25),
        ]);
        assert_eq!(coordinate_precision(&[rhino]), Some(0.001));
        let whole = curve(vec![DVec3::new(10.0, -20.0, 3.0)]);
        assert_eq!(coordinate_precision(&[whole]), Some(1.0));
        let exact = curve(vec![DVec3::new(1.0 / 3.0, 2.0f64.sqrt(), 0.1)]);
        assert_eq!(coordinate_precision(&[exact]), None);
    }

    #[test]
    fn a_declared_precision_raises_the_decimals_grid_and_a_bad_one_is_refused() {
        let raw = |precision: Option<f64>| RawNetwork {
            name: "film".into(),
            unit: Unit::M,
            tolerance: None,
            precision,
            curves: vec![
                curve(vec![DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0)]),
                RawCurve {
                    id: "B".into(),
                    family: Family::B,
                    points: vec![DVec3::new(0.5, -0.5, 0.0), DVec3::new(0.5, 0.5, 0.0)],
                    normals: None,
                },
            ],
        };
        // Coordinates to one decimal of a metre: a grid of 100 mm; 1e-4 m
        // declared is finer, so the grid stands.
        let net = Network::new(raw(None), Path::new("f.yaml")).unwrap();
        assert_eq!(net.precision_mm, 100.0);
        let net = Network::new(raw(Some(1e-4)), Path::new("f.yaml")).unwrap();
        assert_eq!(net.precision_mm, 100.0);
        let mut fine = raw(Some(2e-3));
        fine.unit = Unit::Mm;
        for c in &mut fine.curves {
            for p in &mut c.points {
                *p *= 1000.0;
                *p += DVec3::new(0.1234567, 0.0, 0.0);
            }
        }
        let net = Network::new(fine, Path::new("f.yaml")).unwrap();
        assert_eq!(net.precision_mm, 2e-3);
        let e = Network::new(raw(Some(-1.0)), Path::new("f.yaml")).unwrap_err();
        assert!(e.to_string().contains("precision"), "{e}");
        assert!(e.to_string().contains("f.yaml"), "{e}");
        assert!(Network::new(raw(Some(f64::NAN)), Path::new("f.yaml")).is_err());
    }
}
