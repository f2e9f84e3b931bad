//! The finished model later stages and writers build on: per-strip node
//! bookkeeping, every lamella on its own offset line with the stations of
//! its nodes, the network's summary statistics and, after `check`, the
//! profile and the check. Everything is computed here, once; writers
//! (`io::plan`) only format it.
//!
//! Lamella lines exist for A and B strips only: edge strips lie tangential
//! to the surface and are cut as curved bands (fabrication.md).

use crate::analysis::strip::{OffsetArcTable, StripGeometry};
use crate::analysis::Analysis;
use crate::check::{CheckReport, Suggestion};
use crate::geom::curve::SmoothCurve;
use crate::network::{Family, Network};
use crate::profile::{LamellaOffset, Profile};
use rayon::prelude::*;

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
/// ([`crate::check::check_with_lines`]), for fabrication to carry its
/// stations onto without integrating the lines again
/// ([`crate::fabricate::fabricate_with_lines`]).
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

/// Summary statistics of a network.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// Number of curves in the network, edges included.
    pub curves: usize,
    /// Number of nodes (A×B, A×edge and B×edge).
    pub nodes: usize,
    /// Sum of every strip's curve length, edges included, mm.
    pub total_length_mm: f64,
    /// Shortest distance between consecutive nodes along a curve, mm, over all
    /// strips; None when no strip has two nodes.
    pub shortest_node_to_node_mm: Option<f64>,
    /// Longest distance between consecutive nodes along a curve, mm, over all
    /// strips; None when no strip has two nodes.
    pub longest_node_to_node_mm: Option<f64>,
    /// The kn residual over A and B strips (edges are not asymptotic).
    pub max_normal_curvature_per_mm: f64,
    /// Crossing angles over A×B nodes (edges do not cross at 90°).
    pub min_angle_deg: Option<f64>,
    /// Largest acute crossing angle over A×B nodes, degrees; None without one.
    pub max_angle_deg: Option<f64>,
}

impl Summary {
    /// The summary of an analysed network (`an` computed from `net`).
    pub fn of(net: &Network, an: &Analysis) -> Summary {
        let all_n2n: Vec<f64> = an.strips.iter().flat_map(|s| s.node_to_node_mm()).collect();
        let angles: Vec<f64> = an
            .topology
            .nodes
            .iter()
            .filter(|n| net.curves[n.a].family == Family::A && net.curves[n.b].family == Family::B)
            .map(|n| n.angle_deg)
            .collect();
        Summary {
            curves: net.curves.len(),
            nodes: an.topology.nodes.len(),
            total_length_mm: an.strips.iter().map(|s| s.length_mm).sum(),
            shortest_node_to_node_mm: all_n2n.iter().copied().reduce(f64::min),
            longest_node_to_node_mm: all_n2n.iter().copied().reduce(f64::max),
            max_normal_curvature_per_mm: an
                .lamella_strips()
                .map(|s| s.max_abs_kn_per_mm)
                .fold(0.0, f64::max),
            min_angle_deg: angles.iter().copied().reduce(f64::min),
            max_angle_deg: angles.iter().copied().reduce(f64::max),
        }
    }
}

/// One strip of the model (index-aligned with `Analysis::strips`).
#[derive(Debug, Clone, PartialEq)]
pub struct StripModel {
    /// Lengths between consecutive nodes on the curve.
    pub node_to_node_mm: Vec<f64>,
    /// From the curve's start to its first node; None without nodes.
    pub start_to_first_node_mm: Option<f64>,
    /// From the last node to the curve's end; None without nodes.
    pub last_node_to_end_mm: Option<f64>,
    /// Every lamella on its own line (A and B strips; empty for edges).
    pub lamellas: Vec<LamellaLine>,
}

/// The profile a network was checked against, and the results.
#[derive(Debug, Clone, PartialEq)]
pub struct Checked {
    /// The profile checked against (validated).
    pub profile: Profile,
    /// Per strip and per lamella: stresses, utilisation, governing station.
    pub report: CheckReport,
    /// What to change in the section so every strip passes, when asked for (`check --suggest`).
    pub suggestion: Option<Suggestion>,
}

/// The finished model of a network.
///
/// Guarantees: one [`StripModel`] per strip, index-aligned with
/// `Analysis::strips`; lamella lines for A and B strips only (none on
/// edges): without a profile one on the centre line, after `check` the
/// profile's lamellas, taken from the check report; each line lists the
/// strip's nodes in the strip's order at ascending stations on its own line,
/// the last at most its length.
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    /// Counts, lengths and extreme values over the whole network.
    pub summary: Summary,
    /// One per strip, index-aligned with `Analysis::strips` (and the network's curves).
    pub strips: Vec<StripModel>,
    /// Added by `check`.
    pub check: Option<Checked>,
}

impl Model {
    /// Without a profile: one lamella per A/B strip, on the centre line.
    pub fn new(net: &Network, an: &Analysis) -> Model {
        let lines: Vec<Vec<LamellaLine>> = an
            .strips
            .par_iter()
            .map(|s| {
                if s.family == Family::Edge {
                    Vec::new()
                } else {
                    vec![LamellaLine::new(
                        s,
                        &an.curves[s.curve],
                        LamellaOffset::CENTRE,
                    )]
                }
            })
            .collect::<Vec<_>>();
        Model::build(net, an, lines, None)
    }

    /// After the check: the profile's lamellas (taken from the report, which
    /// computed their lines), the profile and the results.
    pub fn checked(
        net: &Network,
        an: &Analysis,
        profile: Profile,
        report: CheckReport,
        suggestion: Option<Suggestion>,
    ) -> Model {
        let mut lines: Vec<Vec<LamellaLine>> = vec![Vec::new(); an.strips.len()];
        for sc in &report.strips {
            lines[sc.strip] = sc.lamellas.iter().map(|l| l.line.clone()).collect();
        }
        Model::build(
            net,
            an,
            lines,
            Some(Checked {
                profile,
                report,
                suggestion,
            }),
        )
    }

    fn build(
        net: &Network,
        an: &Analysis,
        lines: Vec<Vec<LamellaLine>>,
        check: Option<Checked>,
    ) -> Model {
        let strips = an
            .strips
            .iter()
            .zip(lines)
            .map(|(s, lamellas)| StripModel {
                node_to_node_mm: s.node_to_node_mm(),
                start_to_first_node_mm: s.nodes.first().map(|n| n.station_mm),
                last_node_to_end_mm: s.nodes.last().map(|n| s.length_mm - n.station_mm),
                lamellas,
            })
            .collect();
        Model {
            summary: Summary::of(net, an),
            strips,
            check,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
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
