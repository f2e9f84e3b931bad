//! The frame model of the erected grid, built from the analysis and the kit.
//!
//! Input: the [`Network`], its [`Analysis`], the [`Profile`] and the
//! [`Kit`] fabricated for it (the shear blocks' and splices' stations, the
//! parts' and the hardware's masses). Output: a [`BuiltFrame`]: the
//! [`FrameModel`] (supports left empty: the loads stage chooses them), one
//! [`BeamRole`] per beam and the [`LoadTargets`]. Units N, mm (see
//! [`crate::structure::model`]).
//!
//! **Lamellas.** Every lamella of every A and B strip (one or two per the
//! profile) is a chain of beam elements on its own offset line
//! ([`StripLines`]: the nodes' stations on that line, integrated once),
//! from the strip's first node to its last, with
//! [`FrameOptions::elements_per_span`] elements of equal arc length (on the
//! lamella's line) between consecutive nodes (A×B crossings and the nodes
//! on edge strips). A curve station is found for every line station by
//! Newton's method on the line's arc length (derivative: the stretch
//! ds'/ds), to 1e-9 mm. The parts of a lamella beyond its first and last
//! node are not modelled (on the shipped samples the strips end on the
//! edge strips, where that overhang is nil).
//!
//! * Section (upright rectangle, t across, h along the normal): A = t·h,
//!   I_y = t·h³/12 (strong: deflection along the normal), I_z = h·t³/12
//!   (weak), J = h·t³·(1/3 − 0.21·(t/h)·(1 − (t/h)⁴/12)) (Roark, thin
//!   rectangle), E and G of the material. `z_axis` = the surface normal at
//!   the element's middle.
//! * Erection state (the strip is cut flat and straight: its rest state
//!   has no curvature): in the local axes (x tangent, y = z × x, z normal)
//!   the Darboux frame turns at ω = (tg, −kn, kg) per unit curve length
//!   (x' = kg·y + kn·z, y' = −kg·x + tg·z, z' = −kn·x − tg·y, so
//!   e' = ω × e; held to a finite difference of the frame in the tests);
//!   on a lamella's offset line, per unit of its own length, ω divided by
//!   the stretch ds'/ds, as the elastic check does. At the element's middle
//!   [`InitialForces`] = (0, G·J·ω_x, E·I_y·ω_y, E·I_z·ω_z) (section moment
//!   = stiffness × rotation rate about that axis). σb = |M_z|/(h·t²/6) and
//!   τ = |T|·t/J are then the check's E·|kg|·t/2 and G·|tg|·t exactly.
//! * [`BeamRole`]: strip (file order), lamella (1 or 2), the middle's
//!   station on the lamella's line, the node-to-node span it lies in, and
//!   σ_w = E·tg²·h²/12 there (tg on the lamella's line).
//!
//! **Edge strips.** A band on the edge curve (tangential to the surface,
//! dz = 0) from its first node to its last, `elements_per_span` elements
//! between nodes. Its section lies flat: width h in the surface, thickness
//! t along the normal, so I_y = h·t³/12 (weak, about local y), I_z =
//! t·h³/12 (strong, in the surface), the same A and J. It is cut curved to
//! its geodesic curvature, so its erection state is the torque G·J·tg and
//! the moment E·I_y·(−kn) only. Its elements have no role (`None`: the
//! verdict checks upright lamellas) but are listed in
//! [`LoadTargets::strip_beams`] under the edge's id.
//!
//! **Joints.** Every topology node (A×B, A×edge, B×edge) is a joint node
//! at the node's position (mid-point of the closest approach). Every
//! lamella (or band) through it has its own chain node there; a chain node
//! on the curve itself (dy = dz = 0) is put exactly at the joint's
//! position (it is off by at most half the node gap, below the network's
//! tolerance); a lamella on an offset line (doubled lamellas at
//! dy = ∓(g + t)/2, two-level lamellas at dz = ±level offset) stays on its
//! line. Where the joint ties a chain node fully it is a **rigid tie**:
//! the bolt's and the washers' clamp, or the stud, is rigid across the
//! offset (see below).
//!
//! * Interlocking with star washers, and two-level studs (square in both
//!   gaps): every translation and rotation tied (the washers' arms, or the
//!   stud's square, lock the crossing angle).
//! * Interlocking without washers: the halving slots are swept over the
//!   profile's rotation tolerance, so the B strip turns freely about the
//!   normal (when that tolerance is 0 the slots are tight and lock it).
//!   The release sits on the B side only: a connector node at the joint
//!   takes B's lamellas rigidly, and a link with no stiffness about the
//!   normal joins it to the joint node (releasing both sides would leave
//!   the joint node free to spin); a centred B lamella needs no connector:
//!   its own chain node is that link's end.
//! * Edge joints (bolt or slot): the band sits in the lamellas' end slots:
//!   translations and the rotations about the surface's tangents tied, the
//!   rotation about the normal free (a single bolt along the normal, or the
//!   slot alone, is a pin about it); the release is on the band's side.
//!
//! **Rigid ties are eliminated, not modelled stiff.** Nodes tied rigidly
//! (a chain node to its joint or connector, the two lamellas' nodes at a
//! shear block) form a group that moves with one node of it, its anchor:
//! the joint, the connector, a release link's end, else the group's first
//! node (a block's node on lamella 1). The other nodes are not in the
//! model: the elements that ended there reach the anchor by rigid end
//! offsets ([`Beam::offsets_mm`], u_end = u_anchor + θ_anchor × r,
//! OpenSees `-jntOffset`), and the weights lumped there act at the anchor
//! with their lever ([`LoadTargets::node_weight_lever_mm`]). This is exact
//! where a stiff element only approaches rigidity, and it keeps the
//! stiffness as well conditioned as the lamellas themselves allow: stiff
//! ties 100 times the lamellas' stiffness on 6-mm arms made the
//! Jacobi-scaled smallest eigenvalue of a 100 × 100 grid 1.6e-14, within
//! reach of round-off, so it was taken for a mechanism. A group never
//! holds two anchors (checked: an internal inconsistency otherwise).
//!
//! **Release links** ([`RIGID_FACTOR`] = 100). A joint that frees one
//! rotation is a zero-length link: along each axis 100 × E·A/L and about
//! the two tied axes 100 × E·I_y/L, L the shortest lamella or band element
//! at its nodes (E·A/L and E·I_y/L are the largest axial and bending
//! stiffness scales of a lamella element), so its compliance is under 1 %
//! of the joint's. Measured: at a factor of 1e3 the Enneper pavilion's
//! loads and reactions balanced to only 2.3e-6 (round-off in the links'
//! forces); at 100 to better than 1e-6, as the tests require.
//!
//! **Doubled strips** are Vierendeel beams: at every shear block of the
//! kit (its bolt holes' stations on each lamella's own line, paired in
//! order along the strip) both lamellas get a chain node (inserted between
//! the subdivision nodes, or the subdivision node itself when within
//! [`SNAP_MM`]), tied rigidly across the gap (lamella 2's elements there
//! reach lamella 1's node by offsets): the clamped block is taken rigid in
//! every direction (its single
//! bolt's pin about its axis is held by the block's bearing and friction;
//! both lamellas bend about that axis together anyway). Splices: the
//! lamella stays continuous (the plates restore it).
//!
//! **Load targets.**
//!
//! * Tributary areas: the grid's cells are the faces of the graph of
//!   nodes and strips: every 4-cycle n1–n2 (along a strip), n2–n4 and
//!   n1–n3 (along the strips crossing there), n3–n4 (along a fourth
//!   strip), and every 3-cycle where n3 = n4 (cells with an edge strip as a
//!   side included; cells at a corner where two edge curves meet without a
//!   node are not found). A quad's area is that of the bilinear patch on
//!   its corners (the sum of the vector areas of 4 × 4 sub-quads; exact
//!   for a hyperbolic paraboloid's cell between rulings), a triangle's
//!   ½|(p2 − p1) × (p3 − p1)|. Each corner carries an equal share (a
//!   quarter of a quad) along its node normal turned to z ≥ 0. Σ over
//!   nodes = Σ over cells.
//! * `beam_weight_n_per_mm` = ρ·A·g (g = 9.81 m/s²) for lamella and band
//!   elements (the only elements).
//! * `node_weight_n` (N): the made small parts (star washers by their
//!   node's angle class, studs at A×B joints, shear blocks half to each
//!   lamella's node at the block, splice plates at the chain node nearest
//!   their cut: a band's plate `SP-<edge>.<k>` at its own cut, the
//!   lamellas' plates shared among the lamellas' cuts) at their part's mass
//!   ([`crate::fabricate::part_mass_kg`], as the takeoff), and the bought
//!   bolts with their nuts and plain washers (masses estimated below) at
//!   the joints they close: node and stud bolts at A×B joints, shear-block
//!   bolts with the blocks, splice bolts with the lamellas' plates, band
//!   splice bolts with the bands' plates, edge bolts at
//!   the edge joints, each kind's total shared evenly among its places.
//!   Parts or bolts with no place in the model (a block beyond a strip's
//!   last node) go to the nearest chain node; a kind with no place at all
//!   is shared among the A×B joints, so Σ `node_weight_n` = g × (the kit's
//!   small parts + the bolts' estimate).
//! * Bolt masses (steel, 7850 kg/m³): the shank a cylinder of the nominal
//!   diameter and length (the thread's smaller core not deducted: at most
//!   ~20 % high on the shank), the head a hexagon of ISO 4017's width
//!   across flats s and height k, the nut a hexagon of s by ISO 4032's m
//!   less the hole, a plain washer ISO 7089's ring ([`BOLT_HEADS`]).
//! * `boundary_nodes`: the joint nodes of every strip's first and last
//!   node (A, B and edge strips).
//!
//! Node numbering: the joint nodes first, by topology node id; then the
//! chain nodes that are not tied rigidly to another, strip by strip (file
//! order), lamella by lamella, by station; then the connector nodes, by
//! topology node id. Beams: the chains' elements in that order. Links: the
//! connectors' by topology node id, then the other releases in the same
//! order. The same input gives the same model bit for bit.

use crate::analysis::lines::StripLines;
use crate::analysis::strip::StripGeometry;
use crate::analysis::Analysis;
use crate::error::{Error, Result};
use crate::fabricate::edge_strip::band_splice_id;
use crate::fabricate::fasteners;
use crate::fabricate::hardware::HardwareKind;
use crate::fabricate::part::{HoleUse, Part, PartKind};
use crate::fabricate::{part_mass_kg, washer, Kit};
use crate::geom::curve::SmoothCurve;
use crate::network::{Family, Network};
use crate::profile::{JointSystem, LamellaOffset, Profile};
use crate::structure::model::{
    Beam, BeamRole, FrameModel, InitialForces, Link, LoadTargets, Section,
};
use glam::{DMat3, DVec3};
use rayon::prelude::*;
use std::collections::{BTreeMap, BTreeSet};

/// Standard gravity, m/s² (N per kg).
pub const G_M_PER_S2: f64 = 9.81;

/// How much stiffer than a lamella element a release link is in the
/// directions it ties.
pub const RIGID_FACTOR: f64 = 100.0;

/// A shear block within this of a subdivision node (on the lamella's line)
/// takes that node instead of a new one, mm.
pub const SNAP_MM: f64 = 1.0;

/// Nodes of one strip closer than this along it are one chain node, mm.
pub const MIN_SPAN_MM: f64 = 1e-3;

/// Density of the bought bolts, nuts and washers (steel), kg/m³.
pub const BOLT_STEEL_KG_PER_M3: f64 = 7850.0;

/// ISO 4017 hexagon heads (and ISO 4032 nuts): (thread d, width across
/// flats s, head height k), mm.
pub const BOLT_HEADS: [(f64, f64, f64); 13] = [
    (1.6, 3.2, 1.1),
    (2.0, 4.0, 1.4),
    (2.5, 5.0, 1.7),
    (3.0, 5.5, 2.0),
    (4.0, 7.0, 2.8),
    (5.0, 8.0, 3.5),
    (6.0, 10.0, 4.0),
    (8.0, 13.0, 5.3),
    (10.0, 16.0, 6.4),
    (12.0, 18.0, 7.5),
    (16.0, 24.0, 10.0),
    (20.0, 30.0, 12.5),
    (24.0, 36.0, 15.0),
];

/// How the frame is meshed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FrameOptions {
    /// Beam elements between consecutive nodes of a strip (at least 1).
    pub elements_per_span: usize,
}

impl Default for FrameOptions {
    fn default() -> Self {
        FrameOptions {
            elements_per_span: 4,
        }
    }
}

/// The frame model with what the verdict and the loads need.
#[derive(Debug, Clone, PartialEq)]
pub struct BuiltFrame {
    /// The model (supports left empty).
    pub model: FrameModel,
    /// One per beam: the lamella element's role, `None` for edge bands.
    pub roles: Vec<Option<BeamRole>>,
    /// Tributary areas, names, weights and the boundary.
    pub targets: LoadTargets,
}

/// Index of the lamella section in [`FrameModel::sections`].
pub const SECTION_LAMELLA: usize = 0;
/// Index of the edge band's section.
pub const SECTION_BAND: usize = 1;

/// St. Venant constant of a thin rectangle b × c (c the shorter side):
/// b·c³·(1/3 − 0.21·(c/b)·(1 − (c/b)⁴/12)) (Roark), mm⁴.
pub fn torsion_constant_mm4(thickness_mm: f64, height_mm: f64) -> f64 {
    let (b, c) = if height_mm >= thickness_mm {
        (height_mm, thickness_mm)
    } else {
        (thickness_mm, height_mm)
    };
    let r = c / b;
    b * c.powi(3) * (1.0 / 3.0 - 0.21 * r * (1.0 - r.powi(4) / 12.0))
}

/// The two sections: the upright lamella, the flat band.
pub fn sections(profile: &Profile) -> [Section; 2] {
    let (t, h) = (profile.thickness_mm(), profile.height_mm());
    let (e, g) = (profile.youngs_modulus_mpa(), profile.shear_modulus_mpa());
    let area = t * h;
    let strong = t * h.powi(3) / 12.0;
    let weak = h * t.powi(3) / 12.0;
    let j = torsion_constant_mm4(t, h);
    let lamella = Section {
        e_mpa: e,
        g_mpa: g,
        area_mm2: area,
        i_y_mm4: strong,
        i_z_mm4: weak,
        j_mm4: j,
    };
    let band = Section {
        i_y_mm4: weak,
        i_z_mm4: strong,
        ..lamella.clone()
    };
    [lamella, band]
}

/// The rotation rate of the Darboux frame in its own axes (x, y, z) per
/// unit curve length: (tg, −kn, kg).
pub fn darboux_rate(kg_per_mm: f64, kn_per_mm: f64, tg_per_mm: f64) -> DVec3 {
    DVec3::new(tg_per_mm, -kn_per_mm, kg_per_mm)
}

/// Stretch ds'/ds of the line offset (dy, dz) (as the elastic check).
fn stretch(dy: f64, dz: f64, kg: f64, kn: f64, tg: f64) -> f64 {
    let a = 1.0 - dy * kg - dz * kn;
    (a * a + (dz * tg).powi(2) + (dy * tg).powi(2)).sqrt()
}

/// One chain: a lamella of an A/B strip, or an edge band.
#[derive(Debug, Clone)]
struct Chain {
    /// Strip index (`Analysis::strips`).
    strip: usize,
    /// Lamella number (1 or 2); 0 for a band.
    number: u32,
    /// Offset of the line from the curve.
    offset: LamellaOffset,
    /// Per chain node: its station on the line, mm.
    stations: Vec<f64>,
    /// Per chain node: its model node.
    nodes: Vec<usize>,
    /// Per topology node of the strip: the chain position there.
    at_node: BTreeMap<usize, usize>,
    /// Per shear block (in order along the lamella): its chain position,
    /// or None when outside the chain (then the nearest chain position
    /// carries its weight).
    blocks: Vec<(usize, bool)>,
    /// The model beams of its elements, in order.
    beams: Vec<usize>,
}

/// Strips whose chains' geometry is made side by side on the threads
/// before their nodes and beams are numbered ([`build_frame`]).
const STRIPS_AT_ONCE: usize = 64;

/// What a strip's chains are made from.
struct ChainGeometryOf<'a> {
    an: &'a Analysis,
    profile: &'a Profile,
    sections: &'a [Section; 2],
    /// (E, G), MPa.
    moduli_mpa: (f64, f64),
    /// The lamella's height, mm.
    height_mm: f64,
    elements_per_span: usize,
    /// Shear-block stations by (strip id, lamella), ascending.
    kit_blocks: &'a BTreeMap<(String, u32), Vec<f64>>,
}

/// A chain's geometry before its nodes and beams are numbered: a
/// [`Chain`] with its nodes' points and its elements' beams to be.
struct ChainGeometry {
    strip: usize,
    number: u32,
    offset: LamellaOffset,
    stations: Vec<f64>,
    at_node: BTreeMap<usize, usize>,
    blocks: Vec<(usize, bool)>,
    /// Per chain node: its point, mm.
    points: Vec<DVec3>,
    /// Per element: its beam, `None` where it is shorter than
    /// [`MIN_SPAN_MM`] (two chain nodes at one station: no beam).
    elements: Vec<Option<ChainElement>>,
}

/// A chain element's beam, all but its nodes.
struct ChainElement {
    section: usize,
    z_axis: DVec3,
    initial: InitialForces,
    role: Option<BeamRole>,
}

impl ChainGeometryOf<'_> {
    /// The chains of `strip` (one per lamella, one for an edge band; none
    /// for a strip without nodes).
    fn of(&self, strip: &StripGeometry) -> Vec<ChainGeometry> {
        if strip.nodes.is_empty() {
            return Vec::new();
        }
        let (an, profile, secs) = (self.an, self.profile, self.sections);
        let (e_mod, g_mod) = self.moduli_mpa;
        let (h, e_per) = (self.height_mm, self.elements_per_span);
        let topo = &an.topology;
        let smooth = &an.curves[strip.curve];
        let is_edge = strip.family == Family::Edge;
        let offsets = if is_edge {
            vec![LamellaOffset {
                number: 0,
                ..LamellaOffset::CENTRE
            }]
        } else {
            profile.lamella_offsets(strip.family)
        };
        let lines = StripLines::new(strip, smooth, &offsets);
        let mut chains = Vec::with_capacity(offsets.len());
        for (li, off) in offsets.iter().enumerate() {
            let node_st: Vec<f64> = lines.lines[li].nodes.iter().map(|n| n.station_mm).collect();
            let blocks = if is_edge {
                Vec::new()
            } else {
                self.kit_blocks
                    .get(&(strip.id.clone(), off.number))
                    .cloned()
                    .unwrap_or_default()
            };
            // Chain stations: the nodes, the subdivisions, the blocks.
            let mut st: Vec<(f64, usize)> = Vec::new(); // (station, span index)
            let mut node_pos: Vec<usize> = Vec::with_capacity(node_st.len());
            let mut spans: Vec<(f64, f64)> = Vec::new();
            st.push((node_st[0], 0));
            node_pos.push(0);
            for k in 0..node_st.len() - 1 {
                let (a, c) = (node_st[k], node_st[k + 1]);
                if c - a < MIN_SPAN_MM {
                    node_pos.push(st.len() - 1);
                    continue;
                }
                let mut inner: Vec<f64> = (1..e_per)
                    .map(|i| a + (c - a) * i as f64 / e_per as f64)
                    .collect();
                // The blocks strictly inside the span (sorted: a range).
                let inside =
                    blocks.partition_point(|&s| s <= a)..blocks.partition_point(|&s| s < c);
                for &s in blocks.get(inside).unwrap_or_default() {
                    let near = inner
                        .iter()
                        .chain([a, c].iter())
                        .any(|&x| (x - s).abs() <= SNAP_MM);
                    if !near {
                        inner.push(s);
                    }
                }
                inner.sort_by(f64::total_cmp);
                for s in inner {
                    st.push((s, spans.len()));
                }
                st.push((c, spans.len()));
                node_pos.push(st.len() - 1);
                spans.push((a, c));
            }
            let stations: Vec<f64> = st.iter().map(|x| x.0).collect();
            // Element middles, then curve stations of everything at once.
            let mids: Vec<f64> = stations.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
            let mut ask = stations.clone();
            ask.extend(&mids);
            let curve = curve_stations_of(strip, smooth, &lines, li, &ask);
            let centre = off.dy_mm == 0.0 && off.dz_mm == 0.0;
            let mut at_node = BTreeMap::new();
            for (cn, &pos) in strip.nodes.iter().zip(&node_pos) {
                at_node.entry(cn.node).or_insert(pos);
            }
            let snapped: BTreeMap<usize, usize> = at_node.iter().map(|(&n, &p)| (p, n)).collect();
            let points: Vec<DVec3> = (0..stations.len())
                .map(|i| match snapped.get(&i) {
                    Some(&n) if centre => topo.nodes[n].position_world_mm,
                    _ => {
                        let f = strip.frame_at(smooth, curve[i]);
                        f.point_world_mm + off.dy_mm * f.y + off.dz_mm * f.z
                    }
                })
                .collect();
            let block_pos: Vec<(usize, bool)> = blocks
                .iter()
                .map(|&s| {
                    let i = nearest_station(&stations, s);
                    let inside = s > stations[0] && s < stations[stations.len() - 1];
                    (i, inside)
                })
                .collect();
            // Per element: the node-to-node span it lies in (line
            // stations of its first node and its last).
            let spans: Vec<(f64, f64)> = st[1..]
                .iter()
                .map(|x| spans.get(x.1).copied().unwrap_or_default())
                .collect();
            // Elements.
            let elements = (0..stations.len() - 1)
                .map(|i| {
                    if stations[i + 1] - stations[i] < MIN_SPAN_MM {
                        return None;
                    }
                    let f = strip.frame_at(smooth, curve[stations.len() + i]);
                    let k = stretch(off.dy_mm, off.dz_mm, f.kg_per_mm, f.kn_per_mm, f.tg_per_mm);
                    let w = darboux_rate(f.kg_per_mm, f.kn_per_mm, f.tg_per_mm) / k;
                    let (section, initial, role) = if is_edge {
                        let s = &secs[SECTION_BAND];
                        (
                            SECTION_BAND,
                            InitialForces {
                                axial_n: 0.0,
                                torque_nmm: g_mod * s.j_mm4 * w.x,
                                moment_y_nmm: e_mod * s.i_y_mm4 * w.y,
                                moment_z_nmm: 0.0,
                            },
                            None,
                        )
                    } else {
                        let s = &secs[SECTION_LAMELLA];
                        let (a, c) = spans[i];
                        (
                            SECTION_LAMELLA,
                            InitialForces {
                                axial_n: 0.0,
                                torque_nmm: g_mod * s.j_mm4 * w.x,
                                moment_y_nmm: e_mod * s.i_y_mm4 * w.y,
                                moment_z_nmm: e_mod * s.i_z_mm4 * w.z,
                            },
                            Some(BeamRole {
                                strip: strip.curve,
                                lamella: off.number,
                                station_mm: 0.5 * (stations[i] + stations[i + 1]),
                                member_span_mm: c - a,
                                trapeze_mpa: e_mod * w.x * w.x * h * h / 12.0,
                            }),
                        )
                    };
                    Some(ChainElement {
                        section,
                        z_axis: f.z,
                        initial,
                        role,
                    })
                })
                .collect();
            chains.push(ChainGeometry {
                strip: strip.curve,
                number: off.number,
                offset: *off,
                stations,
                at_node,
                blocks: block_pos,
                points,
                elements,
            });
        }
        chains
    }
}

/// Where the model grows.
struct Builder {
    model: FrameModel,
    roles: Vec<Option<BeamRole>>,
    /// Per model node: the shortest chain element at it, mm.
    shortest_mm: Vec<f64>,
}

impl Builder {
    fn node(&mut self, p: DVec3) -> usize {
        self.model.nodes_mm.push(p);
        self.shortest_mm.push(f64::INFINITY);
        self.model.nodes_mm.len() - 1
    }

    fn beam(
        &mut self,
        nodes: [usize; 2],
        section: usize,
        z_axis: DVec3,
        initial: InitialForces,
        role: Option<BeamRole>,
    ) -> usize {
        self.model.beams.push(Beam {
            nodes,
            section,
            z_axis,
            initial,
            offsets_mm: [DVec3::ZERO; 2],
        });
        self.roles.push(role);
        self.model.beams.len() - 1
    }

    /// The chain of `geometry`: its nodes and beams numbered next.
    fn chain(&mut self, geometry: ChainGeometry) -> Chain {
        let nodes: Vec<usize> = geometry.points.iter().map(|&p| self.node(p)).collect();
        let mut beams = Vec::new();
        for (i, element) in geometry.elements.into_iter().enumerate() {
            let Some(e) = element else { continue };
            let (na, nb) = (nodes[i], nodes[i + 1]);
            beams.push(self.beam([na, nb], e.section, e.z_axis, e.initial, e.role));
            let len = self.model.nodes_mm[na].distance(self.model.nodes_mm[nb]);
            self.shortest_mm[na] = self.shortest_mm[na].min(len);
            self.shortest_mm[nb] = self.shortest_mm[nb].min(len);
        }
        Chain {
            strip: geometry.strip,
            number: geometry.number,
            offset: geometry.offset,
            stations: geometry.stations,
            nodes,
            at_node: geometry.at_node,
            blocks: geometry.blocks,
            beams,
        }
    }

    /// A zero-length link, `free_about_normal` releasing the rotation about
    /// the frame's third column.
    fn link(&mut self, a: usize, b: usize, frame: DMat3, free_about_normal: bool, lam: &Section) {
        let l = self.shortest_mm[a].min(self.shortest_mm[b]);
        let l = if l.is_finite() && l > 0.0 { l } else { 1.0 };
        let kt = RIGID_FACTOR * lam.e_mpa * lam.area_mm2 / l;
        let kr = RIGID_FACTOR * lam.e_mpa * lam.i_y_mm4 / l;
        self.model.links.push(Link {
            nodes: [a, b],
            frame,
            translation_n_per_mm: [kt; 3],
            rotation_nmm_per_rad: [kr, kr, if free_about_normal { 0.0 } else { kr }],
        });
    }
}

/// The station on the curve of each line station of `line` (index into
/// `lines.lines`), by Newton's method from a guess interpolated between
/// the nodes' (curve, line) stations.
fn curve_stations_of(
    strip: &StripGeometry,
    smooth: &SmoothCurve,
    lines: &StripLines,
    line: usize,
    targets: &[f64],
) -> Vec<f64> {
    let off = lines.lines[line].offset;
    if off.dy_mm == 0.0 && off.dz_mm == 0.0 {
        return targets.to_vec();
    }
    let pairs: Vec<(f64, f64)> = lines.lines[line]
        .nodes
        .iter()
        .zip(&strip.nodes)
        .map(|(ln, cn)| (ln.station_mm, cn.station_mm))
        .collect();
    let len = smooth.length_mm();
    let mut s: Vec<f64> = targets
        .iter()
        .map(|&t| {
            let k = pairs
                .partition_point(|p| p.0 <= t)
                .clamp(1, pairs.len().max(2) - 1);
            match (pairs.get(k - 1), pairs.get(k)) {
                (Some(a), Some(b)) if b.0 > a.0 => a.1 + (t - a.0) / (b.0 - a.0) * (b.1 - a.1),
                _ => t,
            }
            .clamp(0.0, len)
        })
        .collect();
    for _ in 0..8 {
        let at = lines.stations(strip, smooth, &s).swap_remove(line);
        let mut worst: f64 = 0.0;
        for ((si, &got), &want) in s.iter_mut().zip(&at).zip(targets) {
            let f = strip.frame_at(smooth, *si);
            let d = stretch(off.dy_mm, off.dz_mm, f.kg_per_mm, f.kn_per_mm, f.tg_per_mm);
            let step = (got - want) / d.max(1e-6);
            *si = (*si - step).clamp(0.0, len);
            worst = worst.max(step.abs());
        }
        if worst < 1e-9 {
            break;
        }
    }
    s
}

/// The index of the station of `stations` (ascending) nearest to `s`,
/// the first of equally near ones (0 for none): a binary search, where
/// scanning the chain for each of its blocks grew with the square of a
/// strip's length (the 400 × 400 grid's model took 45 s, most of it
/// here).
fn nearest_station(stations: &[f64], s: f64) -> usize {
    let above = stations.partition_point(|&x| x < s);
    let distance = |i: usize| (stations[i] - s).abs();
    let i = match (above.checked_sub(1), above < stations.len()) {
        (Some(below), true) if distance(below) <= distance(above) => below,
        (Some(below), false) => below,
        (_, true) => above,
        (None, false) => return 0,
    };
    // The first of equal stations.
    stations.partition_point(|&x| x < stations[i])
}

/// Build the frame model of the erected grid (see the module doc).
/// `kit` is what [`crate::fabricate::fabricate`] made for `profile` on
/// this network (shear blocks, splices, masses).
pub fn build_frame(
    net: &Network,
    an: &Analysis,
    profile: &Profile,
    kit: &Kit,
    opts: &FrameOptions,
) -> Result<BuiltFrame> {
    if opts.elements_per_span == 0 {
        return Err(Error::network(
            &net.source,
            "the frame needs at least one element per span (elements_per_span is 0)",
        ));
    }
    let e_per = opts.elements_per_span;
    let secs = sections(profile);
    let h = profile.height_mm();
    let (e_mod, g_mod) = (profile.youngs_modulus_mpa(), profile.shear_modulus_mpa());
    let topo = &an.topology;
    let mut b = Builder {
        model: FrameModel {
            sections: secs.to_vec(),
            ..FrameModel::default()
        },
        roles: Vec::new(),
        shortest_mm: Vec::new(),
    };
    // Joint nodes, by topology node id.
    let joint: Vec<usize> = topo
        .nodes
        .iter()
        .map(|n| b.node(n.position_world_mm))
        .collect();

    // Shear block and splice stations from the kit, by (strip id, lamella).
    let mut kit_blocks: BTreeMap<(String, u32), Vec<f64>> = BTreeMap::new();
    let mut piece_starts: BTreeMap<(String, Option<u32>), Vec<f64>> = BTreeMap::new();
    for p in &kit.parts {
        let Some(strip) = &p.strip else { continue };
        if matches!(p.kind, PartKind::Lamella | PartKind::EdgeStrip) {
            if let Some(s) = p.station_start_mm {
                piece_starts
                    .entry((strip.clone(), p.lamella))
                    .or_default()
                    .push(s);
            }
        }
        if let (PartKind::Lamella, Some(l)) = (p.kind, p.lamella) {
            let list = kit_blocks.entry((strip.clone(), l)).or_default();
            list.extend(
                p.features
                    .iter()
                    .filter(|f| f.hole_use == Some(HoleUse::ShearBlock))
                    .filter_map(|f| f.station_mm),
            );
        }
    }
    for v in kit_blocks.values_mut().chain(piece_starts.values_mut()) {
        v.sort_by(f64::total_cmp);
    }

    // The chains: the strips' lamella lines, stations, points and
    // elements made [`STRIPS_AT_ONCE`] strips at a time on the threads
    // (their geometry is most of the model's time), then numbered in the
    // strips' order: the same model whatever the threads.
    let chain_geometry = ChainGeometryOf {
        an,
        profile,
        sections: &secs,
        moduli_mpa: (e_mod, g_mod),
        height_mm: h,
        elements_per_span: e_per,
        kit_blocks: &kit_blocks,
    };
    // Room for every chain's nodes and beams at once: a vector grown by
    // doubling leaves each smaller copy behind, memory the allocator keeps
    // (at 400 × 400 benchmark curves, 2.6 million beams of 128 bytes, the
    // model's peak fell by 113 MiB). Room past the count is never written,
    // so it takes no memory: the bound counts every block as a station of
    // its own.
    let chain_nodes: usize = (an.strips.iter())
        .filter(|strip| !strip.nodes.is_empty())
        .map(|strip| {
            let stations = (strip.nodes.len() - 1) * e_per + 1;
            if strip.family == Family::Edge {
                return stations;
            }
            (profile.lamella_offsets(strip.family).iter())
                .map(|off| {
                    let key = (strip.id.clone(), off.number);
                    stations + kit_blocks.get(&key).map_or(0, Vec::len)
                })
                .sum()
        })
        .sum();
    b.model.nodes_mm.reserve(chain_nodes);
    b.shortest_mm.reserve(chain_nodes);
    b.model.beams.reserve(chain_nodes);
    b.roles.reserve(chain_nodes);
    let mut chains: Vec<Chain> = Vec::new();
    for group in an.strips.chunks(STRIPS_AT_ONCE) {
        let made: Vec<Vec<ChainGeometry>> = group
            .par_iter()
            .map(|strip| chain_geometry.of(strip))
            .collect();
        for geometry in made.into_iter().flatten() {
            chains.push(b.chain(geometry));
        }
    }

    // Joints.
    let release_b = profile.joint.system == JointSystem::Interlocking
        && profile.washer.is_none()
        && profile.joint.rotation_tolerance_deg > 0.0;
    let chains_of: BTreeMap<usize, Vec<usize>> = {
        let mut m: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
        for (ci, c) in chains.iter().enumerate() {
            m.entry(c.strip).or_default().push(ci);
        }
        m
    };
    // Ties: (chain node, target, frame, release); a target
    // is a joint node (by topology id) or a connector (by its index).
    #[derive(Clone, Copy)]
    enum Target {
        Joint(usize),
        Connector(usize),
    }
    let mut connectors: Vec<(usize, DMat3)> = Vec::new(); // (topology id, frame)
    let mut ties: Vec<(usize, Target, DMat3, bool)> = Vec::new();
    for n in &topo.nodes {
        let normal = n.normal_world;
        let xa = (n.tangent_a_world - normal * n.tangent_a_world.dot(normal))
            .try_normalize()
            .unwrap_or_else(|| normal.any_orthonormal_vector());
        let frame = DMat3::from_cols(xa, normal.cross(xa), normal);
        for (side, strip) in [(0, n.a), (1, n.b)] {
            let Some(cis) = chains_of.get(&strip) else {
                continue;
            };
            let fam = an.strips[strip].family;
            let release = side == 1
                && (fam == Family::Edge || (release_b && net.curves[n.a].family != Family::Edge));
            let offset_lamellas = cis.iter().any(|&ci| {
                let o = chains[ci].offset;
                o.dy_mm != 0.0 || o.dz_mm != 0.0
            });
            let target = if release && offset_lamellas {
                connectors.push((n.id, frame));
                Target::Connector(connectors.len() - 1)
            } else {
                Target::Joint(n.id)
            };
            for &ci in cis {
                let c = &chains[ci];
                if let Some(&pos) = c.at_node.get(&n.id) {
                    let free = release && !offset_lamellas;
                    ties.push((c.nodes[pos], target, frame, free));
                }
            }
        }
    }
    let connector_nodes: Vec<usize> = connectors
        .iter()
        .map(|&(id, _)| b.node(topo.nodes[id].position_world_mm))
        .collect();
    let target_node = |t: Target| match t {
        Target::Joint(j) => joint[j],
        Target::Connector(k) => connector_nodes[k],
    };
    // A connector's stiffness scale: the shortest element it ties.
    for &(chain_node, target, ..) in &ties {
        let tn = target_node(target);
        b.shortest_mm[tn] = b.shortest_mm[tn].min(b.shortest_mm[chain_node]);
    }
    for (k, &(id, frame)) in connectors.iter().enumerate() {
        b.link(
            connector_nodes[k],
            joint[id],
            frame,
            true,
            &secs[SECTION_LAMELLA],
        );
    }
    // Rigid ties (a node, the node it moves with), eliminated below.
    let mut rigid: Vec<(usize, usize)> = Vec::new();
    for &(chain_node, target, frame, free) in &ties {
        let tn = target_node(target);
        if free {
            // A centred chain node at its joint's point.
            b.link(chain_node, tn, frame, true, &secs[SECTION_LAMELLA]);
        } else {
            rigid.push((chain_node, tn));
        }
    }

    // Shear blocks: the two lamellas' nodes paired in order.
    let mut block_places: Vec<(usize, usize)> = Vec::new(); // model nodes of each block
    for cis in chains_of.values() {
        if cis.len() != 2 {
            continue;
        }
        let (c1, c2) = (&chains[cis[0]], &chains[cis[1]]);
        let strip = &an.strips[c1.strip];
        if c1.blocks.len() != c2.blocks.len() {
            return Err(Error::fabrication(
                &profile.source,
                &strip.id,
                None,
                format!(
                    "lamella 1 has {} shear-block holes and lamella 2 has {}: they cannot be paired",
                    c1.blocks.len(),
                    c2.blocks.len()
                ),
            ));
        }
        for (&(p1, in1), &(p2, in2)) in c1.blocks.iter().zip(&c2.blocks) {
            let (n1, n2) = (c1.nodes[p1], c2.nodes[p2]);
            block_places.push((n1, n2));
            if in1 && in2 && n1 != n2 {
                rigid.push((n2, n1));
            }
        }
    }

    // Load targets (on the nodes before the rigid ties are eliminated).
    let n_nodes = b.model.nodes_mm.len();
    let mut tributary_mm2 = vec![DVec3::ZERO; n_nodes];
    for (id, a) in tributary_areas(an).into_iter().enumerate() {
        tributary_mm2[joint[id]] = a;
    }
    let mut strip_beams: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for c in &chains {
        strip_beams
            .entry(an.strips[c.strip].id.clone())
            .or_default()
            .extend(&c.beams);
    }
    let density = profile.material.density_kg_per_m3;
    let beam_weight_n_per_mm: Vec<f64> = b
        .model
        .beams
        .iter()
        .map(|bm| density * 1e-9 * b.model.sections[bm.section].area_mm2 * G_M_PER_S2)
        .collect();
    let grid_joints: Vec<usize> = washer::grid_nodes(an).iter().map(|g| joint[g.id]).collect();
    let weights = node_weights(
        net,
        an,
        profile,
        kit,
        &chains,
        &joint,
        &grid_joints,
        &block_places,
        &piece_starts,
        n_nodes,
    );

    // The rigid ties eliminated: every node keeps its anchor's unknowns.
    let mut anchors: Vec<usize> = joint.clone();
    anchors.extend(&connector_nodes);
    anchors.extend(b.model.links.iter().flat_map(|l| l.nodes));
    let rigid = RigidGroups::new(&b.model.nodes_mm, &rigid, &anchors).map_err(|node| {
        let id = joint.iter().position(|&j| j == node);
        Error::fabrication_joint(
            &profile.source,
            &id.map_or_else(|| format!("model node {node}"), |i| format!("node {i}")),
            "two joints or releases are tied rigidly together (an internal inconsistency of the frame model)",
        )
    })?;
    let model = rigid.condense(b.model);
    let mut node_weight_n = vec![0.0; rigid.nodes()];
    let mut lever = vec![DVec3::ZERO; rigid.nodes()];
    for (old, &w) in weights.iter().enumerate() {
        let new = rigid.node_of[old];
        node_weight_n[new] += w;
        lever[new] += w * rigid.lever_mm[old];
    }
    let node_weight_lever_mm: Vec<DVec3> = lever
        .iter()
        .zip(&node_weight_n)
        .map(|(l, &w)| if w != 0.0 { *l / w } else { DVec3::ZERO })
        .collect();
    let mut tributary = vec![DVec3::ZERO; rigid.nodes()];
    for (old, a) in tributary_mm2.iter().enumerate() {
        // Only joints carry areas, and joints are anchors (lever 0).
        tributary[rigid.node_of[old]] += *a;
    }
    let node_ids: BTreeMap<String, usize> = topo
        .nodes
        .iter()
        .map(|n| (n.id.to_string(), rigid.node_of[joint[n.id]]))
        .collect();
    let mut boundary: BTreeSet<usize> = BTreeSet::new();
    for s in &an.strips {
        if let (Some(f), Some(l)) = (s.nodes.first(), s.nodes.last()) {
            boundary.insert(rigid.node_of[joint[f.node]]);
            boundary.insert(rigid.node_of[joint[l.node]]);
        }
    }
    Ok(BuiltFrame {
        model,
        roles: b.roles,
        targets: LoadTargets {
            tributary_mm2: tributary,
            node_ids,
            strip_beams,
            beam_weight_n_per_mm,
            node_weight_n,
            node_weight_lever_mm,
            boundary_nodes: boundary.into_iter().collect(),
        },
    })
}

/// Nodes tied rigidly together, each group moving with one node of it
/// (its anchor): the others' unknowns are eliminated (u = u_a + θ_a × r,
/// θ = θ_a, r the node's lever from its anchor) and the elements at them
/// reach the anchor by rigid end offsets. Exact where a stiff tie would
/// only approximate, and it leaves the stiffness no worse conditioned than
/// the lamellas themselves.
#[derive(Debug, Clone)]
struct RigidGroups {
    /// Per node before: its node after.
    node_of: Vec<usize>,
    /// Per node before: its position less its anchor's, mm.
    lever_mm: Vec<DVec3>,
    /// Per node after: the node before it was.
    kept: Vec<usize>,
}

impl RigidGroups {
    /// The groups of `ties` among `nodes_mm`; a group's anchor is its one
    /// node among `anchors` (joints, connectors, links' ends: nodes whose
    /// own unknowns other parts of the model use), else its first node.
    /// `Err(node)` when a group holds two anchors.
    fn new(
        nodes_mm: &[DVec3],
        ties: &[(usize, usize)],
        anchors: &[usize],
    ) -> std::result::Result<RigidGroups, usize> {
        let n = nodes_mm.len();
        let mut parent: Vec<usize> = (0..n).collect();
        fn root(p: &mut [usize], mut i: usize) -> usize {
            while p[i] != i {
                p[i] = p[p[i]];
                i = p[i];
            }
            i
        }
        for &(a, c) in ties {
            let (ra, rc) = (root(&mut parent, a), root(&mut parent, c));
            if ra != rc {
                parent[ra.max(rc)] = ra.min(rc);
            }
        }
        let mut is_anchor = vec![false; n];
        for &a in anchors {
            is_anchor[a] = true;
        }
        // Per group root: its anchor (the first node when none).
        let mut anchor_of: Vec<Option<usize>> = vec![None; n];
        for i in 0..n {
            let r = root(&mut parent, i);
            if is_anchor[i] {
                if let Some(other) = anchor_of[r].filter(|&o| is_anchor[o]) {
                    return Err(other);
                }
                anchor_of[r] = Some(i);
            } else if anchor_of[r].is_none() {
                anchor_of[r] = Some(i);
            }
        }
        let mut node_of = vec![usize::MAX; n];
        let mut kept = Vec::new();
        for (i, new) in node_of.iter_mut().enumerate() {
            let r = root(&mut parent, i);
            if anchor_of[r] == Some(i) {
                *new = kept.len();
                kept.push(i);
            }
        }
        let mut lever_mm = vec![DVec3::ZERO; n];
        for i in 0..n {
            let a = anchor_of[root(&mut parent, i)].unwrap_or(i);
            node_of[i] = node_of[a];
            lever_mm[i] = nodes_mm[i] - nodes_mm[a];
        }
        Ok(RigidGroups {
            node_of,
            lever_mm,
            kept,
        })
    }

    /// Nodes after.
    fn nodes(&self) -> usize {
        self.kept.len()
    }

    /// `model` on the anchors: beams at eliminated nodes reach their anchor
    /// by end offsets; links join anchors only.
    fn condense(&self, mut model: FrameModel) -> FrameModel {
        for beam in &mut model.beams {
            for end in 0..2 {
                let old = beam.nodes[end];
                beam.offsets_mm[end] += self.lever_mm[old];
                beam.nodes[end] = self.node_of[old];
            }
        }
        for link in &mut model.links {
            link.nodes = link.nodes.map(|old| self.node_of[old]);
        }
        model.nodes_mm = self.kept.iter().map(|&i| model.nodes_mm[i]).collect();
        model
    }
}

/// Mass of one bolt d × l with its nut and `plain` plain washers, kg
/// (see the module doc; None for a thread outside the tables).
pub fn bolt_set_mass_kg(d_mm: f64, length_mm: f64, plain: u32) -> Option<f64> {
    let th = fasteners::thread(d_mm)?;
    let &(_, s, k) = BOLT_HEADS.iter().find(|x| (x.0 - d_mm).abs() < 1e-9)?;
    let hexagon = 3f64.sqrt() / 2.0 * s * s;
    let hole = std::f64::consts::FRAC_PI_4 * d_mm * d_mm;
    let bolt = hole * length_mm + hexagon * k;
    let nut = (hexagon - hole) * th.nut_mm;
    let ring = std::f64::consts::FRAC_PI_4
        * (th.washer_outside_mm.powi(2) - th.washer_hole_mm.powi(2))
        * th.washer_mm;
    Some((bolt + nut + f64::from(plain) * ring) * BOLT_STEEL_KG_PER_M3 * 1e-9)
}

/// The bought bolts' estimated mass by joint kind (`node bolt`, …; edge
/// bolts of every length under `edge bolt`), kg, each with its nut and
/// plain washers.
pub fn bolt_masses_kg(kit: &Kit, profile: &Profile) -> BTreeMap<String, f64> {
    let mut out = BTreeMap::new();
    for hw in &kit.summary.hardware {
        if hw.kind != HardwareKind::Bolt {
            continue;
        }
        let plain = if hw.item == "node bolt" && profile.washer.is_some() {
            0
        } else {
            2
        };
        let l = hw.length_mm.or(hw.needed_mm).unwrap_or(0.0);
        let unit = bolt_set_mass_kg(hw.diameter_mm, l, plain).unwrap_or(0.0);
        let key = if hw.item.starts_with("edge bolt") {
            "edge bolt".to_string()
        } else {
            hw.item.clone()
        };
        *out.entry(key).or_insert(0.0) += unit * hw.count as f64;
    }
    out
}

/// The weights lumped at nodes (see the module doc), N.
#[allow(clippy::too_many_arguments)]
fn node_weights(
    net: &Network,
    an: &Analysis,
    profile: &Profile,
    kit: &Kit,
    chains: &[Chain],
    joint: &[usize],
    grid_joints: &[usize],
    block_places: &[(usize, usize)],
    piece_starts: &BTreeMap<(String, Option<u32>), Vec<f64>>,
    n_nodes: usize,
) -> Vec<f64> {
    let mut w = vec![0.0; n_nodes];
    let g = G_M_PER_S2;
    // Spread a mass (kg) evenly over places; none: over the grid joints.
    let spread = |w: &mut Vec<f64>, kg: f64, places: &[usize]| {
        let places = if places.is_empty() {
            grid_joints
        } else {
            places
        };
        if places.is_empty() {
            return;
        }
        let each = kg * g / places.len() as f64;
        for &p in places {
            w[p] += each;
        }
    };
    let mass_of = |kind: PartKind| -> f64 {
        kit.parts
            .iter()
            .filter(|p| p.kind == kind)
            .map(|p| part_mass_kg(p, profile) * f64::from(p.count))
            .sum()
    };
    // Star washers by the node's angle class.
    if profile.washer.is_some() {
        let per_node = profile.washer.as_ref().map_or(0, |x| x.per_node);
        let mut placed = 0.0;
        let washers: BTreeMap<&str, &Part> = kit
            .parts
            .iter()
            .filter(|p| p.kind == PartKind::Washer)
            .rev()
            .map(|p| (p.id.as_str(), p))
            .collect();
        for gn in washer::grid_nodes(an) {
            let id = washer::washer_id(washer::angle_class_deg(gn.angle_deg));
            if let Some(p) = washers.get(id.as_str()) {
                let kg = part_mass_kg(p, profile) * f64::from(per_node);
                w[joint[gn.id]] += kg * g;
                placed += kg;
            }
        }
        let rest = mass_of(PartKind::Washer) - placed;
        if rest.abs() > 1e-12 {
            spread(&mut w, rest, grid_joints);
        }
    }
    // Studs at the A×B joints.
    spread(&mut w, mass_of(PartKind::Stud), grid_joints);
    // Shear blocks, half to each lamella's node.
    let halves: Vec<usize> = block_places.iter().flat_map(|&(a, b)| [a, b]).collect();
    spread(&mut w, mass_of(PartKind::ShearBlock), &halves);
    // Splice plates at their cuts: each band plate (`SP-<edge>.<k>`) at
    // its own cut, the lamella plates shared among the lamellas' cuts.
    let mut plate_places: Vec<usize> = Vec::new();
    let mut band_places: Vec<usize> = Vec::new();
    let mut band_plates_kg = 0.0;
    for c in chains {
        let strip = &an.strips[c.strip];
        let is_edge = strip.family == Family::Edge;
        let key = (strip.id.clone(), (!is_edge).then_some(c.number));
        let Some(starts) = piece_starts.get(&key) else {
            continue;
        };
        for (k, &cut) in starts.iter().skip(1).enumerate() {
            let i = nearest_station(&c.stations, cut);
            if is_edge {
                band_places.push(c.nodes[i]);
                let id = band_splice_id(&strip.id, k + 1);
                if let Some(q) = kit
                    .parts
                    .iter()
                    .find(|q| q.kind == PartKind::SplicePlate && q.id == id)
                {
                    let kg = part_mass_kg(q, profile) * f64::from(q.count);
                    w[c.nodes[i]] += kg * g;
                    band_plates_kg += kg;
                }
            } else {
                plate_places.push(c.nodes[i]);
            }
        }
    }
    spread(
        &mut w,
        mass_of(PartKind::SplicePlate) - band_plates_kg,
        &plate_places,
    );
    // Bolts.
    let edge_joints: Vec<usize> = an
        .topology
        .nodes
        .iter()
        .filter(|n| {
            net.curves[n.a].family == Family::Edge || net.curves[n.b].family == Family::Edge
        })
        .map(|n| joint[n.id])
        .collect();
    for (item, kg) in bolt_masses_kg(kit, profile) {
        let places: &[usize] = match item.as_str() {
            "node bolt" | "stud bolt" => grid_joints,
            "shear-block bolt" => &halves,
            "splice bolt" => &plate_places,
            "band splice bolt" => &band_places,
            "edge bolt" => &edge_joints,
            _ => grid_joints,
        };
        spread(&mut w, kg, places);
    }
    w
}

/// Tributary area vector (area × unit normal, z ≥ 0), mm², of every
/// topology node (by id): an equal share of every grid cell it is a
/// corner of (see the module doc).
pub fn tributary_areas(an: &Analysis) -> Vec<DVec3> {
    let topo = &an.topology;
    let mut out = vec![DVec3::ZERO; topo.nodes.len()];
    for (corners, area) in grid_cells(an) {
        let share = area / corners.len() as f64;
        for id in corners {
            let n = topo.nodes[id].normal_world;
            let n = if n.z < 0.0 { -n } else { n };
            out[id] += share * n;
        }
    }
    out
}

/// The grid's cells: corner node ids (in order round the cell) and area,
/// mm² (see the module doc), sorted by their corner sets.
pub fn grid_cells(an: &Analysis) -> Vec<(Vec<usize>, f64)> {
    let topo = &an.topology;
    let per = &topo.per_curve;
    // Position of each node on each of its curves.
    let pos = |curve: usize, node: usize| per[curve].iter().position(|cn| cn.node == node);
    let nbrs = |curve: usize, node: usize| -> Vec<usize> {
        let Some(i) = pos(curve, node) else {
            return Vec::new();
        };
        let mut v = Vec::new();
        if i > 0 {
            v.push(per[curve][i - 1].node);
        }
        if i + 1 < per[curve].len() {
            v.push(per[curve][i + 1].node);
        }
        v
    };
    let curves_of = |node: usize| [topo.nodes[node].a, topo.nodes[node].b];
    let adjacent = |curve: usize, p: usize, q: usize| match (pos(curve, p), pos(curve, q)) {
        (Some(i), Some(j)) => i.abs_diff(j) == 1,
        _ => false,
    };
    let mut cells: BTreeMap<Vec<usize>, Vec<usize>> = BTreeMap::new();
    for (a, list) in per.iter().enumerate() {
        for w in list.windows(2) {
            let (n1, n2) = (w[0].node, w[1].node);
            let (c1, c2) = (w[0].crossing, w[1].crossing);
            if c1 == c2 || n1 == n2 {
                continue;
            }
            for n3 in nbrs(c1, n1) {
                for n4 in nbrs(c2, n2) {
                    let poly = if n3 == n4 {
                        if n3 == n1 || n3 == n2 {
                            continue;
                        }
                        vec![n1, n2, n3]
                    } else {
                        let common = curves_of(n3)
                            .into_iter()
                            .find(|c| curves_of(n4).contains(c) && *c != a && *c != c1 && *c != c2);
                        match common {
                            Some(a2) if adjacent(a2, n3, n4) => vec![n1, n2, n4, n3],
                            _ => continue,
                        }
                    };
                    let mut key = poly.clone();
                    key.sort_unstable();
                    key.dedup();
                    if key.len() == poly.len() {
                        cells.entry(key).or_insert(poly);
                    }
                }
            }
        }
    }
    cells
        .into_values()
        .map(|poly| {
            let p: Vec<DVec3> = poly
                .iter()
                .map(|&i| topo.nodes[i].position_world_mm)
                .collect();
            let area = if p.len() == 3 {
                0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length()
            } else {
                bilinear_area_mm2(p[0], p[1], p[2], p[3], 4)
            };
            (poly, area)
        })
        .collect()
}

/// Area of the bilinear patch on the corners p00, p10, p11, p01 (in order
/// round it): Σ of the vector areas of m × m sub-quads.
pub fn bilinear_area_mm2(p00: DVec3, p10: DVec3, p11: DVec3, p01: DVec3, m: usize) -> f64 {
    let at = |u: f64, v: f64| {
        p00 * (1.0 - u) * (1.0 - v) + p10 * u * (1.0 - v) + p11 * u * v + p01 * (1.0 - u) * v
    };
    let mut sum = 0.0;
    let m_f = m as f64;
    for i in 0..m {
        for j in 0..m {
            let (u0, u1) = (i as f64 / m_f, (i + 1) as f64 / m_f);
            let (v0, v1) = (j as f64 / m_f, (j + 1) as f64 / m_f);
            let d1 = at(u1, v1) - at(u0, v0);
            let d2 = at(u0, v1) - at(u1, v0);
            sum += 0.5 * d1.cross(d2).length();
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::lines::{LamellaLine, NetworkLines};
    use crate::analysis::{analyze, AnalysisOptions};
    use crate::check::Stresses;
    use crate::fabricate::fabricate;
    use crate::formats::read::{profile_file, read_network, ReadOptions};
    use crate::network::{RawCurve, RawNetwork, Unit};
    use std::path::Path;

    /// The binary search finds the station a scan of the chain finds: the
    /// nearest, the first of equally near ones (repeated stations, ties
    /// halfway, before the first and past the last).
    #[test]
    fn nearest_station_is_the_scans() {
        let scan = |stations: &[f64], s: f64| {
            stations
                .iter()
                .enumerate()
                .min_by(|x, y| (x.1 - s).abs().total_cmp(&(y.1 - s).abs()))
                .map_or(0, |x| x.0)
        };
        let stations = [0.0, 10.0, 10.0, 20.0, 25.0, 25.0, 25.0, 40.0, 100.0];
        for tenth in -50..1100 {
            let s = f64::from(tenth) / 10.0;
            assert_eq!(
                nearest_station(&stations, s),
                scan(&stations, s),
                "station {s}"
            );
        }
        assert_eq!(nearest_station(&[], 3.0), 0);
        assert_eq!(nearest_station(&[7.0], 3.0), 0);
    }

    fn root() -> &'static Path {
        Path::new(env!("CARGO_MANIFEST_DIR"))
    }

    fn load(sample: &str, profile: &str) -> (Network, Analysis, Profile, Kit) {
        let net = read_network(
            &root().join(format!("samples/{sample}.yaml")),
            ReadOptions::default(),
        )
        .expect("sample");
        let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analysis");
        let p =
            profile_file::load(&root().join(format!("profiles/{profile}.yaml"))).expect("profile");
        let kit = fabricate(&net, &an, &p, None, NetworkLines::default()).expect("kit");
        (net, an, p, kit)
    }

    fn build(sample: &str, profile: &str) -> (Network, Analysis, Profile, Kit, BuiltFrame) {
        let (net, an, p, kit) = load(sample, profile);
        let f = build_frame(&net, &an, &p, &kit, &FrameOptions::default()).expect("frame");
        (net, an, p, kit, f)
    }

    #[test]
    fn the_rotation_rate_is_a_finite_difference_of_the_frame() {
        // ω from e_i' = ω × e_i: ω = ½ Σ e_i × e_i', central differences
        // over ±0.05 mm, against (tg, −kn, kg) in the frame's own axes.
        let (_, an, _, _) = load("enneper-4m", "steel-1.5");
        let mut worst: f64 = 0.0;
        let mut scale: f64 = 0.0;
        for s in an.strips.iter().step_by(3) {
            let smooth = &an.curves[s.curve];
            for k in 1..10 {
                let at = s.length_mm * k as f64 / 10.0;
                let d = 0.05;
                let (f0, fm, fp) = (
                    s.frame_at(smooth, at),
                    s.frame_at(smooth, at - d),
                    s.frame_at(smooth, at + d),
                );
                let der = |a: DVec3, b: DVec3| (b - a) / (2.0 * d);
                let w = 0.5
                    * (f0.x.cross(der(fm.x, fp.x))
                        + f0.y.cross(der(fm.y, fp.y))
                        + f0.z.cross(der(fm.z, fp.z)));
                let local = DVec3::new(w.dot(f0.x), w.dot(f0.y), w.dot(f0.z));
                let want = darboux_rate(f0.kg_per_mm, f0.kn_per_mm, f0.tg_per_mm);
                worst = worst.max((local - want).abs().max_element());
                scale = scale.max(want.abs().max_element());
            }
        }
        assert!(scale > 1e-4, "the sample bends and twists: {scale}");
        assert!(worst < 1e-3 * scale, "{worst} against {scale}");
    }

    #[test]
    fn the_rotation_rate_of_a_helix_on_its_cylinder_has_normal_curvature() {
        // r = 1000, p = 500 mm per radian, the cylinder's outward normals
        // from the file: kg = 0, kn = −r/(r² + p²) = −8e-4, tg = p/(r² +
        // p²) = 4e-4 per mm, so ω = (4e-4, 8e-4, 0); the frame's finite
        // difference gives the same, in particular the sign of ω_y = −kn.
        let (r, pitch) = (1000.0f64, 500.0f64);
        let th: Vec<f64> = (0..=120).map(|k| f64::from(k * 3).to_radians()).collect();
        let curve = crate::network::Curve {
            id: "A0".into(),
            family: Family::A,
            normals_world: Some(
                th.iter()
                    .map(|&t| DVec3::new(t.cos(), t.sin(), 0.0))
                    .collect(),
            ),
            points_world_mm: th
                .iter()
                .map(|&t| DVec3::new(r * t.cos(), r * t.sin(), pitch * t))
                .collect(),
        };
        let smooth = SmoothCurve::new(&curve.points_world_mm);
        let strip = StripGeometry::new(
            0,
            &curve,
            &smooth,
            &[],
            &[],
            crate::analysis::strip::FrameOptions::default(),
        );
        let a2 = r * r + pitch * pitch;
        let at = 0.5 * strip.length_mm;
        let d = 0.05;
        let (f0, fm, fp) = (
            strip.frame_at(&smooth, at),
            strip.frame_at(&smooth, at - d),
            strip.frame_at(&smooth, at + d),
        );
        let der = |a: DVec3, b: DVec3| (b - a) / (2.0 * d);
        let w = 0.5
            * (f0.x.cross(der(fm.x, fp.x))
                + f0.y.cross(der(fm.y, fp.y))
                + f0.z.cross(der(fm.z, fp.z)));
        let local = DVec3::new(w.dot(f0.x), w.dot(f0.y), w.dot(f0.z));
        let exact = DVec3::new(pitch / a2, r / a2, 0.0);
        assert!(
            (local - exact).abs().max_element() < 1e-7,
            "{local} against {exact}"
        );
        let rate = darboux_rate(f0.kg_per_mm, f0.kn_per_mm, f0.tg_per_mm);
        assert!(
            (rate - exact).abs().max_element() < 1e-7,
            "{rate} against {exact}"
        );
    }

    /// Union–find root.
    fn find(p: &mut [usize], i: usize) -> usize {
        let mut i = i;
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }

    fn connected(m: &FrameModel) -> bool {
        let mut p: Vec<usize> = (0..m.nodes_mm.len()).collect();
        let pairs = m
            .beams
            .iter()
            .map(|b| b.nodes)
            .chain(m.links.iter().map(|l| l.nodes));
        for [a, b] in pairs {
            let (ra, rb) = (find(&mut p, a), find(&mut p, b));
            p[ra] = rb;
        }
        let r = find(&mut p, 0);
        (0..m.nodes_mm.len()).all(|i| find(&mut p, i) == r)
    }

    /// Counts, chains and connectivity of a built sample.
    fn check_shape(an: &Analysis, p: &Profile, kit: &Kit, f: &BuiltFrame, e: usize) {
        let m = &f.model;
        assert_eq!(f.roles.len(), m.beams.len());
        assert_eq!(f.targets.beam_weight_n_per_mm.len(), m.beams.len());
        assert_eq!(f.targets.tributary_mm2.len(), m.nodes_mm.len());
        assert_eq!(f.targets.node_weight_n.len(), m.nodes_mm.len());
        assert!(connected(m), "every node reachable from every joint");
        for s in an.lamella_strips() {
            let beams = &f.targets.strip_beams[&s.id];
            for o in p.lamella_offsets(s.family) {
                let line = LamellaLine::new(s, &an.curves[s.curve], o);
                let st: Vec<f64> = line.nodes.iter().map(|n| n.station_mm).collect();
                let spans = st.windows(2).filter(|w| w[1] - w[0] >= MIN_SPAN_MM).count();
                // Blocks inside the chain, off the subdivision nodes.
                let sub: Vec<f64> = st
                    .windows(2)
                    .flat_map(|w| (0..=e).map(move |i| w[0] + (w[1] - w[0]) * i as f64 / e as f64))
                    .collect();
                let extra = kit
                    .parts
                    .iter()
                    .filter(|q| q.strip.as_deref() == Some(&s.id) && q.lamella == Some(o.number))
                    .flat_map(|q| q.features.iter())
                    .filter(|x| x.hole_use == Some(HoleUse::ShearBlock))
                    .filter_map(|x| x.station_mm)
                    .filter(|&x| x > st[0] && x < st[st.len() - 1])
                    .filter(|&x| sub.iter().all(|&y| (x - y).abs() > SNAP_MM))
                    .count();
                let mine: Vec<usize> = beams
                    .iter()
                    .copied()
                    .filter(|&b| f.roles[b].as_ref().map(|r| r.lamella) == Some(o.number))
                    .collect();
                assert_eq!(
                    mine.len(),
                    spans * e + extra,
                    "{} lamella {}",
                    s.id,
                    o.number
                );
                // A chain: each element starts where the last ended, and
                // stations increase.
                for w in mine.windows(2) {
                    assert_eq!(m.beams[w[0]].nodes[1], m.beams[w[1]].nodes[0]);
                    let (r0, r1) = (
                        f.roles[w[0]].as_ref().unwrap(),
                        f.roles[w[1]].as_ref().unwrap(),
                    );
                    assert!(r1.station_mm > r0.station_mm);
                }
                // The chain's ends are at the first and last nodes' stations.
                let total: f64 = mine
                    .iter()
                    .map(|&b| m.beams[b].length_mm(&m.nodes_mm))
                    .sum();
                let arc = st[st.len() - 1] - st[0];
                assert!(
                    total <= arc + 1e-6 && total > arc * (1.0 - 1e-4),
                    "{total} against {arc}"
                );
            }
        }
    }

    #[test]
    fn enneper_in_steel_is_doubled_interlocking_vierendeel_chains() {
        let (net, an, p, kit, f) = build("enneper-4m", "steel-1.5");
        check_shape(&an, &p, &kit, &f, 4);
        let m = &f.model;
        // Every A×B joint: its four lamellas (doubled at dy = ±5.75 mm)
        // reach the joint node by rigid offsets 5.75 mm long (the bolt and
        // the washers' clamp), no release (star washers lock the angle:
        // see the pins below), and no node of their own there.
        let grid = washer::grid_nodes(&an);
        let at = |j: usize| -> Vec<DVec3> {
            let mut v: Vec<DVec3> = m
                .beams
                .iter()
                .flat_map(|b| {
                    (0..2)
                        .filter(move |&e| b.nodes[e] == j)
                        .map(|e| b.offsets_mm[e])
                })
                .collect();
            v.sort_by(|a, b| a.to_array().partial_cmp(&b.to_array()).unwrap());
            v.dedup_by(|a, b| a.distance(*b) < 1e-9);
            v
        };
        for g in &grid {
            let j = f.targets.node_ids[&g.id.to_string()];
            let levers = at(j);
            assert_eq!(levers.len(), 4, "node {}: {levers:?}", g.id);
            for o in levers {
                assert!((o.length() - 5.75).abs() < 1e-6, "{o}");
            }
        }
        // Shear blocks: lamella 2 reaches lamella 1's node at every block
        // by an offset 11.5 mm across the gap.
        let blocks: u64 = kit
            .parts
            .iter()
            .filter(|q| q.kind == PartKind::ShearBlock)
            .map(|q| u64::from(q.count))
            .sum();
        let across = (0..m.nodes_mm.len())
            .filter(|&n| at(n).iter().any(|o| (o.length() - 11.5).abs() < 1e-3))
            .count() as u64;
        assert!(blocks > 0);
        assert_eq!(across, blocks);
        // Every element is a lamella's or a band's: each weighs.
        assert_eq!(m.sections.len(), 2);
        assert!(f.targets.beam_weight_n_per_mm.iter().all(|&w| w > 0.0));
        // Edge joints: the band's node linked with the rotation about the
        // normal free.
        let edge_nodes = an
            .topology
            .nodes
            .iter()
            .filter(|n| net.curves[n.b].family == Family::Edge)
            .count();
        let pins = m
            .links
            .iter()
            .filter(|l| l.rotation_nmm_per_rad[2] == 0.0)
            .count();
        assert_eq!(pins, edge_nodes);
        eprintln!(
            "enneper steel: {} nodes, {} beams, {} links",
            m.nodes_mm.len(),
            m.beams.len(),
            m.links.len()
        );
        // Each A×B joint carries its two star washers and its node bolt
        // (M8, no plain washers under the stars), nothing else.
        let bolt = kit
            .summary
            .hardware
            .iter()
            .find(|hw| hw.item == "node bolt")
            .expect("node bolts");
        let set_kg = bolt_set_mass_kg(8.0, bolt.length_mm.expect("a length"), 0).unwrap();
        for g in &grid {
            let star = kit
                .parts
                .iter()
                .find(|q| q.id == washer::washer_id(washer::angle_class_deg(g.angle_deg)))
                .expect("its washer");
            let want = (2.0 * part_mass_kg(star, &p) + set_kg) * G_M_PER_S2;
            let got = f.targets.node_weight_n[f.targets.node_ids[&g.id.to_string()]];
            assert!(
                (got - want).abs() < 1e-9,
                "node {}: {got} against {want}",
                g.id
            );
        }
        // The boundary: every strip's first and last node.
        for s in &an.strips {
            for cn in [s.nodes.first(), s.nodes.last()].into_iter().flatten() {
                let j = f.targets.node_ids[&cn.node.to_string()];
                assert!(f.targets.boundary_nodes.binary_search(&j).is_ok());
            }
        }
        // Edge bands: chains on the edge curves, `elements_per_span` per
        // span between their nodes, no role.
        for s in an.edge_strips() {
            let beams = &f.targets.strip_beams[&s.id];
            let spans = s
                .node_to_node_mm()
                .iter()
                .filter(|&&l| l >= MIN_SPAN_MM)
                .count();
            assert_eq!(beams.len(), 4 * spans, "{}", s.id);
            assert!(beams.iter().all(|&b| f.roles[b].is_none()
                && m.beams[b].section == SECTION_BAND
                && f.targets.beam_weight_n_per_mm[b] > 0.0));
        }
        // Two elements a span: the same shape.
        let two = FrameOptions {
            elements_per_span: 2,
        };
        let f2 = build_frame(&net, &an, &p, &kit, &two).unwrap();
        check_shape(&an, &p, &kit, &f2, 2);
        let zero = FrameOptions {
            elements_per_span: 0,
        };
        let err = build_frame(&net, &an, &p, &kit, &zero)
            .unwrap_err()
            .to_string();
        assert!(err.ends_with("elements_per_span is 0)"), "{err}");
        // Deterministic, bit for bit.
        let again = build_frame(&net, &an, &p, &kit, &FrameOptions::default()).unwrap();
        assert_eq!(again, f);
    }

    #[test]
    fn a_two_level_hypar_in_poplar_has_eccentric_stud_links() {
        let (_, an, p, kit, f) = build("hypar-small", "poplar-ply-4");
        check_shape(&an, &p, &kit, &f, 4);
        let m = &f.model;
        // Lamellas at dy = ±12, dz = ±30 from the surface: each reaches
        // the joint by a rigid offset √(12² + 30²) = 32.311 mm long (the
        // stud).
        for g in washer::grid_nodes(&an) {
            let j = f.targets.node_ids[&g.id.to_string()];
            let lens: Vec<f64> = m
                .beams
                .iter()
                .flat_map(|b| {
                    (0..2)
                        .filter(move |&e| b.nodes[e] == j)
                        .map(|e| b.offsets_mm[e])
                })
                .map(|o| o.length())
                .collect();
            assert!(!lens.is_empty());
            for d in lens {
                assert!((d - (144.0f64 + 900.0).sqrt()).abs() < 1e-6, "{d}");
            }
        }
    }

    #[test]
    fn single_veneer_slots_turn_about_the_normal() {
        // No washers, slots swept over 10°: every A×B joint's B side is a
        // link with no stiffness about the normal; A's link is full.
        let (net, an, p, kit, f) = build("enneper-4m", "beech-veneer");
        check_shape(&an, &p, &kit, &f, 4);
        let free = f
            .model
            .links
            .iter()
            .filter(|l| l.rotation_nmm_per_rad[2] == 0.0)
            .count();
        let nodes = an.topology.nodes.len();
        assert_eq!(free, nodes, "one release per node (B or the band)");
        // A's side is rigid: no link, A's node is the joint's.
        assert_eq!(f.model.links.len(), nodes);
        let _ = net;
    }

    /// The strip's curvature samples linearly interpolated at `s`.
    fn sampled(s: &StripGeometry, at: f64) -> (f64, f64, f64) {
        let i = s
            .samples
            .partition_point(|c| c.station_mm <= at)
            .clamp(1, s.samples.len() - 1);
        let (a, b) = (&s.samples[i - 1], &s.samples[i]);
        let u = ((at - a.station_mm) / (b.station_mm - a.station_mm)).clamp(0.0, 1.0);
        let lerp = |x: f64, y: f64| x + u * (y - x);
        (
            lerp(a.kg_per_mm, b.kg_per_mm),
            lerp(a.kn_per_mm, b.kn_per_mm),
            lerp(a.tg_per_mm, b.tg_per_mm),
        )
    }

    /// σb = |M_z|/(h·t²/6) and τ = |T|·t/J of every lamella element against
    /// the elastic check's at the same station (the strip's samples
    /// interpolated, divided by the line's stretch): within 1 % (plus 0.2 %
    /// of the strip's peak and 1e-4 f_d, where the stress crosses zero or
    /// the strip is straight).
    fn erection_matches_the_check(sample: &str, profile: &str) {
        let (_, an, p, _, f) = build(sample, profile);
        erection_matches(&an, &p, &f);
    }

    /// The frame's erection state, element by element, against the
    /// check's stresses at the same station of the same lamella line.
    fn erection_matches(an: &Analysis, p: &Profile, f: &BuiltFrame) {
        let (t, h) = (p.thickness_mm(), p.height_mm());
        let sec = &f.model.sections[SECTION_LAMELLA];
        let mut compared = 0;
        for s in an.lamella_strips() {
            let smooth = &an.curves[s.curve];
            for o in p.lamella_offsets(s.family) {
                let line = LamellaLine::new(s, smooth, o);
                let pairs: Vec<(f64, f64)> = line
                    .nodes
                    .iter()
                    .zip(&s.nodes)
                    .map(|(l, c)| (l.station_mm, c.station_mm))
                    .collect();
                let mut got = Vec::new();
                for (bm, r) in f.model.beams.iter().zip(&f.roles) {
                    let Some(r) = r else { continue };
                    if r.strip != s.curve || r.lamella != o.number {
                        continue;
                    }
                    let k = pairs
                        .partition_point(|q| q.0 <= r.station_mm)
                        .clamp(1, pairs.len() - 1);
                    let (a, b) = (pairs[k - 1], pairs[k]);
                    let cs = a.1 + (r.station_mm - a.0) / (b.0 - a.0) * (b.1 - a.1);
                    let (kg, kn, tg) = sampled(s, cs);
                    let d = stretch(o.dy_mm, o.dz_mm, kg, kn, tg);
                    let want = Stresses::of(p, kg / d, tg / d);
                    let sb = bm.initial.moment_z_nmm.abs() / (h * t * t / 6.0);
                    let tau = bm.initial.torque_nmm.abs() * t / sec.j_mm4;
                    let sw = r.trapeze_mpa;
                    got.push((
                        sb,
                        want.bending_stress_mpa,
                        tau,
                        want.torsion_shear_mpa,
                        sw,
                        want.trapeze_stress_mpa,
                    ));
                }
                let floor = 1e-4 * p.design_strength_mpa();
                let peak = got.iter().fold((floor, floor, floor), |m, g| {
                    (m.0.max(g.1), m.1.max(g.3), m.2.max(g.5))
                });
                for g in &got {
                    assert!(
                        (g.0 - g.1).abs() <= 0.01 * g.1 + 2e-3 * peak.0,
                        "{} σb {} {}",
                        s.id,
                        g.0,
                        g.1
                    );
                    assert!(
                        (g.2 - g.3).abs() <= 0.01 * g.3 + 2e-3 * peak.1,
                        "{} τ {} {}",
                        s.id,
                        g.2,
                        g.3
                    );
                    assert!(
                        (g.4 - g.5).abs() <= 0.01 * g.5 + 2e-3 * peak.2,
                        "{} σw {} {}",
                        s.id,
                        g.4,
                        g.5
                    );
                    compared += 1;
                }
            }
        }
        assert!(compared > 100, "{compared}");
    }

    #[test]
    fn erection_stresses_are_the_checks_in_steel() {
        erection_matches_the_check("enneper-4m", "steel-1.5");
    }

    #[test]
    fn erection_stresses_are_the_checks_in_two_levels() {
        erection_matches_the_check("hypar-small", "poplar-ply-4");
    }

    /// The helicoid: its rulings are straight and purely twisted (the
    /// torque alone), its helices bend and twist.
    #[test]
    fn erection_stresses_are_the_checks_on_a_helicoid() {
        let dir =
            std::env::temp_dir().join(format!("lamella-erection-helicoid-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let spec_path = dir.join("helicoid.trace.yaml");
        std::fs::write(
            &spec_path,
            "surface: helicoid\nc: 1.0\nscale_mm: 1000\nseed: [0.75, 0.9]\nspacing_mm: 250\n\
             clip:\n  parameters: {polygon: [[0.0, 0.3], [1.5, 0.3], [1.5, 1.5], [0.0, 1.5]]}\n\
             sampling: {step_mm: 25}\n",
        )
        .expect("spec");
        let spec = crate::formats::read::trace_spec::load(&spec_path).expect("spec reads");
        let (raw, _) =
            crate::design::design(&spec, &spec_path, &crate::formats::read::mesh::read_mesh)
                .expect("traced");
        let _ = std::fs::remove_dir_all(&dir);
        let net = Network::new(raw, &spec_path).expect("network");
        let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analysis");
        let p = profile_file::load(&root().join("profiles/steel-1.5.yaml")).expect("profile");
        let kit = fabricate(&net, &an, &p, None, NetworkLines::default()).expect("kit");
        let f = build_frame(&net, &an, &p, &kit, &FrameOptions::default()).expect("frame");
        // Straight rulings: no bending, a torque; helices: both.
        let twisted_only = f
            .model
            .beams
            .iter()
            .zip(&f.roles)
            .filter(|(b, r)| {
                r.is_some()
                    && b.initial.torque_nmm.abs() > 1.0
                    && b.initial.moment_z_nmm.abs() < 1e-3 * b.initial.torque_nmm.abs()
            })
            .count();
        assert!(twisted_only > 50, "{twisted_only} purely twisted elements");
        erection_matches(&an, &p, &f);
    }

    /// A network of straight lines: A at x = 0, 100, …, 400 (y from −50 to
    /// 450), B at y = 0, 100, …, 400, in the plane z = 0.
    fn planar_grid() -> (Network, Analysis) {
        let line = |id: String, family, p0: DVec3, p1: DVec3| RawCurve {
            id,
            family,
            points: (0..=10).map(|k| p0.lerp(p1, k as f64 / 10.0)).collect(),
            normals: None,
        };
        let mut curves = Vec::new();
        for i in 0..5 {
            let x = 100.0 * i as f64;
            curves.push(line(
                format!("A{i}"),
                Family::A,
                DVec3::new(x, -50.0, 0.0),
                DVec3::new(x, 450.0, 0.0),
            ));
        }
        for i in 0..5 {
            let y = 100.0 * i as f64;
            curves.push(line(
                format!("B{i}"),
                Family::B,
                DVec3::new(-50.0, y, 0.0),
                DVec3::new(450.0, y, 0.0),
            ));
        }
        let raw = RawNetwork {
            name: "grid".into(),
            unit: Unit::Mm,
            tolerance: Some(0.5),
            precision: None,
            curves,
        };
        let net = Network::new(raw, Path::new("grid.yaml")).expect("network");
        let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analysis");
        (net, an)
    }

    #[test]
    fn a_planar_grid_carries_its_cells_in_quarters() {
        // 4 × 4 cells of 100 × 100 mm: 160 000 mm²; a corner node carries a
        // quarter cell (2 500 mm²), an edge node two quarters, an inner node
        // a whole cell; all along +z.
        let (_, an) = planar_grid();
        assert_eq!(grid_cells(&an).len(), 16);
        let t = tributary_areas(&an);
        let total: DVec3 = t.iter().copied().sum();
        assert!(
            (total - DVec3::new(0.0, 0.0, 160_000.0)).length() < 1e-6,
            "{total}"
        );
        let mut by = t
            .iter()
            .map(|v| (v.z * 1000.0).round() as i64)
            .collect::<Vec<_>>();
        by.sort_unstable();
        let count = |v: i64| by.iter().filter(|&&x| x == v * 1000).count();
        assert_eq!((count(2500), count(5000), count(10_000)), (4, 12, 9));
    }

    #[test]
    fn the_hypar_carries_its_surface_area() {
        // z = xy/1500 over [−650, 650]² (the strips at x, y = −600 … 600 step
        // 200 and the edge rulings at ±650), less the four corner squares
        // [600, 650]² where two edges meet without a node: ∫∫ √(1 + (x² +
        // y²)/c²) by the midpoint rule on 2.5 mm cells.
        let (_, an, _, _, f) = build("hypar-small", "poplar-ply-4");
        let c = 1500.0;
        let step = 2.5;
        let n = (1300.0 / step) as usize;
        let mut want = 0.0;
        for i in 0..n {
            for j in 0..n {
                let x = -650.0 + step * (i as f64 + 0.5);
                let y = -650.0 + step * (j as f64 + 0.5);
                if x.abs() > 600.0 && y.abs() > 600.0 {
                    continue;
                }
                want += step * step * (1.0 + (x * x + y * y) / (c * c)).sqrt();
            }
        }
        let got: f64 = f.targets.tributary_mm2.iter().map(|v| v.length()).sum();
        let cells: f64 = grid_cells(&an).iter().map(|c| c.1).sum();
        assert!((got - cells).abs() < 1e-6 * cells, "{got} against {cells}");
        eprintln!("hypar: tributary {got} mm², integral {want} mm²");
        assert!((got - want).abs() < 2e-3 * want, "{got} against {want}");
        // Every tributary vector points up.
        assert!(f.targets.tributary_mm2.iter().all(|v| v.z >= 0.0));
    }

    #[test]
    fn a_bolt_weighs_its_shank_head_nut_and_washers() {
        // M8 × 70: shank π/4·8²·70 = 3518.58 mm³, head (√3/2)·13²·5.3 =
        // 775.69 mm³, nut ((√3/2)·13² − π/4·8²)·6.8 = 653.41 mm³; 4947.68
        // mm³ × 7.85e-6 kg/mm³ = 0.0388396 kg (a catalogue M8 × 70 with its
        // nut: about 0.036 kg).
        let m = bolt_set_mass_kg(8.0, 70.0, 0).unwrap();
        assert!((m - 0.038_839_6).abs() < 1e-6, "{m}");
        // Two M8 washers: π/4·(16² − 8.4²)·1.6 = 233.0 mm³ each.
        let w = bolt_set_mass_kg(8.0, 70.0, 2).unwrap() - m;
        assert!((w - 2.0 * 232.98 * 7.85e-6).abs() < 1e-6, "{w}");
        assert_eq!(bolt_set_mass_kg(7.0, 70.0, 0), None);
    }

    /// Σ node weights = g × (the kit's mass less its lamellas and bands,
    /// plus the bolts); the lamella elements weigh ρ·g·A per mm over the
    /// lines between their end nodes.
    fn masses(sample: &str, profile: &str) {
        let (_, an, p, kit, f) = build(sample, profile);
        let strips: f64 = kit
            .parts
            .iter()
            .filter(|q| matches!(q.kind, PartKind::Lamella | PartKind::EdgeStrip))
            .map(|q| part_mass_kg(q, &p) * f64::from(q.count))
            .sum();
        let bolts: f64 = bolt_masses_kg(&kit, &p).values().sum();
        let nodes: f64 = f.targets.node_weight_n.iter().sum();
        let want = (kit.summary.mass_kg - strips + bolts) * G_M_PER_S2;
        assert!(want > 0.0);
        assert!((nodes - want).abs() < 1e-9 * want, "{nodes} against {want}");
        let m = &f.model;
        let mut lamella_n = 0.0;
        for (i, b) in m.beams.iter().enumerate() {
            if f.roles[i].is_some() {
                lamella_n += f.targets.beam_weight_n_per_mm[i] * b.length_mm(&m.nodes_mm);
            }
        }
        let mut length = 0.0;
        for s in an.lamella_strips() {
            for o in p.lamella_offsets(s.family) {
                let l = LamellaLine::new(s, &an.curves[s.curve], o);
                length += l.nodes[l.nodes.len() - 1].station_mm - l.nodes[0].station_mm;
            }
        }
        let rho_g_a =
            p.material.density_kg_per_m3 * 1e-9 * G_M_PER_S2 * p.thickness_mm() * p.height_mm();
        assert!(
            (lamella_n - rho_g_a * length).abs() < 1e-4 * lamella_n,
            "{lamella_n}"
        );
        // The model carries the gross section between the end nodes: less
        // than the whole cut rectangles (allowances, ends beyond the end
        // nodes), as do the cut lamellas (slots and holes taken out).
        let cut: f64 = kit
            .parts
            .iter()
            .filter(|q| q.kind == PartKind::Lamella)
            .map(|q| part_mass_kg(q, &p) * f64::from(q.count))
            .sum::<f64>()
            * G_M_PER_S2;
        let full: f64 = an
            .lamella_strips()
            .flat_map(|s| p.lamella_offsets(s.family).into_iter().map(move |o| (s, o)))
            .map(|(s, o)| {
                LamellaLine::new(s, &an.curves[s.curve], o).length_mm
                    + 2.0 * p.section.end_allowance_mm
            })
            .sum::<f64>()
            * rho_g_a;
        eprintln!("model {lamella_n} N, cut {cut} N, whole rectangles {full} N");
        assert!(
            lamella_n < full && cut < full,
            "{lamella_n}, {cut} < {full}"
        );
    }

    #[test]
    fn steel_masses_add_up() {
        masses("enneper-4m", "steel-1.5");
    }

    #[test]
    fn poplar_masses_add_up() {
        masses("hypar-small", "poplar-ply-4");
    }

    #[test]
    fn every_shipped_profile_builds_a_connected_frame_on_five_samples() {
        let mut built = 0;
        for sample in [
            "catenoid",
            "scherk",
            "schwarz-d-patch",
            "film-saddle",
            "hypar-small",
        ] {
            for profile in ["steel-1.5", "poplar-ply-4", "beech-veneer"] {
                let (net, an, p, kit) = load(sample, profile);
                let f = build_frame(&net, &an, &p, &kit, &FrameOptions::default())
                    .unwrap_or_else(|e| panic!("{sample} {profile}: {e}"));
                assert!(connected(&f.model), "{sample} {profile}");
                let trib: f64 = f.targets.tributary_mm2.iter().map(|v| v.length()).sum();
                let cells: f64 = grid_cells(&an).iter().map(|c| c.1).sum();
                assert!(cells > 0.0 && (trib - cells).abs() < 1e-9 * cells);
                assert!(f.targets.boundary_nodes.windows(2).all(|w| w[0] < w[1]));
                assert_eq!(f.targets.node_ids.len(), an.topology.nodes.len());
                built += 1;
            }
        }
        assert_eq!(built, 15);
    }
}
