//! Strip-geometry stage: along every curve, the Darboux frame (x tangent,
//! z surface normal, y = z × x) with geodesic curvature kg, geodesic torsion
//! tg and the normal-curvature residual kn; node-to-node lengths; stations on
//! lamella lines offset from the curve.
//!
//! Where the surface normal comes from (docs/geometry.md):
//! * the file's normals, interpolated like the points; kn and tg from their
//!   rotation (z' = −kn·x − tg·y);
//! * otherwise a [`NormalField`]: the normal's angle about the tangent in a
//!   rotation-minimising frame, fitted to the node normals (tangent_a ×
//!   tangent_b) and, on A and B curves, to the binormal weighted by how
//!   well the curvature is known; tg is the angle's derivative. Edge curves
//!   take their normal from their nodes only (they are not asymptotic).
//!
//! Without file normals the kn residual is measured at the nodes, as the
//! curve's curvature vector against the node normal.
//!
//! Sign conventions: z agrees with the oriented node normals; kg and kn change
//! sign with z, tg does not change with z or with the curve's direction.

use crate::analysis::normal_field::{NodeNormal, NormalField, NormalFieldOptions};
use crate::analysis::topology::{CurveNode, Node};
use crate::geom::curve::{Hermite5, Jet, Piece, SmoothCurve};
use crate::network::{Curve, Family};
use glam::DVec3;

/// Largest distance between the stations where curvatures are evaluated, mm.
pub const MAX_CURVATURE_SPACING_MM: f64 = 50.0;

/// Options of the strip-geometry stage.
#[derive(Debug, Clone, Copy)]
pub struct FrameOptions {
    /// How the normal field of a curve without file normals is fitted.
    pub field: NormalFieldOptions,
    /// A strip whose curvature stays below this (1/mm) is straight: it has no
    /// minimum bending radius.
    pub straight_curvature_per_mm: f64,
}

impl Default for FrameOptions {
    fn default() -> Self {
        FrameOptions {
            field: NormalFieldOptions::default(),
            straight_curvature_per_mm: 1e-5,
        }
    }
}

/// Where a strip's normals came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NormalSource {
    /// The network file gave normals; they are interpolated like the points.
    File,
    /// Fitted to the binormal only (a curve with no node).
    Binormal,
    /// Binormal where curved, node normals where straight.
    BinormalAndNodes,
    /// Fitted to the node normals only (edge curves, straight curves).
    Nodes,
}

impl NormalSource {
    /// The name plan.json uses: `file`, `binormal`, `binormal+nodes` or `nodes`.
    pub fn as_str(self) -> &'static str {
        match self {
            NormalSource::File => "file",
            NormalSource::Binormal => "binormal",
            NormalSource::BinormalAndNodes => "binormal+nodes",
            NormalSource::Nodes => "nodes",
        }
    }
}

/// The Darboux frame and curvatures at one station.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DarbouxFrame {
    /// Arc length from the curve's first point, mm.
    pub station_mm: f64,
    /// The curve point at this station, world frame, mm.
    pub point_world_mm: DVec3,
    /// Unit tangent (the strip's long axis), world frame.
    pub x: DVec3,
    /// Unit in-surface normal z × x (across the strip: its thickness direction), world frame.
    pub y: DVec3,
    /// Unit surface normal, oriented like the node normals, world frame.
    pub z: DVec3,
    /// Geodesic curvature, 1/mm (bending about z, the strip's weak axis).
    pub kg_per_mm: f64,
    /// Normal curvature, 1/mm (bending about y; zero on an asymptotic curve).
    pub kn_per_mm: f64,
    /// Geodesic torsion, rad/mm (twist about x).
    pub tg_per_mm: f64,
}

/// Curvatures at one sample of a strip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Curvatures {
    /// Arc length from the curve's first point, mm.
    pub station_mm: f64,
    /// Geodesic curvature, 1/mm (sign follows z).
    pub kg_per_mm: f64,
    /// Normal curvature, 1/mm (the residual: zero on an exact asymptotic curve).
    pub kn_per_mm: f64,
    /// Geodesic torsion, rad/mm.
    pub tg_per_mm: f64,
}

/// The normals of a strip.
#[derive(Debug, Clone)]
enum Normals {
    /// The file's, over the curve's chord parameter.
    File(Hermite5),
    /// Fitted to nodes (and binormals).
    Field(NormalField),
}

/// Normalise v and carry its derivative: (v/|v|)' = (v' − v̂(v̂·v'))/|v|.
fn unit_and_derivative(v: DVec3, dv: DVec3) -> (DVec3, DVec3) {
    let len = v.length();
    if len < 1e-300 {
        return (DVec3::Z, DVec3::ZERO);
    }
    let u = v / len;
    (u, (dv - u * u.dot(dv)) / len)
}

/// The geometry of one strip (curve).
///
/// Guarantees: one normal per sample (file normals, else the binormal
/// oriented by the node normals and blended into them near inflections,
/// else node normals on straight stretches), interpolated like the curve;
/// kg, kn, tg from the frame x = tangent, z = normal ⟂ x, y = z × x;
/// `samples` sorted by station, at most [`MAX_CURVATURE_SPACING_MM`] apart;
/// `max_abs_kn_per_mm` is the residual, per sample with file normals and at
/// the nodes otherwise.
#[derive(Debug, Clone)]
pub struct StripGeometry {
    /// Index of the curve in `Network::curves` (and `Analysis::curves`).
    pub curve: usize,
    /// The curve's id, as in the network file.
    pub id: String,
    /// The curve's family: A, B or edge.
    pub family: Family,
    /// Arc length of the smooth curve, mm.
    pub length_mm: f64,
    /// Where the surface normals along this strip came from.
    pub normal_source: NormalSource,
    /// The curve's nodes, by station.
    pub nodes: Vec<CurveNode>,
    /// Curvatures at every sample of the curve, and between samples farther
    /// apart than [`MAX_CURVATURE_SPACING_MM`]; sorted by station.
    pub samples: Vec<Curvatures>,
    /// Largest |kg| over `samples`, 1/mm.
    pub max_abs_kg_per_mm: f64,
    /// Largest |tg| over `samples`, rad/mm.
    pub max_abs_tg_per_mm: f64,
    /// Largest |kn| (the residual: zero on an exact asymptotic curve).
    pub max_abs_kn_per_mm: f64,
    normals: Normals,
    straight_curvature_per_mm: f64,
}

impl StripGeometry {
    /// Build the strip geometry of one curve.
    pub fn new(
        index: usize,
        curve: &Curve,
        smooth: &SmoothCurve,
        nodes: &[CurveNode],
        all_nodes: &[Node],
        opts: FrameOptions,
    ) -> StripGeometry {
        let n = smooth.samples().len();
        let knot = |i: usize| if i + 1 < n { (i, 0.0) } else { (n - 2, 1.0) };
        let (normals, normal_source) = match &curve.normals_world {
            Some(file) => {
                let t: Vec<f64> = (0..n).map(|i| smooth.sample_param(i)).collect();
                // Normals of a curve smoothed to its precision are as rough as
                // its points (a network traced on a mesh or a film carries its
                // surface's noise in both): smoothed over the same window,
                // where that is wider than the 7-sample fit.
                let window_mm = smooth.smoothing_mm();
                let seven_samples_mm = 3.5 * smooth.length_mm() / (n - 1).max(1) as f64;
                let h = if window_mm > seven_samples_mm && n >= 9 {
                    Hermite5::smoothed(t, file, window_mm)
                } else {
                    Hermite5::new(t, file.clone())
                };
                (Normals::File(h), NormalSource::File)
            }
            None => {
                let mut at_nodes: Vec<NodeNormal> = Vec::with_capacity(nodes.len());
                for cn in nodes {
                    if at_nodes
                        .last()
                        .is_some_and(|nn| cn.station_mm - nn.station_mm < 1e-6)
                    {
                        continue;
                    }
                    at_nodes.push(NodeNormal {
                        station_mm: cn.station_mm,
                        segment: cn.segment,
                        u: cn.u,
                        normal_world: all_nodes[cn.node].normal_world,
                    });
                }
                // Edge curves are not asymptotic: their binormal is not the
                // surface normal. Only a curve with no node at all falls back on it.
                let use_binormal = curve.family != Family::Edge || at_nodes.is_empty();
                let field = NormalField::new(smooth, &at_nodes, use_binormal, opts.field);
                let source = match (field.sources.binormals, field.sources.nodes) {
                    (true, true) => NormalSource::BinormalAndNodes,
                    (true, false) => NormalSource::Binormal,
                    _ => NormalSource::Nodes,
                };
                (Normals::Field(field), source)
            }
        };
        let mut strip = StripGeometry {
            curve: index,
            id: curve.id.clone(),
            family: curve.family,
            length_mm: smooth.length_mm(),
            normal_source,
            nodes: nodes.to_vec(),
            samples: Vec::new(),
            max_abs_kg_per_mm: 0.0,
            max_abs_tg_per_mm: 0.0,
            max_abs_kn_per_mm: 0.0,
            normals,
            straight_curvature_per_mm: opts.straight_curvature_per_mm,
        };
        // Curvatures at every sample, and between samples where they are
        // sparse (at most `MAX_CURVATURE_SPACING_MM` apart), so extremes of a
        // coarsely sampled curve (DXF LINEs, short polylines) are not missed.
        let stations = smooth.sample_stations_mm();
        let parts_of =
            |i: usize| ((stations[i + 1] - stations[i]) / MAX_CURVATURE_SPACING_MM).ceil() as usize;
        let count = 1 + (0..n - 1).map(|i| parts_of(i).max(1)).sum::<usize>();
        let mut samples: Vec<Curvatures> = Vec::with_capacity(count);
        let mut push = |f: DarbouxFrame| {
            samples.push(Curvatures {
                station_mm: f.station_mm,
                kg_per_mm: f.kg_per_mm,
                kn_per_mm: f.kn_per_mm,
                tg_per_mm: f.tg_per_mm,
            });
        };
        for i in 0..n {
            let (k, u) = knot(i);
            let piece = smooth.piece(k);
            push(strip.frame_of_jet(piece.jet(u), k, u, stations[i]));
            if i + 1 < n {
                let len = stations[i + 1] - stations[i];
                let parts = parts_of(i);
                for p in 1..parts {
                    let target = stations[i] + len * p as f64 / parts as f64;
                    let (k, u) = smooth.locate_station_near(target, i);
                    let j = if k == i {
                        piece.jet(u)
                    } else {
                        smooth.jet_at(k, u)
                    };
                    push(strip.frame_of_jet(j, k, u, target));
                }
            }
        }
        strip.max_abs_kg_per_mm = samples
            .iter()
            .map(|c| c.kg_per_mm.abs())
            .fold(0.0, f64::max);
        strip.max_abs_tg_per_mm = samples
            .iter()
            .map(|c| c.tg_per_mm.abs())
            .fold(0.0, f64::max);
        strip.max_abs_kn_per_mm = if normal_source == NormalSource::File {
            samples
                .iter()
                .map(|c| c.kn_per_mm.abs())
                .fold(0.0, f64::max)
        } else {
            // Residual at the nodes: the curvature vector against the node normal.
            nodes
                .iter()
                .map(|cn| {
                    debug_assert_eq!(smooth.locate_station(cn.station_mm), (cn.segment, cn.u));
                    curvature_vector(smooth, cn.segment, cn.u)
                        .dot(all_nodes[cn.node].normal_world)
                        .abs()
                })
                .fold(0.0, f64::max)
        };
        strip.samples = samples;
        strip
    }

    /// Below this curvature (1/mm) the strip counts as straight.
    pub fn straight_curvature_per_mm(&self) -> f64 {
        self.straight_curvature_per_mm
    }

    /// Lengths between consecutive nodes, mm.
    pub fn node_to_node_mm(&self) -> Vec<f64> {
        self.nodes
            .windows(2)
            .map(|w| w[1].station_mm - w[0].station_mm)
            .collect()
    }

    /// Minimum bending radius (mm), or None for a straight strip.
    pub fn min_bending_radius_mm(&self) -> Option<f64> {
        (self.max_abs_kg_per_mm > self.straight_curvature_per_mm)
            .then(|| 1.0 / self.max_abs_kg_per_mm)
    }

    /// The Darboux frame at a station.
    pub fn frame_at(&self, smooth: &SmoothCurve, station_mm: f64) -> DarbouxFrame {
        let (k, u) = smooth.locate_station(station_mm);
        self.frame_at_param(smooth, k, u, station_mm.clamp(0.0, smooth.length_mm()))
    }

    /// The Darboux frame at segment k, local u (station given by the caller).
    pub fn frame_at_param(
        &self,
        smooth: &SmoothCurve,
        k: usize,
        u: f64,
        station_mm: f64,
    ) -> DarbouxFrame {
        self.frame_of_jet(smooth.jet_at(k, u), k, u, station_mm)
    }

    /// The Darboux frame from the curve's jet `j` at segment k, local u
    /// (`j = smooth.jet_at(k, u)`; station given by the caller).
    fn frame_of_jet(&self, j: Jet, k: usize, u: f64, station_mm: f64) -> DarbouxFrame {
        let speed = j.d1.length();
        let x = j.d1 / speed;
        let kvec = curvature_of(&j);
        let (z, y, kn_per_mm, tg_per_mm) = match &self.normals {
            Normals::File(h) => {
                let nj = h.jet_at(k, u);
                let (zt, dz_dt) = unit_and_derivative(nj.value, nj.d1);
                let z = (zt - x * zt.dot(x)).try_normalize().unwrap_or(zt);
                let y = z.cross(x);
                let dz_ds = dz_dt / speed;
                (z, y, -dz_ds.dot(x), -dz_ds.dot(y))
            }
            Normals::Field(f) => {
                let (z, tg) = f.at_in(k, station_mm, j.value, x);
                (z, z.cross(x), kvec.dot(z), tg)
            }
        };
        DarbouxFrame {
            station_mm,
            point_world_mm: j.value,
            x,
            y,
            z,
            kg_per_mm: kvec.dot(y),
            kn_per_mm,
            tg_per_mm,
        }
    }

    /// Stations on the lamella line c(s) + dy·y(s) + dz·z(s) that correspond
    /// to the given centre-line stations (any order); see
    /// [`StripGeometry::offset_stations_many`].
    pub fn offset_stations(
        &self,
        smooth: &SmoothCurve,
        dy_mm: f64,
        dz_mm: f64,
        stations_mm: &[f64],
        max_step_mm: f64,
    ) -> Vec<f64> {
        self.offset_stations_many(smooth, &[(dy_mm, dz_mm)], stations_mm, max_step_mm)
            .pop()
            .unwrap_or_default()
    }

    /// For each offset (dy, dz), the stations on the lamella line
    /// c(s) + dy·y(s) + dz·z(s) that correspond to the given centre-line
    /// stations (any order): the line's arc length on the grid
    /// ([`StripGeometry::offset_arc_table`]), then each station from the
    /// grid point before it ([`StripGeometry::offset_stations_in`]).
    pub fn offset_stations_many(
        &self,
        smooth: &SmoothCurve,
        offsets_mm: &[(f64, f64)],
        stations_mm: &[f64],
        max_step_mm: f64,
    ) -> Vec<Vec<f64>> {
        // Where each requested station lies: (segment, local u).
        let mut hint = 0;
        let targets: Vec<(usize, f64)> = stations_mm
            .iter()
            .map(|&s| {
                let at = smooth.locate_station_near(s, hint);
                hint = at.0;
                at
            })
            .collect();
        let table = self.offset_arc_table(smooth, offsets_mm, max_step_mm);
        self.offset_stations_in(smooth, &table, &targets)
    }

    /// For each offset (dy, dz), the arc length of the lamella line
    /// c(s) + dy·y(s) + dz·z(s) from its start to every point of the
    /// strip's integration grid: every segment of the curve cut into
    /// ⌈length / `max_step_mm`⌉ equal steps of its parameter, each integrated by 4-point Gauss–Legendre in the curve's
    /// own parameter, ds' = sqrt((1 − dy·kg − dz·kn)² + (dz·tg)² + (dy·tg)²) ds
    /// (exact for integrands of degree 7 per step; the tests hold it to
    /// exact offset lines to 0.01 mm). The frames are evaluated once for
    /// all offsets. The grid depends on the curve and `max_step_mm` alone.
    pub fn offset_arc_table(
        &self,
        smooth: &SmoothCurve,
        offsets_mm: &[(f64, f64)],
        max_step_mm: f64,
    ) -> OffsetArcTable {
        let m = offsets_mm.len();
        let first = grid_first_points(smooth, max_step_mm);
        let points = first.last().map_or(1, |&g| g + 1);
        let mut cumulative_mm: Vec<f64> = Vec::with_capacity(points * m);
        let mut acc = vec![0.0; m];
        cumulative_mm.extend_from_slice(&acc);
        for (k, w) in first.windows(2).enumerate() {
            let piece = smooth.piece(k);
            let parts = w[1] - w[0];
            for p in 1..=parts {
                let (u0, u1) = ((p - 1) as f64 / parts as f64, p as f64 / parts as f64);
                self.add_offset_arcs(smooth, &piece, k, (u0, u1), offsets_mm, &mut acc);
                cumulative_mm.extend_from_slice(&acc);
            }
        }
        OffsetArcTable {
            offsets_mm: offsets_mm.to_vec(),
            max_step_mm,
            cumulative_mm,
        }
    }

    /// For each offset of `table` (made on this strip), the stations on its
    /// line of curve stations already located,
    /// `targets[i] = smooth.locate_station(station_i)`, in any order: the
    /// table's arc length at the grid point at or before each, plus 4-point
    /// Gauss–Legendre from there to the station. A station's value depends
    /// on the table and its own location alone, never on the other targets.
    pub fn offset_stations_in(
        &self,
        smooth: &SmoothCurve,
        table: &OffsetArcTable,
        targets: &[(usize, f64)],
    ) -> Vec<Vec<f64>> {
        let m = table.offsets_mm.len();
        let mut out: Vec<Vec<f64>> = vec![Vec::with_capacity(targets.len()); m];
        if m == 0 {
            return out;
        }
        let first = grid_first_points(smooth, table.max_step_mm);
        debug_assert_eq!(
            first.last().map_or(1, |&g| g + 1) * m,
            table.cumulative_mm.len(),
            "the table was made on another curve"
        );
        let segments = first.len() - 1;
        let mut acc = vec![0.0; m];
        let mut piece: Option<(usize, Piece)> = None;
        for &(k, u) in targets {
            // The grid point at or before (k, u), and the part past it.
            let (g, u0) = if segments == 0 {
                (0, u)
            } else {
                let k = k.min(segments - 1);
                let parts = first[k + 1] - first[k];
                let mut p = ((u * parts as f64).floor().max(0.0) as usize).min(parts);
                if p > 0 && p as f64 / parts as f64 > u {
                    p -= 1;
                }
                (first[k] + p, p as f64 / parts as f64)
            };
            acc.fill(0.0);
            if segments > 0 && u > u0 {
                let pc = match piece {
                    Some((pk, pc)) if pk == k => pc,
                    _ => {
                        let pc = smooth.piece(k);
                        piece = Some((k, pc));
                        pc
                    }
                };
                self.add_offset_arcs(smooth, &pc, k, (u0, u), &table.offsets_mm, &mut acc);
            }
            for (j, o) in out.iter_mut().enumerate() {
                o.push(table.cumulative_mm[g * m + j] + acc[j]);
            }
        }
        out
    }

    /// Add ∫ ds' over segment k from local u0 to u1 (4-point Gauss–Legendre)
    /// of each offset line (dy, dz) to `acc`.
    fn add_offset_arcs(
        &self,
        smooth: &SmoothCurve,
        piece: &Piece,
        k: usize,
        (u0, u1): (f64, f64),
        offsets_mm: &[(f64, f64)],
        acc: &mut [f64],
    ) {
        if u1 <= u0 {
            return;
        }
        for (u, s, w) in smooth.gauss_nodes4_in(piece, k, u0, u1) {
            let f = self.frame_of_jet(piece.jet(u), k, u, s);
            for (a, &(dy, dz)) in acc.iter_mut().zip(offsets_mm) {
                let c = 1.0 - dy * f.kg_per_mm - dz * f.kn_per_mm;
                *a += w * (c * c + (dz * f.tg_per_mm).powi(2) + (dy * f.tg_per_mm).powi(2)).sqrt();
            }
        }
    }
}

/// The index of every segment's first point on the integration grid of a
/// curve (segment k cut into `first[k + 1] − first[k]` =
/// ⌈length / `max_step_mm`⌉ equal steps of its parameter, at least one);
/// the last entry is the curve's end.
fn grid_first_points(smooth: &SmoothCurve, max_step_mm: f64) -> Vec<usize> {
    let knots = smooth.sample_stations_mm();
    let mut first = Vec::with_capacity(knots.len());
    let mut g = 0;
    first.push(g);
    for w in knots.windows(2) {
        g += ((w[1] - w[0]) / max_step_mm).ceil().max(1.0) as usize;
        first.push(g);
    }
    first
}

/// The arc length of lamella lines offset from one strip's curve at every
/// point of its integration grid ([`StripGeometry::offset_arc_table`]):
/// one f64 per offset per step of at most `max_step_mm`. Stations between
/// grid points come from [`StripGeometry::offset_stations_in`].
#[derive(Debug, Clone, PartialEq)]
pub struct OffsetArcTable {
    /// The offsets (dy, dz), mm, in the order given.
    offsets_mm: Vec<(f64, f64)>,
    /// Longest step of the grid along the curve, mm.
    max_step_mm: f64,
    /// At grid point g, offset j: `cumulative_mm[g · offsets + j]`, the arc
    /// length from the line's start, mm.
    cumulative_mm: Vec<f64>,
}

impl OffsetArcTable {
    /// The offsets (dy, dz) of the lines, mm, in the order given.
    pub fn offsets_mm(&self) -> &[(f64, f64)] {
        &self.offsets_mm
    }

    /// Longest step of the grid along the curve, mm.
    pub fn max_step_mm(&self) -> f64 {
        self.max_step_mm
    }

    /// Number of grid points (the curve's start and the end of every step).
    pub fn grid_points(&self) -> usize {
        self.cumulative_mm
            .len()
            .checked_div(self.offsets_mm.len())
            .unwrap_or(0)
    }

    /// Arc length of line j (by offset order) from its start to its end, mm.
    pub fn length_mm(&self, j: usize) -> f64 {
        let m = self.offsets_mm.len();
        self.cumulative_mm[self.cumulative_mm.len() - m + j]
    }
}

/// Curvature vector κN (1/mm) at segment k, local u.
fn curvature_vector(smooth: &SmoothCurve, k: usize, u: f64) -> DVec3 {
    curvature_of(&smooth.jet_at(k, u))
}

/// Curvature vector κN (1/mm) of a jet: the second derivative's part
/// normal to the tangent, over the squared speed.
fn curvature_of(j: &crate::geom::curve::Jet) -> DVec3 {
    let v2 = j.d1.length_squared();
    let x = j.d1 / v2.sqrt();
    (j.d2 - x * j.d2.dot(x)) / v2
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The helix θ ↦ (r cos θ, r sin θ, p θ), θ ∈ [0, 2π], sampled every
    /// 3°; with the cylinder's outward normals (cos θ, sin θ, 0) when
    /// `normals`.
    fn helix(r: f64, p: f64, normals: bool) -> (Curve, SmoothCurve) {
        let th: Vec<f64> = (0..=120).map(|k| f64::from(k * 3).to_radians()).collect();
        let points: Vec<DVec3> = th
            .iter()
            .map(|&t| DVec3::new(r * t.cos(), r * t.sin(), p * t))
            .collect();
        let curve = Curve {
            id: "A0".into(),
            family: Family::A,
            normals_world: normals.then(|| {
                th.iter()
                    .map(|&t| DVec3::new(t.cos(), t.sin(), 0.0))
                    .collect()
            }),
            points_world_mm: points,
        };
        let smooth = SmoothCurve::new(&curve.points_world_mm);
        (curve, smooth)
    }

    fn strip(curve: &Curve, smooth: &SmoothCurve) -> StripGeometry {
        StripGeometry::new(0, curve, smooth, &[], &[], FrameOptions::default())
    }

    fn close(got: f64, want: f64, tol: f64, what: &str) {
        assert!((got - want).abs() <= tol, "{what}: {got} against {want}");
    }

    fn close_vec(got: DVec3, want: DVec3, tol: f64, what: &str) {
        assert!(got.distance(want) <= tol, "{what}: {got} against {want}");
    }

    // Helix r = 1000 mm, p = 500 mm per radian: speed a = √(r² + p²) =
    // √1 250 000 = 1118.034 mm per radian, arc length s = a θ; tangent
    // x = (−r sin θ, r cos θ, p)/a, curvature vector −(r/a²)(cos θ, sin θ, 0),
    // |κ| = r/a² = 1/1250 mm, Frenet torsion τ = p/a² = 1/2500 mm.
    const R: f64 = 1000.0;
    const P: f64 = 500.0;
    const A2: f64 = R * R + P * P;

    #[test]
    fn helix_on_its_cylinder_is_a_geodesic_that_twists() {
        // Normal z = (cos θ, sin θ, 0) outward; y = z × x = (p sin θ,
        // −p cos θ, r)/a. kg = κ·y = 0 (a helix is a geodesic of the
        // cylinder); z' = (−sin θ, cos θ, 0)/a, so kn = −z'·x = −r/a² =
        // −0.0008 and tg = −z'·y = p/a² = 0.0004 per mm (the cylinder's
        // k1 = 1/r at cos φ = r/a to its circles: kn = k1 cos² φ, |tg| =
        // k1 sin φ cos φ).
        // Sampled every 3° (58.5 mm): curvatures to 1e-6 relative.
        let (curve, smooth) = helix(R, P, true);
        let s = strip(&curve, &smooth);
        assert_eq!(s.normal_source, NormalSource::File);
        let a = A2.sqrt();
        close(s.length_mm, a * std::f64::consts::TAU, 1e-5, "length");
        for c in &s.samples {
            close(c.kg_per_mm, 0.0, 5e-7, "kg");
            close(c.kn_per_mm, -R / A2, 1e-8, "kn");
            close(c.tg_per_mm, P / A2, 1e-8, "tg");
        }
        close(s.max_abs_tg_per_mm, 4e-4, 1e-8, "max |tg|");
        // |kg| stays below the straightness threshold (1e-5 per mm).
        assert_eq!(s.min_bending_radius_mm(), None, "a geodesic is not bent");
        // The frame a quarter turn in: θ = π/2, s = a π/2.
        let f = s.frame_at(&smooth, a * std::f64::consts::FRAC_PI_2);
        let at = DVec3::new(0.0, R, P * std::f64::consts::FRAC_PI_2);
        close_vec(f.point_world_mm, at, 1e-6, "point");
        close_vec(f.x, DVec3::new(-R, 0.0, P) / a, 2e-6, "x");
        close_vec(f.z, DVec3::Y, 1e-9, "z");
        close_vec(f.y, DVec3::new(P, 0.0, R) / a, 2e-6, "y");
    }

    #[test]
    fn without_normals_a_helix_takes_its_binormal() {
        // No file normals and no nodes: z is the binormal, so the Darboux
        // frame is Frenet's: kg = |κ| = r/a² = 0.0008, kn = 0, tg = τ = p/a²
        // = 0.0004 per mm; the smallest bending radius is a²/r = 1250 mm.
        // The normal's angle is fitted along the curve: near the ends (the
        // fit one-sided there) tg is good to 1 %, more than 1000 mm inside
        // to 5e-9 per mm (1e-5 relative).
        let (curve, smooth) = helix(R, P, false);
        let s = strip(&curve, &smooth);
        assert_eq!(s.normal_source, NormalSource::Binormal);
        for c in &s.samples {
            close(c.kg_per_mm.abs(), R / A2, 2e-7, "kg");
            close(c.kn_per_mm, 0.0, 5e-8, "kn");
            close(c.tg_per_mm, P / A2, 0.01 * P / A2, "tg");
            if c.station_mm > 1000.0 && c.station_mm < s.length_mm - 1000.0 {
                close(c.tg_per_mm, P / A2, 5e-9, "tg inside");
            }
        }
        close(
            s.min_bending_radius_mm().expect("bent"),
            1250.0,
            0.5,
            "radius",
        );
    }

    #[test]
    fn a_circle_in_its_plane_bends_without_twist() {
        // Radius 800 mm in z = 0, counter-clockwise, normals +z: y = z × x
        // points to the centre, kg = 1/800 = 0.00125, kn = tg = 0; length
        // 2π × 800. Sampled every 5° (69.7 mm): kg to 1e-3 relative.
        let points: Vec<DVec3> = (0..=72)
            .map(|k| {
                let t = f64::from(k * 5).to_radians();
                DVec3::new(800.0 * t.cos(), 800.0 * t.sin(), 0.0)
            })
            .collect();
        let curve = Curve {
            id: "B0".into(),
            family: Family::B,
            normals_world: Some(vec![DVec3::Z; points.len()]),
            points_world_mm: points,
        };
        let smooth = SmoothCurve::new(&curve.points_world_mm);
        let s = strip(&curve, &smooth);
        close(s.length_mm, 1600.0 * std::f64::consts::PI, 1e-4, "length");
        for c in &s.samples {
            close(c.kg_per_mm, 1.0 / 800.0, 1.25e-6, "kg");
            close(c.kn_per_mm, 0.0, 1e-12, "kn");
            close(c.tg_per_mm, 0.0, 1e-12, "tg");
        }
        // At 90°: the point (0, 800, 0), x = (−1, 0, 0), y = (0, −1, 0).
        let f = s.frame_at(&smooth, 400.0 * std::f64::consts::PI);
        close_vec(f.point_world_mm, DVec3::new(0.0, 800.0, 0.0), 1e-6, "point");
        close_vec(f.x, DVec3::NEG_X, 1e-8, "x");
        close_vec(f.y, DVec3::NEG_Y, 1e-8, "y");
        close_vec(f.z, DVec3::Z, 1e-12, "z");
        // Stations on the line 10 mm outside (dy = −10, radius 810 mm) at a
        // quarter and at the whole turn: 810 × π/2 and 810 × 2π.
        let on = s.offset_stations(
            &smooth,
            -10.0,
            0.0,
            &[400.0 * std::f64::consts::PI, s.length_mm],
            5.0,
        );
        close(on[0], 405.0 * std::f64::consts::PI, 1e-3, "quarter");
        close(on[1], 1620.0 * std::f64::consts::PI, 1e-3, "whole");
    }
}
