//! Runs the geometric stages in order: smooth curves → topology (nodes) →
//! strip geometry. Plain data in ([`Network`]), plain data out ([`Analysis`]).

pub mod lines;
pub mod normal_field;
pub mod strip;
pub mod topology;

use crate::analysis::strip::{FrameOptions, StripGeometry};
use crate::analysis::topology::{find_nodes, NodeOptions, Topology, Warning};
use crate::error::{Error, Result};
use crate::geom::curve::SmoothCurve;
use crate::network::{Family, Network};
use rayon::prelude::*;

/// Options of the geometric stages.
#[derive(Debug, Clone, Copy)]
pub struct AnalysisOptions {
    /// How nodes are found (tolerance, near-tangent warning angle).
    pub nodes: NodeOptions,
    /// How strip frames are built (normal field fit, straightness threshold).
    pub frames: FrameOptions,
    /// The grid the coordinates are rounded to, mm (0: exact): curves are
    /// smoothed to it. Defaults to what the file's decimals imply.
    pub precision_mm: f64,
}

impl AnalysisOptions {
    /// The defaults for a network: its node tolerance (mm), default frame
    /// options, and the precision its coordinates imply.
    pub fn for_network(net: &Network) -> AnalysisOptions {
        AnalysisOptions {
            nodes: NodeOptions::new(net.tolerance_mm),
            frames: FrameOptions::default(),
            precision_mm: net.precision_mm,
        }
    }
}

/// The network's geometry: smooth curves, nodes and strips, index-aligned
/// with `Network::curves`.
#[derive(Debug, Clone)]
pub struct Analysis {
    /// One smooth interpolant per curve of the network, in the world frame, mm.
    pub curves: Vec<SmoothCurve>,
    /// Every node, per-curve node lists and the topology warnings.
    pub topology: Topology,
    /// One strip per curve (edges included): frames, curvatures, node stations.
    pub strips: Vec<StripGeometry>,
}

impl Analysis {
    /// The topology stage's warnings, in the order they were found.
    pub fn warnings(&self) -> &[Warning] {
        &self.topology.warnings
    }

    /// The strips that become lamellas: families A and B, in strip order.
    /// Every stage that bends, checks or cuts lamellas starts here.
    pub fn lamella_strips(&self) -> impl Iterator<Item = &StripGeometry> + Clone + '_ {
        self.strips.iter().filter(|s| s.family != Family::Edge)
    }

    /// The edge strips (the cut boundary), in strip order: tangential to the
    /// surface, cut as curved bands, never checked as lamellas.
    pub fn edge_strips(&self) -> impl Iterator<Item = &StripGeometry> + Clone + '_ {
        self.strips.iter().filter(|s| s.family == Family::Edge)
    }
}

/// Interpolate, find nodes and compute strip geometry. Fails when the
/// network has no A×B crossing.
pub fn analyze(net: &Network, opts: AnalysisOptions) -> Result<Analysis> {
    let curves: Vec<SmoothCurve> = net
        .curves
        .par_iter()
        .map(|c| SmoothCurve::with_precision(&c.points_world_mm, opts.precision_mm))
        .collect();
    let topology = find_nodes(net, &curves, opts.nodes);
    let ab = topology
        .nodes
        .iter()
        .any(|n| net.curves[n.a].family == Family::A && net.curves[n.b].family == Family::B);
    if !ab {
        return Err(Error::network(
            &net.source,
            format!(
                "no A×B crossing within the tolerance of {} mm: is this an asymptotic network?",
                net.tolerance_mm
            ),
        ));
    }
    let strips: Vec<StripGeometry> = (0..net.curves.len())
        .into_par_iter()
        .map(|i| {
            StripGeometry::new(
                i,
                &net.curves[i],
                &curves[i],
                &topology.per_curve[i],
                &topology.nodes,
                opts.frames,
            )
        })
        .collect();
    Ok(Analysis {
        curves,
        topology,
        strips,
    })
}
