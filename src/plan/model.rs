//! The finished model the plan is formatted from: per-strip node
//! bookkeeping, every lamella on its own offset line with the stations of
//! its nodes, the network's summary statistics and, after `check`, the
//! profile and the check. Everything is computed here, once; the plan
//! only rounds and names it.

use crate::analysis::lines::LamellaLine;
use crate::analysis::Analysis;
use crate::check::{CheckReport, Suggestion};
use crate::network::{Family, Network};
use crate::profile::{LamellaOffset, Profile};
use rayon::prelude::*;

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
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Checked<'a> {
    /// The profile checked against (validated).
    pub profile: &'a Profile,
    /// Per strip and per lamella: stresses, utilisation, governing station.
    pub report: &'a CheckReport,
    /// What to change in the section so every strip passes, when asked for (`check --suggest`).
    pub suggestion: Option<&'a Suggestion>,
    /// The profile in the form of its file (current version), as plan.json
    /// writes it under `resolved`: the pipeline, which reads files, makes it.
    pub resolved: &'a serde_json::Value,
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
pub struct Model<'a> {
    /// Counts, lengths and extreme values over the whole network.
    pub summary: Summary,
    /// One per strip, index-aligned with `Analysis::strips` (and the network's curves).
    pub strips: Vec<StripModel>,
    /// Added by `check`.
    pub check: Option<Checked<'a>>,
}

impl<'a> Model<'a> {
    /// The model of an analysed network: without a check, one lamella per
    /// A/B strip on the centre line; after the check, the profile's
    /// lamellas (taken from the report, which computed their lines), the
    /// profile and the results.
    pub fn new(net: &Network, an: &Analysis, check: Option<Checked<'a>>) -> Model<'a> {
        let lines: Vec<Vec<LamellaLine>> = match &check {
            None => an
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
                .collect::<Vec<_>>(),
            Some(c) => {
                let mut lines: Vec<Vec<LamellaLine>> = vec![Vec::new(); an.strips.len()];
                for sc in &c.report.strips {
                    lines[sc.strip] = sc.lamellas.iter().map(|l| l.line.clone()).collect();
                }
                lines
            }
        };
        Model::build(net, an, lines, check)
    }

    fn build(
        net: &Network,
        an: &Analysis,
        lines: Vec<Vec<LamellaLine>>,
        check: Option<Checked<'a>>,
    ) -> Model<'a> {
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
