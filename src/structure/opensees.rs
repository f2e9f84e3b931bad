//! The frame model exported to OpenSees: a plain JSON of the model and its
//! load sets, and a runnable OpenSeesPy script that builds the same model,
//! solves every load set by a linear static analysis and writes each
//! node's displacements and each support's reaction to a JSON file
//! (`python3 opensees.py results.json`), so that lamella's solver can be
//! checked against an independent one (the integration tests do, to 1 %
//! of each load set's largest displacement and reaction; they agree to
//! about 1e-9).
//!
//! **One to one.** Nodes keep their order (OpenSees tag = index + 1). A
//! beam is an `elasticBeamColumn` (A, E, G, J, I_y, I_z: OpenSees' order
//! and local axes, see [`super::model`]) with its own
//! `geomTransf('Linear', …, *z_axis, '-jntOffset', …)` (the z axis is
//! OpenSees' vecxz; the offsets are global, as lamella's). A link is a
//! `zeroLength` element with one `Elastic` material per stiff direction
//! (translations 1–3, rotations 4–6 in the link's frame: `-orient` its
//! first two columns; a zero stiffness is a free direction). Supports of a
//! node are merged into one `fix`. An inclined roller is a `zeroLength`
//! spring along its direction to an extra node fixed in all six degrees
//! of freedom (tags after the model's nodes), of the stiffness lamella
//! gives it ([`PENALTY`] × the node's largest translational stiffness,
//! computed here from lamella's own assembly and written as a number), so
//! both solve the same matrix; its force is added to the node's reaction.
//!
//! **Loads.** Node loads are `load`s; a uniform element load (global
//! N/mm) is a `-beamUniform` element load in the element's local axes
//! (the frame of [`element_frame`], identical to OpenSees' for the same
//! vecxz); a following pressure is exported as the same uniform load
//! along the element's initial local z (identical in a linear analysis;
//! its load stiffness is not exported). Each load set is a pattern on a
//! `Linear` time series, so a `LoadControl` step of λ applies λ times it.
//! `build('PDelta')` builds the model with OpenSees' P-Δ geometric
//! stiffness (the flexural terms only, no polar term): a linear buckling
//! search (`tests/tools/opensees_buckling.py`) imports the script and
//! bisects on λ the definiteness of the tangent after one linear step.
//!
//! **Cables** (tension-only) are `Truss` elements of an `Elastic`
//! material of modulus E + T₀/A with no stiffness in compression
//! (`Eneg` 0), wrapped in an `InitStrainMaterial` of T₀/(E·A + T₀) when
//! pretensioned, so the truss carries T₀ + (E·A + T₀)/L·δ while taut, as
//! lamella's [`Cable`]. A fitting beside its node is an extra node on a
//! `rigidLink('beam', …)` (constraints `Transformation`), its reaction
//! added to the node's with its lever. With cables the analysis is
//! `Newton` (the cables' state is found by iteration), else `Linear`.
//!
//! **Not exported.** The elements' erection state ([`Beam::initial`]):
//! lamella's linear solve adds the geometric stiffness of its axial force,
//! the OpenSees model has none, so compare models without one.
//!
//! [`Beam::initial`]: super::model::Beam::initial
//! [`Cable`]: super::model::Cable
//! [`element_frame`]: super::solve::element_frame

use super::loads::flattened;
use super::model::{FrameModel, LoadSet};
use super::solve::{validate_loads, Assembly, ElementFrame, FrameError, PENALTY};
use glam::DVec3;
use serde_json::{json, Value};
use std::borrow::Cow;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// A roller on an inclined bearing as exported: a spring to a fixed node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollerSpring {
    /// The supported node.
    pub node: usize,
    /// The bearing's direction (unit).
    pub along: DVec3,
    /// The spring's stiffness, N/mm (lamella's penalty).
    pub stiffness_n_per_mm: f64,
}

/// What the export computes from the model once.
struct Prepared {
    frames: Vec<ElementFrame>,
    /// Per node with supports: its merged fixed flags.
    fixed: BTreeMap<usize, [bool; 6]>,
    rollers: Vec<RollerSpring>,
}

/// Each load set of `model` with its parts' loads as its own (a
/// combination's, the factored sum of its cases), as the files list them;
/// checked first (a part naming an element that does not exist is an
/// error, not a sum grown to its index).
fn flat<'a>(
    model: &FrameModel,
    load_sets: &'a [LoadSet],
) -> Result<Vec<Cow<'a, LoadSet>>, FrameError> {
    for l in load_sets {
        validate_loads(model, l)?;
    }
    Ok(load_sets
        .iter()
        .map(|l| match l.parts.is_empty() {
            true => Cow::Borrowed(l),
            false => Cow::Owned(flattened(l)),
        })
        .collect())
}

/// The supports and inclined rollers of `model`, as exported.
fn prepare(model: &FrameModel) -> Result<Prepared, FrameError> {
    let assembly = Assembly::new(model, &model.nodes_mm)?;
    let mut fixed: BTreeMap<usize, [bool; 6]> = BTreeMap::new();
    for s in &model.supports {
        let f = fixed.entry(s.node).or_insert([false; 6]);
        for (f, &fixed) in f.iter_mut().zip(&s.fixed) {
            *f |= fixed;
        }
    }
    let mut rollers = Vec::new();
    if model.supports.iter().any(|s| s.along.is_some()) {
        // The stiffness without penalties, as the solver scales its
        // penalty springs by it.
        let k = assembly.stiffness(model);
        let diagonal = k.scaling.clone().unwrap_or_else(|| k.diagonal());
        for s in &model.supports {
            let Some(along) = s.along else { continue };
            let own = (0..3)
                .map(|p| assembly.dofs.index[s.node * 6 + p])
                .filter(|&d| d != usize::MAX)
                .map(|d| diagonal[d])
                .fold(0.0, f64::max)
                .max(1.0);
            rollers.push(RollerSpring {
                node: s.node,
                along: along.normalize(),
                stiffness_n_per_mm: PENALTY * own,
            });
        }
    }
    Ok(Prepared {
        frames: assembly.frames,
        fixed,
        rollers,
    })
}

/// The springs that stand for `model`'s inclined rollers in the export.
pub fn roller_springs(model: &FrameModel) -> Result<Vec<RollerSpring>, FrameError> {
    Ok(prepare(model)?.rollers)
}

fn v3(v: DVec3) -> Value {
    json!([v.x, v.y, v.z])
}

/// The model and its load sets as plain JSON (N, mm, MPa; indices from 0;
/// deterministic), with each element's local axes and each inclined
/// roller's spring as exported.
pub fn model_json(model: &FrameModel, load_sets: &[LoadSet]) -> Result<String, FrameError> {
    let load_sets = &flat(model, load_sets)?;
    let p = prepare(model)?;
    let sections: Vec<Value> = model
        .sections
        .iter()
        .map(|s| {
            json!({"e_mpa": s.e_mpa, "g_mpa": s.g_mpa, "area_mm2": s.area_mm2,
                   "i_y_mm4": s.i_y_mm4, "i_z_mm4": s.i_z_mm4, "j_mm4": s.j_mm4})
        })
        .collect();
    let beams: Vec<Value> = model
        .beams
        .iter()
        .zip(&p.frames)
        .map(|(b, f)| {
            json!({
                "nodes": b.nodes, "section": b.section, "z_axis": v3(b.z_axis),
                "offsets_mm": [v3(b.offsets_mm[0]), v3(b.offsets_mm[1])],
                "initial": {"axial_n": b.initial.axial_n, "torque_nmm": b.initial.torque_nmm,
                            "moment_y_nmm": b.initial.moment_y_nmm,
                            "moment_z_nmm": b.initial.moment_z_nmm},
                "length_mm": f.length_mm,
                "local_axes": [v3(f.rotation.row(0)), v3(f.rotation.row(1)), v3(f.rotation.row(2))],
            })
        })
        .collect();
    let links: Vec<Value> = model
        .links
        .iter()
        .map(|l| {
            json!({"nodes": l.nodes,
                   "frame": [v3(l.frame.col(0)), v3(l.frame.col(1)), v3(l.frame.col(2))],
                   "translation_n_per_mm": l.translation_n_per_mm,
                   "rotation_nmm_per_rad": l.rotation_nmm_per_rad})
        })
        .collect();
    let cables: Vec<Value> = model
        .cables
        .iter()
        .map(|c| {
            json!({"nodes": c.nodes,
                   "offsets_mm": [v3(c.offsets_mm[0]), v3(c.offsets_mm[1])],
                   "area_mm2": c.area_mm2, "e_mpa": c.e_mpa, "pretension_n": c.pretension_n,
                   "length_mm": c.length_mm(&model.nodes_mm),
                   "unstressed_length_mm": c.unstressed_length_mm(&model.nodes_mm)})
        })
        .collect();
    let supports: Vec<Value> = model
        .supports
        .iter()
        .map(|s| json!({"node": s.node, "fixed": s.fixed, "along": s.along.map(v3)}))
        .collect();
    let rollers: Vec<Value> = p
        .rollers
        .iter()
        .map(|r| {
            json!({"node": r.node, "along": v3(r.along),
                   "stiffness_n_per_mm": r.stiffness_n_per_mm})
        })
        .collect();
    let sets: Vec<Value> = load_sets
        .iter()
        .map(|l| {
            json!({
                "name": l.name,
                "nodes": l.nodes.iter().map(|n| json!({"node": n.node,
                    "force_n": v3(n.force_n), "moment_nmm": v3(n.moment_nmm)})).collect::<Vec<_>>(),
                "beams": l.beams.iter().map(|b| json!({"beam": b.beam,
                    "force_n_per_mm": v3(b.force_n_per_mm)})).collect::<Vec<_>>(),
                "pressures": l.pressures.iter().map(|b| json!({"beam": b.beam,
                    "n_per_mm": b.n_per_mm})).collect::<Vec<_>>(),
            })
        })
        .collect();
    let doc = json!({
        "units": {"length": "mm", "force": "N", "stress": "MPa"},
        "dofs": ["ux", "uy", "uz", "rx", "ry", "rz"],
        "nodes_mm": model.nodes_mm.iter().map(|n| v3(*n)).collect::<Vec<_>>(),
        "sections": sections,
        "beams": beams,
        "links": links,
        "cables": cables,
        "supports": supports,
        "roller_springs": rollers,
        "load_sets": sets,
    });
    serde_json::to_string_pretty(&doc)
        .map_err(|e| FrameError::Invalid(format!("model JSON: {e}")))
        .map(|s| s + "\n")
}

/// A number as Python reads it back exactly (shortest round trip).
fn num(v: f64) -> String {
    format!("{v:?}")
}

fn nums(v: &[f64]) -> String {
    v.iter().map(|&x| num(x)).collect::<Vec<_>>().join(", ")
}

/// A perpendicular to a unit vector.
fn perpendicular(a: DVec3) -> DVec3 {
    let helper = if a.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    a.cross(helper).normalize()
}

/// A string as a Python literal.
fn py_str(s: &str) -> String {
    serde_json::to_string(s).unwrap_or_else(|_| "\"\"".into())
}

/// A runnable OpenSeesPy script of `model` under `load_sets` (see the
/// module doc); `python3 script.py results.json` writes
/// `{"load_sets": [{"name", "displacements": [[ux, uy, uz, rx, ry, rz]
/// per node], "reactions": [{"node", "force_n", "moment_nmm"} per
/// supported node, ascending]}]}` (node indices from 0, as lamella's).
pub fn script(model: &FrameModel, load_sets: &[LoadSet]) -> Result<String, FrameError> {
    let load_sets = &flat(model, load_sets)?;
    let p = prepare(model)?;
    let n_nodes = model.nodes_mm.len();
    let mut s = String::new();
    let w = &mut s;
    // Writing to a String cannot fail.
    let _ = writeln!(w, "#!/usr/bin/env python3");
    let _ = writeln!(
        w,
        "\"\"\"A lamella frame model in OpenSees: N, mm, MPa.\n\n\
         Usage: python3 {{this file}} results.json\n\n\
         Node tag = lamella node index + 1; beam i is element i + 1, link j element\n\
         {} + j; an inclined roller is a zeroLength spring to an extra fixed node.\n\
         Each load set is a static analysis of a freshly built model (linear, or\n\
         Newton where tension-only cables are); the\n\
         results file holds every node's displacements and every supported node's\n\
         reaction (lamella's indices). The erection state is not modelled.\n\"\"\"",
        model.beams.len() + 1
    );
    let _ = writeln!(
        w,
        "import json\nimport sys\n\nimport openseespy.opensees as ops\n"
    );
    let _ = writeln!(w, "NODES = {n_nodes}");
    let supported: Vec<usize> = p.fixed.keys().copied().collect();
    let _ = writeln!(w, "SUPPORTED = {supported:?}");
    let extra: Vec<(usize, usize)> = p
        .rollers
        .iter()
        .enumerate()
        .map(|(i, r)| (r.node + 1, n_nodes + 1 + i))
        .collect();
    let _ = writeln!(
        w,
        "# (supported node tag, its roller's fixed node tag)\nROLLERS = {:?}\n",
        extra
    );
    let _ = writeln!(
        w,
        "\ndef build(transf='Linear'):\n    \"\"\"The model ('PDelta': with its geometric stiffness).\"\"\"\n    \
         ops.wipe()"
    );
    let _ = writeln!(w, "    ops.model('basic', '-ndm', 3, '-ndf', 6)");
    let _ = writeln!(w, "    # Nodes, mm.");
    for (i, n) in model.nodes_mm.iter().enumerate() {
        let _ = writeln!(w, "    ops.node({}, {})", i + 1, nums(&n.to_array()));
    }
    let _ = writeln!(w, "    # Supports (fixed global ux uy uz rx ry rz).");
    for (node, f) in &p.fixed {
        let flags: Vec<&str> = f.iter().map(|&b| if b { "1" } else { "0" }).collect();
        let _ = writeln!(w, "    ops.fix({}, {})", node + 1, flags.join(", "));
    }
    let _ = writeln!(
        w,
        "    # Beams: vecxz = lamella's z axis, joint offsets global;\n    \
         # elasticBeamColumn tag i j A E G J Iy Iz transf."
    );
    for (i, b) in model.beams.iter().enumerate() {
        let tag = i + 1;
        let sec = &model.sections[b.section];
        let mut transf = format!(
            "    ops.geomTransf(transf, {tag}, {}",
            nums(&b.z_axis.to_array())
        );
        if b.offsets_mm.iter().any(|o| *o != DVec3::ZERO) {
            let _ = write!(
                transf,
                ", '-jntOffset', {}, {}",
                nums(&b.offsets_mm[0].to_array()),
                nums(&b.offsets_mm[1].to_array())
            );
        }
        let _ = writeln!(w, "{transf})");
        let _ = writeln!(
            w,
            "    ops.element('elasticBeamColumn', {tag}, {}, {}, {}, {tag})",
            b.nodes[0] + 1,
            b.nodes[1] + 1,
            nums(&[
                sec.area_mm2,
                sec.e_mpa,
                sec.g_mpa,
                sec.j_mm4,
                sec.i_y_mm4,
                sec.i_z_mm4
            ])
        );
    }
    let mut material = 0usize;
    let mut element = model.beams.len();
    if !model.links.is_empty() {
        let _ = writeln!(
            w,
            "    # Links: zeroLength, directions 1-3 along and 4-6 about the link's axes."
        );
    }
    for l in &model.links {
        element += 1;
        let mut mats = Vec::new();
        let mut dirs = Vec::new();
        let stiff = l
            .translation_n_per_mm
            .iter()
            .chain(&l.rotation_nmm_per_rad)
            .enumerate();
        for (d, &k) in stiff {
            if k != 0.0 {
                material += 1;
                let _ = writeln!(
                    w,
                    "    ops.uniaxialMaterial('Elastic', {material}, {})",
                    num(k)
                );
                mats.push(material.to_string());
                dirs.push((d + 1).to_string());
            }
        }
        if mats.is_empty() {
            continue;
        }
        let _ = writeln!(
            w,
            "    ops.element('zeroLength', {element}, {}, {}, '-mat', {}, '-dir', {}, \
             '-orient', {}, {})",
            l.nodes[0] + 1,
            l.nodes[1] + 1,
            mats.join(", "),
            dirs.join(", "),
            nums(&l.frame.col(0).to_array()),
            nums(&l.frame.col(1).to_array())
        );
    }
    if !p.rollers.is_empty() {
        let _ = writeln!(
            w,
            "    # Inclined rollers: a spring along the bearing (lamella's penalty\n    \
             # stiffness, N/mm) to a node fixed in all directions."
        );
    }
    for (r, &(_, fixed_tag)) in p.rollers.iter().zip(&extra) {
        element += 1;
        material += 1;
        let at = model.nodes_mm[r.node];
        let _ = writeln!(w, "    ops.node({fixed_tag}, {})", nums(&at.to_array()));
        let _ = writeln!(w, "    ops.fix({fixed_tag}, 1, 1, 1, 1, 1, 1)");
        let _ = writeln!(
            w,
            "    ops.uniaxialMaterial('Elastic', {material}, {})",
            num(r.stiffness_n_per_mm)
        );
        let _ = writeln!(
            w,
            "    ops.element('zeroLength', {element}, {}, {fixed_tag}, '-mat', {material}, \
             '-dir', 1, '-orient', {}, {})",
            r.node + 1,
            nums(&r.along.to_array()),
            nums(&perpendicular(r.along).to_array())
        );
    }
    if !model.cables.is_empty() {
        let _ = writeln!(
            w,
            "    # Cables: tension-only trusses, E' = E + T0/A with no stiffness in\n    \
             # compression, pretensioned by an initial strain T0/(E·A + T0); a\n    \
             # fitting beside its node is an extra node on a rigid link."
        );
    }
    let mut fitting = n_nodes + p.rollers.len();
    let mut fittings: Vec<(usize, usize, DVec3)> = Vec::new();
    for c in &model.cables {
        let mut ends = [0usize; 2];
        for (end, (&node, offset)) in ends.iter_mut().zip(c.nodes.iter().zip(&c.offsets_mm)) {
            if *offset == DVec3::ZERO {
                *end = node + 1;
            } else {
                fitting += 1;
                let at = model.nodes_mm[node] + *offset;
                let _ = writeln!(w, "    ops.node({fitting}, {})", nums(&at.to_array()));
                let _ = writeln!(w, "    ops.rigidLink('beam', {}, {fitting})", node + 1);
                fittings.push((node + 1, fitting, *offset));
                *end = fitting;
            }
        }
        let ea = c.e_mpa * c.area_mm2;
        material += 1;
        let _ = writeln!(
            w,
            "    ops.uniaxialMaterial('Elastic', {material}, {}, 0.0, 0.0)",
            num(c.e_mpa + c.pretension_n / c.area_mm2)
        );
        if c.pretension_n > 0.0 {
            material += 1;
            let _ = writeln!(
                w,
                "    ops.uniaxialMaterial('InitStrainMaterial', {material}, {}, {})",
                material - 1,
                num(c.pretension_n / (ea + c.pretension_n))
            );
        }
        element += 1;
        let _ = writeln!(
            w,
            "    ops.element('Truss', {element}, {}, {}, {}, {material})",
            ends[0],
            ends[1],
            num(c.area_mm2)
        );
    }
    let listed: Vec<String> = fittings
        .iter()
        .map(|(node, tag, o)| format!("({node}, {tag}, [{}])", nums(&o.to_array())))
        .collect();
    let _ = writeln!(
        w,
        "\n\n# (node tag, its fitting's node tag, the fitting's offset): the\n\
         # fitting's reaction (its cable's pull) belongs to the node's.\n\
         FITTINGS = [{}]",
        listed.join(", ")
    );
    for (i, l) in load_sets.iter().enumerate() {
        let _ = writeln!(
            w,
            "\n\ndef loads_{i}():\n    \"\"\"Load set {}.\"\"\"",
            l.name.replace('\\', "\\\\").replace('"', "\\\"")
        );
        let _ = writeln!(w, "    ops.timeSeries('Linear', 1)");
        let _ = writeln!(w, "    ops.pattern('Plain', 1, 1)");
        for n in &l.nodes {
            let _ = writeln!(
                w,
                "    ops.load({}, {}, {})",
                n.node + 1,
                nums(&n.force_n.to_array()),
                nums(&n.moment_nmm.to_array())
            );
        }
        let mut local: BTreeMap<usize, DVec3> = BTreeMap::new();
        for b in &l.beams {
            *local.entry(b.beam).or_default() += p.frames[b.beam].rotation * b.force_n_per_mm;
        }
        for b in &l.pressures {
            local.entry(b.beam).or_default().z += b.n_per_mm;
        }
        if !local.is_empty() {
            let _ = writeln!(
                w,
                "    # Uniform element loads, local axes, N/mm: Wy, Wz, Wx (pressures\n    \
                 # as dead loads along the element's local z)."
            );
        }
        for (beam, q) in local {
            let _ = writeln!(
                w,
                "    ops.eleLoad('-ele', {}, '-type', '-beamUniform', {})",
                beam + 1,
                nums(&[q.y, q.z, q.x])
            );
        }
        let _ = writeln!(w, "    return {}", py_str(&l.name));
    }
    let names: Vec<String> = (0..load_sets.len()).map(|i| format!("loads_{i}")).collect();
    let _ = writeln!(w, "\n\nLOAD_SETS = [{}]", names.join(", "));
    // Tension-only cables make the analysis nonlinear (Newton until the
    // cables' state settles) and fittings need multi-point constraints.
    let (constraints, algorithm) = if model.cables.is_empty() {
        ("'Plain'", "ops.algorithm('Linear')")
    } else {
        (
            "'Transformation'",
            "ops.test('NormDispIncr', 1e-10, 100)\n    ops.algorithm('Newton')",
        )
    };
    let _ = write!(
        w,
        r#"

def solve(apply):
    build()
    name = apply()
    ops.constraints({constraints})
    ops.numberer('RCM')
    ops.system('UmfPack')
    {algorithm}
    ops.integrator('LoadControl', 1.0)
    ops.analysis('Static')
    if ops.analyze(1) != 0:
        sys.exit(f'load set {{name}}: the OpenSees analysis failed')
    ops.reactions()
    displacements = [ops.nodeDisp(t + 1) for t in range(NODES)]
    reactions = []
    for node in SUPPORTED:
        r = list(ops.nodeReaction(node + 1))
        for support, fixed in ROLLERS:
            if support == node + 1:
                r = [a + b for a, b in zip(r, ops.nodeReaction(fixed))]
        for held, tag, (ox, oy, oz) in FITTINGS:
            if held == node + 1:
                f = ops.nodeReaction(tag)
                m = [oy * f[2] - oz * f[1], oz * f[0] - ox * f[2], ox * f[1] - oy * f[0]]
                r = [r[k] + f[k] for k in range(3)] + [r[3 + k] + f[3 + k] + m[k] for k in range(3)]
        reactions.append({{'node': node, 'force_n': r[:3], 'moment_nmm': r[3:]}})
    return {{'name': name, 'displacements': displacements, 'reactions': reactions}}


if __name__ == '__main__':
    if len(sys.argv) != 2:
        sys.exit('usage: python3 opensees.py results.json')
    results = {{'load_sets': [solve(apply) for apply in LOAD_SETS]}}
    with open(sys.argv[1], 'w') as f:
        json.dump(results, f, indent=1)
"#
    );
    Ok(s)
}
