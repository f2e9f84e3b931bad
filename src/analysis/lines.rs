//! Lamella lines: every lamella of a strip on its own offset line, with
//! the stations of the strip's nodes on that line, integrated once on a
//! fixed grid ([`StripLines`]) and shared by the check and fabrication
//! ([`NetworkLines`]).
//!
//! Lamella lines exist for A and B strips only: edge strips lie tangential
//! to the surface and are cut as curved bands (docs/fabrication.md).

use crate::analysis::strip::{OffsetArcTable, StripGeometry};
use crate::geom::curve::SmoothCurve;
use crate::profile::LamellaOffset;

/// Largest integration step (mm) along a lamella line.
pub const LINE_STEP_MM: f64 = 100.0;

/// A node seen from one lamella: its station on the lamella's own line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LamellaNode {
    /// Node id (index into `Topology::nodes`).
    pub node: usize,
    /// Arc length along the lamella line from its start, mm.
    pub station_mm: f64,
}

/// One lamella of a strip on its own offset line c(s) + dy·y(s) + dz·z(s).
#[derive(Debug, Clone, PartialEq)]
pub struct LamellaLine {
    /// Number (1 on −y, 2 on +y) and offsets from the strip's curve.
    pub offset: LamellaOffset,
    /// Length of the lamella line, mm.
    pub length_mm: f64,
    /// The strip's nodes in the strip's order, at their stations on this line.
    pub nodes: Vec<LamellaNode>,
}

impl LamellaLine {
    /// The lamella line of `offset` on a strip.
    pub fn new(strip: &StripGeometry, smooth: &SmoothCurve, offset: LamellaOffset) -> LamellaLine {
        StripLines::new(strip, smooth, &[offset])
            .lines
            .swap_remove(0)
    }

    /// The lamella line of `offset` on a strip, and the line stations of the
    /// given curve stations (any order) ([`StripLines`]). On the centre line
    /// (dy = dz = 0) the stations are the curve's.
    pub fn with_stations(
        strip: &StripGeometry,
        smooth: &SmoothCurve,
        offset: LamellaOffset,
        curve_stations_mm: &[f64],
    ) -> (LamellaLine, Vec<f64>) {
        let mut lines =
            LamellaLine::with_stations_many(strip, smooth, &[offset], curve_stations_mm);
        lines.swap_remove(0)
    }

    /// [`LamellaLine::with_stations`] for several lamellas of one strip at
    /// once: the frames along the strip are evaluated once for all of them.
    pub fn with_stations_many(
        strip: &StripGeometry,
        smooth: &SmoothCurve,
        offsets: &[LamellaOffset],
        curve_stations_mm: &[f64],
    ) -> Vec<(LamellaLine, Vec<f64>)> {
        let lines = StripLines::new(strip, smooth, offsets);
        let stations = lines.stations(strip, smooth, curve_stations_mm);
        lines.lines.into_iter().zip(stations).collect()
    }

    /// Lengths between consecutive nodes on this line, mm.
    pub fn node_to_node_mm(&self) -> Vec<f64> {
        self.nodes
            .windows(2)
            .map(|w| w[1].station_mm - w[0].station_mm)
            .collect()
    }
}

/// Every lamella line of one strip from one integration along it: the
/// lines (node stations, lengths) and, for the lines off the centre line,
/// their arc length at every point of the strip's integration grid (steps
/// of at most [`LINE_STEP_MM`]; [`StripGeometry::offset_arc_table`]), so
/// a further station costs one short integral from the grid point before
/// it ([`StripLines::stations`]). No line and no station depends on which
/// other stations are asked for: the check and fabrication, asking for
/// different ones, share one integration and agree on every node.
#[derive(Debug, Clone, PartialEq)]
pub struct StripLines {
    /// Index of the strip the lines lie on (`Analysis::strips`).
    pub strip: usize,
    /// One per offset, in the order given.
    pub lines: Vec<LamellaLine>,
    /// The arc lengths on the grid of the lines off the centre line, in
    /// their order; None when every line is the centre line.
    arc: Option<OffsetArcTable>,
}

impl StripLines {
    /// The lines of `offsets` (any number, the centre line among them or
    /// not) on a strip: every node's station on each line.
    pub fn new(
        strip: &StripGeometry,
        smooth: &SmoothCurve,
        offsets: &[LamellaOffset],
    ) -> StripLines {
        let off: Vec<(f64, f64)> = offsets
            .iter()
            .filter(|o| !is_centre(o))
            .map(|o| (o.dy_mm, o.dz_mm))
            .collect();
        let arc = (!off.is_empty()).then(|| strip.offset_arc_table(smooth, &off, LINE_STEP_MM));
        // The nodes where the topology found them on the curve.
        let at_nodes: Vec<(usize, f64)> = strip.nodes.iter().map(|cn| (cn.segment, cn.u)).collect();
        let mut on_lines = match &arc {
            Some(table) => strip.offset_stations_in(smooth, table, &at_nodes),
            None => Vec::new(),
        }
        .into_iter();
        let mut off_index = 0;
        let lines = offsets
            .iter()
            .map(|&offset| {
                let (stations, length_mm): (Vec<f64>, f64) = match &arc {
                    Some(table) if !is_centre(&offset) => {
                        let length = table.length_mm(off_index);
                        off_index += 1;
                        (on_lines.next().unwrap_or_default(), length)
                    }
                    _ => (
                        strip.nodes.iter().map(|n| n.station_mm).collect(),
                        strip.length_mm,
                    ),
                };
                LamellaLine {
                    offset,
                    length_mm,
                    nodes: strip
                        .nodes
                        .iter()
                        .zip(stations)
                        .map(|(cn, station_mm)| LamellaNode {
                            node: cn.node,
                            station_mm,
                        })
                        .collect(),
                }
            })
            .collect();
        StripLines {
            strip: strip.curve,
            lines,
            arc,
        }
    }

    /// For each line, in order, the line stations of the given curve
    /// stations (any order; `strip` and `smooth` the ones the lines were
    /// made on): the grid's arc length before each, plus one 4-point Gauss
    /// integral to it. On the centre line the stations are the curve's.
    pub fn stations(
        &self,
        strip: &StripGeometry,
        smooth: &SmoothCurve,
        curve_stations_mm: &[f64],
    ) -> Vec<Vec<f64>> {
        debug_assert_eq!(strip.curve, self.strip, "lines of another strip");
        let mut integrated = match &self.arc {
            Some(table) => {
                // Located in order, each search from the last; put back.
                let mut order: Vec<usize> = (0..curve_stations_mm.len()).collect();
                order.sort_by(|&a, &b| curve_stations_mm[a].total_cmp(&curve_stations_mm[b]));
                let mut hint = 0;
                let located: Vec<(usize, f64)> = order
                    .iter()
                    .map(|&i| {
                        let at = smooth.locate_station_near(curve_stations_mm[i], hint);
                        hint = at.0;
                        at
                    })
                    .collect();
                strip
                    .offset_stations_in(smooth, table, &located)
                    .into_iter()
                    .map(|got| {
                        let mut out = vec![0.0; got.len()];
                        for (&i, s) in order.iter().zip(got) {
                            out[i] = s;
                        }
                        out
                    })
                    .collect()
            }
            None => Vec::new(),
        }
        .into_iter();
        self.lines
            .iter()
            .map(|l| {
                if is_centre(&l.offset) {
                    curve_stations_mm.to_vec()
                } else {
                    integrated.next().unwrap_or_default()
                }
            })
            .collect()
    }

    /// Whether these are the lines of exactly `offsets` (in that order) on strip `strip`.
    pub fn are_of(&self, strip: usize, offsets: &[LamellaOffset]) -> bool {
        self.strip == strip
            && self
                .lines
                .iter()
                .map(|l| l.offset)
                .eq(offsets.iter().copied())
    }
}

/// The lamella lies on the strip's curve itself (dy = dz = 0).
fn is_centre(o: &LamellaOffset) -> bool {
    o.dy_mm == 0.0 && o.dz_mm == 0.0
}

/// The [`StripLines`] of every A and B strip for one profile, by strip
/// (`Analysis::strips`; none on edges): what the check integrated
/// ([`crate::check::check`] keeping its lines), for fabrication to carry its
/// stations onto without integrating the lines again
/// ([`crate::fabricate::fabricate`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NetworkLines {
    by_strip: Vec<Option<StripLines>>,
}

impl NetworkLines {
    /// From the lines of some strips (each at its `strip` index).
    pub fn new(lines: impl IntoIterator<Item = StripLines>) -> NetworkLines {
        let mut by_strip: Vec<Option<StripLines>> = Vec::new();
        for l in lines {
            if by_strip.len() <= l.strip {
                by_strip.resize(l.strip + 1, None);
            }
            let i = l.strip;
            by_strip[i] = Some(l);
        }
        NetworkLines { by_strip }
    }

    /// The lines of strip `i`, if kept.
    pub fn get(&self, i: usize) -> Option<&StripLines> {
        self.by_strip.get(i).and_then(Option::as_ref)
    }

    /// Take the lines of strip `i` out, if kept.
    pub fn take(&mut self, i: usize) -> Option<StripLines> {
        self.by_strip.get_mut(i).and_then(Option::take)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::Analysis;
    use crate::formats::read::{read_network, ReadOptions};
    use crate::{analyze, AnalysisOptions};
    use std::path::Path;

    fn enneper() -> Analysis {
        let net = read_network(
            Path::new(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/samples/enneper-4m.yaml"
            )),
            ReadOptions::default(),
        )
        .expect("enneper-4m");
        analyze(&net, AnalysisOptions::for_network(&net)).expect("analysis")
    }

    const OFFSETS: [LamellaOffset; 2] = [
        LamellaOffset {
            number: 1,
            dy_mm: -10.75,
            dz_mm: 0.0,
        },
        LamellaOffset {
            number: 2,
            dy_mm: 10.75,
            dz_mm: 25.0,
        },
    ];

    /// A grid step shorter than the sample's segments (about 21 mm).
    const FINE_STEP_MM: f64 = 7.0;

    /// Curve stations off the nodes and the grid, spread over the strip.
    fn extras(strip: &StripGeometry) -> Vec<f64> {
        (1..12)
            .map(|i| strip.length_mm * (i as f64 - 0.37) / 11.0)
            .collect()
    }

    #[test]
    fn line_stations_do_not_depend_on_the_others_asked_for() {
        let an = enneper();
        let mut compared = 0;
        for s in an.lamella_strips() {
            let smooth = &an.curves[s.curve];
            let extra = extras(s);
            let alone = LamellaLine::with_stations_many(s, smooth, &OFFSETS, &[]);
            let all = LamellaLine::with_stations_many(s, smooth, &OFFSETS, &extra);
            for ((line_alone, _), (line_all, on_line)) in alone.iter().zip(&all) {
                // Bit for bit: the nodes and the length, with or without extras.
                assert_eq!(line_alone, line_all, "{}", s.id);
                assert_eq!(on_line.len(), extra.len());
            }
            // Each extra alone, in another order, or with the nodes' own
            // curve stations: the same value.
            let mut reversed = extra.clone();
            reversed.reverse();
            let backwards = LamellaLine::with_stations_many(s, smooth, &OFFSETS, &reversed);
            let at_nodes: Vec<f64> = s.nodes.iter().map(|n| n.station_mm).collect();
            let nodes_again = LamellaLine::with_stations_many(s, smooth, &OFFSETS, &at_nodes);
            for (i, &e) in extra.iter().enumerate() {
                let one = LamellaLine::with_stations_many(s, smooth, &OFFSETS, &[e]);
                for j in 0..OFFSETS.len() {
                    assert_eq!(one[j].1[0], all[j].1[i], "{} at {e}", s.id);
                    assert_eq!(backwards[j].1[extra.len() - 1 - i], all[j].1[i]);
                }
                compared += 1;
            }
            // On a grid finer than the segments (several steps each), too.
            let off: Vec<(f64, f64)> = OFFSETS.iter().map(|o| (o.dy_mm, o.dz_mm)).collect();
            let fine = s.offset_stations_many(smooth, &off, &extra, FINE_STEP_MM);
            for (i, &e) in extra.iter().enumerate() {
                let one = s.offset_stations_many(smooth, &off, &[e], FINE_STEP_MM);
                for j in 0..off.len() {
                    assert_eq!(one[j][0], fine[j][i], "{} at {e}", s.id);
                }
            }
            for j in 0..OFFSETS.len() {
                assert_eq!(nodes_again[j].0, all[j].0, "{}", s.id);
                for (n, &got) in all[j].0.nodes.iter().zip(&nodes_again[j].1) {
                    assert!((n.station_mm - got).abs() < 1e-9, "{}", s.id);
                }
            }
        }
        assert!(compared > 100, "{compared} stations compared");
    }

    /// ∫ ds' from the curve's start to (segment k, local u) on the line
    /// offset (dy, dz), every segment cut into `parts` equal steps of its
    /// parameter (the last one's at u), 4-point Gauss each.
    fn refined(
        strip: &StripGeometry,
        smooth: &SmoothCurve,
        (dy, dz): (f64, f64),
        (k_to, u_to): (usize, f64),
        parts: usize,
    ) -> f64 {
        let mut sum = 0.0;
        for k in 0..=k_to {
            let end = if k == k_to { u_to } else { 1.0 };
            for p in 0..parts {
                let (u0, u1) = (
                    end * p as f64 / parts as f64,
                    end * (p + 1) as f64 / parts as f64,
                );
                for (u, s, w) in smooth.gauss_nodes4(k, u0, u1) {
                    let f = strip.frame_at_param(smooth, k, u, s);
                    let a = 1.0 - dy * f.kg_per_mm - dz * f.kn_per_mm;
                    sum += w
                        * (a * a + (dz * f.tg_per_mm).powi(2) + (dy * f.tg_per_mm).powi(2)).sqrt();
                }
            }
        }
        sum
    }

    #[test]
    fn line_stations_agree_with_a_refined_integration() {
        let an = enneper();
        let mut worst: f64 = 0.0;
        for s in an.lamella_strips().step_by(5) {
            let smooth = &an.curves[s.curve];
            let extra = extras(s);
            let all = LamellaLine::with_stations_many(s, smooth, &OFFSETS, &extra);
            for (o, (line, on_line)) in OFFSETS.iter().zip(&all) {
                let off = (o.dy_mm, o.dz_mm);
                for (&e, &got) in extra.iter().zip(on_line) {
                    let want = refined(s, smooth, off, smooth.locate_station(e), 8);
                    worst = worst.max((got - want).abs());
                }
                for (n, cn) in line.nodes.iter().zip(&s.nodes).step_by(3) {
                    let want = refined(s, smooth, off, (cn.segment, cn.u), 8);
                    worst = worst.max((n.station_mm - want).abs());
                }
                let last = smooth.sample_stations_mm().len() - 2;
                let want = refined(s, smooth, off, (last, 1.0), 8);
                worst = worst.max((line.length_mm - want).abs());
                // A grid of several steps per segment: stations past its
                // inner points.
                let fine = s.offset_stations(smooth, off.0, off.1, &extra, FINE_STEP_MM);
                for (&e, &got) in extra.iter().zip(&fine) {
                    let want = refined(s, smooth, off, smooth.locate_station(e), 8);
                    worst = worst.max((got - want).abs());
                }
            }
        }
        eprintln!("worst {worst:e}");
        assert!(worst < 1e-9, "{worst} mm from the refined integration");
    }
}
