//! The frame model: plain data a frame solver takes, in N and mm.
//!
//! Units throughout: lengths mm, forces N, moments N·mm, stresses and moduli
//! MPa (N/mm²), distributed loads N/mm. Degrees of freedom per node, in the
//! global frame: `[ux, uy, uz, rx, ry, rz]` (mm and rad).
//!
//! Element local axes follow OpenSees' `geomTransf` convention so that the
//! model exports one to one (`DIR/structure/opensees.py`): local x runs from
//! the element's first node to its second; local z lies in the plane of x
//! and [`Beam::z_axis`] (the strip's height direction, the surface normal),
//! perpendicular to x; local y = z × x. Hence for an upright strip of height
//! h and thickness t:
//!
//! * `i_y_mm4` = t·h³/12 — about local y: bending that deflects along the
//!   normal (the strong axis; curvature kn);
//! * `i_z_mm4` = h·t³/12 — about local z: bending that deflects across the
//!   strip, in the surface (the weak axis; curvature kg);
//! * `j_mm4` — St. Venant torsion (twist tg).

use glam::{DMat3, DVec3};
use std::sync::Arc;

/// Number of degrees of freedom per node.
pub const DOF_PER_NODE: usize = 6;

/// A cross-section with its material.
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    /// Young's modulus, MPa.
    pub e_mpa: f64,
    /// Shear modulus, MPa.
    pub g_mpa: f64,
    /// Area, mm².
    pub area_mm2: f64,
    /// Second moment about local y (strong axis of an upright strip), mm⁴.
    pub i_y_mm4: f64,
    /// Second moment about local z (weak axis of an upright strip), mm⁴.
    pub i_z_mm4: f64,
    /// St. Venant torsion constant, mm⁴.
    pub j_mm4: f64,
}

/// Section forces a beam element carries before any load: the erection
/// state of a strip cut flat and straight and bent into place. Constant
/// along the element, in its local axes (N, N·mm); they add to the section
/// forces of every load combination and the axial force enters the
/// geometric stiffness.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct InitialForces {
    /// Axial force, N (tension positive).
    pub axial_n: f64,
    /// Torque about local x, N·mm.
    pub torque_nmm: f64,
    /// Moment about local y (strong axis), N·mm.
    pub moment_y_nmm: f64,
    /// Moment about local z (weak axis), N·mm.
    pub moment_z_nmm: f64,
}

/// A straight 3D Euler–Bernoulli beam element (12 degrees of freedom).
#[derive(Debug, Clone, PartialEq)]
pub struct Beam {
    /// Its two nodes (indices into [`FrameModel::nodes_mm`]), first → second
    /// is local x.
    pub nodes: [usize; 2],
    /// Index into [`FrameModel::sections`].
    pub section: usize,
    /// A direction in the local x–z plane, not parallel to the element (the
    /// strip's height direction). Need not be unit or exactly perpendicular.
    pub z_axis: DVec3,
    /// The erection state it carries before any load.
    pub initial: InitialForces,
    /// Rigid end offsets, global, mm: the element runs from
    /// `nodes[0] + offsets_mm[0]` to `nodes[1] + offsets_mm[1]`, each end
    /// tied rigidly to its node (u_end = u_node + θ_node × offset). A
    /// lamella meets its joint's node this way, on its own line beside
    /// the joint (OpenSees `geomTransf … -jntOffset`).
    pub offsets_mm: [DVec3; 2],
}

/// The two ends of an element on `nodes` with rigid end `offsets_mm`, at
/// node positions `nodes_mm`, mm.
fn ends(nodes: [usize; 2], offsets_mm: &[DVec3; 2], nodes_mm: &[DVec3]) -> [DVec3; 2] {
    [
        nodes_mm[nodes[0]] + offsets_mm[0],
        nodes_mm[nodes[1]] + offsets_mm[1],
    ]
}

impl Beam {
    /// Its two ends (its nodes plus their offsets) at node positions
    /// `nodes_mm`, mm.
    pub fn ends_mm(&self, nodes_mm: &[DVec3]) -> [DVec3; 2] {
        ends(self.nodes, &self.offsets_mm, nodes_mm)
    }

    /// Its length between its ends at node positions `nodes_mm`, mm.
    pub fn length_mm(&self, nodes_mm: &[DVec3]) -> f64 {
        let [a, b] = self.ends_mm(nodes_mm);
        a.distance(b)
    }
}

/// A zero-length spring between two nodes: six stiffnesses in a local frame
/// (translations along, rotations about the frame's columns). Joints
/// (bolted crossings, shear blocks, stud connections) are links; a "rigid"
/// tie is a link of a stiffness the model builder chooses (see its doc), so
/// that lamella and the OpenSees export solve exactly the same model
/// (OpenSees `zeroLength` with elastic materials, `-orient` from `frame`).
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    /// Its two nodes; they may be at different points (an eccentric link is
    /// a short stiff [`Beam`] instead).
    pub nodes: [usize; 2],
    /// Columns: the local axes (orthonormal).
    pub frame: DMat3,
    /// Translational stiffness along each axis, N/mm (0: free).
    pub translation_n_per_mm: [f64; 3],
    /// Rotational stiffness about each axis, N·mm/rad (0: free).
    pub rotation_nmm_per_rad: [f64; 3],
}

/// A tension-only bar between two nodes: a bracing cable. While taut it
/// carries N = T₀ + k·δ, δ its lengthening from the erected geometry and
/// k = (E·A + T₀)/L (= E·A/L₀ over its unstressed length
/// L₀ = L/(1 + T₀/(E·A))); where N would be negative it is slack and
/// carries nothing. T₀ is the pretension it is cut and tensioned for: its
/// force on the erected, unloaded geometry before the frame yields to it
/// (the frame's own shortening then takes some of it back, which the
/// analysis finds).
#[derive(Debug, Clone, PartialEq)]
pub struct Cable {
    /// Its two nodes.
    pub nodes: [usize; 2],
    /// Where it is fixed, from each node, global, mm (a fitting's point
    /// beside the node, tied rigidly to it).
    pub offsets_mm: [DVec3; 2],
    /// Metallic area, mm².
    pub area_mm2: f64,
    /// Young's modulus of the cable, MPa.
    pub e_mpa: f64,
    /// Pretension T₀, N (≥ 0).
    pub pretension_n: f64,
}

impl Cable {
    /// Its two ends at node positions `nodes_mm`, mm.
    pub fn ends_mm(&self, nodes_mm: &[DVec3]) -> [DVec3; 2] {
        ends(self.nodes, &self.offsets_mm, nodes_mm)
    }

    /// Its length between its ends (the erected length L), mm.
    pub fn length_mm(&self, nodes_mm: &[DVec3]) -> f64 {
        let [a, b] = self.ends_mm(nodes_mm);
        a.distance(b)
    }

    /// Its unstressed length L₀ = L/(1 + T₀/(E·A)), mm: what it is made
    /// to between its fixing points.
    pub fn unstressed_length_mm(&self, nodes_mm: &[DVec3]) -> f64 {
        self.length_mm(nodes_mm) / (1.0 + self.pretension_n / (self.e_mpa * self.area_mm2))
    }

    /// Its axial stiffness while taut, k = E·A/L₀ = (E·A + T₀)/L, N/mm.
    pub fn stiffness_n_per_mm(&self, nodes_mm: &[DVec3]) -> f64 {
        (self.e_mpa * self.area_mm2 + self.pretension_n) / self.length_mm(nodes_mm)
    }
}

/// How an analysis treats a frame's cables.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CableState {
    /// As built: taut or slack as the load makes them (each load set
    /// solved whole).
    TensionOnly,
    /// Held taut as bars, in compression too: what a cable pretensioned
    /// enough to stay taut does, and linear (the bracing design's model).
    Held,
}

/// A support: restrained global degrees of freedom of one node, and
/// optionally a translation restrained along one oblique direction (a
/// roller on an inclined bearing).
#[derive(Debug, Clone, PartialEq)]
pub struct Support {
    /// The node.
    pub node: usize,
    /// Which of `[ux, uy, uz, rx, ry, rz]` are fixed (global).
    pub fixed: [bool; 6],
    /// A unit direction along which translation is fixed (besides `fixed`).
    pub along: Option<DVec3>,
}

/// A distributed load on a beam element, uniform along it, in global
/// directions, N per mm of the element's length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElementLoad {
    /// The element (index into [`FrameModel::beams`]).
    pub beam: usize,
    /// Force per length, global, N/mm.
    pub force_n_per_mm: DVec3,
}

/// A force and moment on a node, global.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeLoad {
    /// The node.
    pub node: usize,
    /// Force, N.
    pub force_n: DVec3,
    /// Moment, N·mm.
    pub moment_nmm: DVec3,
}

/// A set of loads applied together (a load case or a combination of them,
/// already factored).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LoadSet {
    /// Its name (`G`, `S`, `W+`, `ULS-1`, …).
    pub name: String,
    /// Loads on nodes.
    pub nodes: Vec<NodeLoad>,
    /// Uniform loads on beam elements.
    pub beams: Vec<ElementLoad>,
    /// Pressures that follow their element's rotation.
    pub pressures: Vec<PressureLoad>,
    /// Load sets included whole, each times its factor: a combination's
    /// load cases, shared with the cases rather than copied into each
    /// combination (at 400 × 400 curves every element's own weight is
    /// 82 MB a copy). Read the loads through [`LoadSet::for_each_node_load`]
    /// and its siblings, which count these.
    pub parts: Vec<(Arc<LoadSet>, f64)>,
}

impl LoadSet {
    /// Every node load with the factor it applies with: 1 for the set's
    /// own, a part's factor (times its own part's, and so on) for a
    /// part's.
    pub fn for_each_node_load(&self, mut f: impl FnMut(&NodeLoad, f64)) {
        self.visit(1.0, &mut |set, k| set.nodes.iter().for_each(|l| f(l, k)));
    }

    /// Every element load with the factor it applies with (as
    /// [`LoadSet::for_each_node_load`]).
    pub fn for_each_beam_load(&self, mut f: impl FnMut(&ElementLoad, f64)) {
        self.visit(1.0, &mut |set, k| set.beams.iter().for_each(|l| f(l, k)));
    }

    /// Every pressure with the factor it applies with (as
    /// [`LoadSet::for_each_node_load`]).
    pub fn for_each_pressure(&self, mut f: impl FnMut(&PressureLoad, f64)) {
        self.visit(1.0, &mut |set, k| {
            set.pressures.iter().for_each(|l| f(l, k))
        });
    }

    /// This set with `factor`, then each part with its factor times it.
    fn visit(&self, factor: f64, f: &mut dyn FnMut(&LoadSet, f64)) {
        f(self, factor);
        for (part, k) in &self.parts {
            part.visit(factor * k, f);
        }
    }
}

/// A uniform pressure on a beam element along its own local z axis (the
/// surface normal of an upright strip), N per mm of its length, that turns
/// with the element's chord: hydrostatic pressure on an arch, wind on a
/// surface. Its load stiffness enters the buckling analysis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PressureLoad {
    /// The element (index into [`FrameModel::beams`]).
    pub beam: usize,
    /// Force per length along the element's local z, N/mm.
    pub n_per_mm: f64,
}

/// The frame: nodes, elements, links and supports. Plain data; the solver
/// checks indices and reports a mechanism by the node that moves.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FrameModel {
    /// Node positions, mm.
    pub nodes_mm: Vec<DVec3>,
    /// Sections.
    pub sections: Vec<Section>,
    /// Beam elements.
    pub beams: Vec<Beam>,
    /// Zero-length springs.
    pub links: Vec<Link>,
    /// Tension-only cables (bracing).
    pub cables: Vec<Cable>,
    /// Supports.
    pub supports: Vec<Support>,
}

/// Which limit state a combination is checked at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LimitState {
    /// Ultimate (EN 1990 6.10): strength and stability.
    Ultimate,
    /// Serviceability, characteristic (EN 1990 6.14b): deflection.
    Serviceability,
}

impl LimitState {
    /// `ULS` or `SLS`.
    pub fn as_str(self) -> &'static str {
        match self {
            LimitState::Ultimate => "ULS",
            LimitState::Serviceability => "SLS",
        }
    }
}

/// A factored combination of load cases.
#[derive(Debug, Clone, PartialEq)]
pub struct Combination {
    /// The factored loads (their name is the combination's).
    pub loads: LoadSet,
    /// Where it is checked.
    pub limit_state: LimitState,
}

/// What a beam element is, for the verdict: a lamella's element (checked)
/// or a connecting piece (a block, a link beam: not checked; `None` in the
/// roles list).
#[derive(Debug, Clone, PartialEq)]
pub struct BeamRole {
    /// Index of the strip in the network (file order).
    pub strip: usize,
    /// The lamella of the strip (1 or 2).
    pub lamella: u32,
    /// The element's middle, as a station along its lamella's line, mm.
    pub station_mm: f64,
    /// The member's length between restraints (the crossing nodes), mm.
    pub member_span_mm: f64,
    /// σ_w = E·tg²·h²/12 of the erection twist there, MPa.
    pub trapeze_mpa: f64,
}

/// What loads and supports are applied to, named as the user names them
/// (network node ids, strip ids), built with the model.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LoadTargets {
    /// Per model node: the surface area it carries times the unit surface
    /// normal there (normal oriented with z ≥ 0), mm²; zero for nodes that
    /// are not joints. Σ over nodes of the area is the grid's surface area;
    /// |z component| is the plan-projected area (snow).
    pub tributary_mm2: Vec<DVec3>,
    /// Network node id → the model node of that joint.
    pub node_ids: std::collections::BTreeMap<String, usize>,
    /// Strip id → its lamella elements (beam indices), in order along it.
    pub strip_beams: std::collections::BTreeMap<String, Vec<usize>>,
    /// Self-weight of every beam element from the kit (the lamella's
    /// material), N per mm of its length, acting along −z; 0 for links.
    pub beam_weight_n_per_mm: Vec<f64>,
    /// Hardware and small parts (bolts, washers, shear blocks, studs,
    /// splice plates) lumped at model nodes, N, along −z.
    pub node_weight_n: Vec<f64>,
    /// Per model node: where its weight acts, from the node, mm (the
    /// weights' centre: parts on a lamella tied rigidly to the node, such
    /// as a shear block's half on the far lamella, act beside it, so the
    /// node takes their moment too).
    pub node_weight_lever_mm: Vec<DVec3>,
    /// The joints on the network's boundary (a strip's first or last
    /// node), model node indices, ascending.
    pub boundary_nodes: Vec<usize>,
}

#[cfg(test)]
impl Section {
    /// The steel prototype's strip, 1.5 × 50 mm, for unit tests.
    pub(crate) fn steel_strip() -> Section {
        Section {
            e_mpa: 210_000.0,
            g_mpa: 81_000.0,
            area_mm2: 75.0,
            i_y_mm4: 15_625.0,
            i_z_mm4: 14.0625,
            j_mm4: 52.0,
        }
    }
}
