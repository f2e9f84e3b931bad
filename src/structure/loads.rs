//! A loads file ([`crate::loads`]) applied to a frame model: the
//! unfactored load cases as [`LoadSet`]s, their EN 1990 combinations, the
//! supports and the deflection limit. The loads file is in kN and m; the
//! model in N and mm (1 kN/m² = 10⁻³ N/mm², 1 kN/m = 1 N/mm, 1 kN =
//! 10³ N).
//!
//! Surface loads go to the joints by [`LoadTargets::tributary_mm2`]: the
//! vector a = A·n of a node (its tributary surface area A times the unit
//! normal n, n_z ≥ 0). A node takes
//!
//! * snow s (on plan): −z · s · |a_z| (Σ|a_z| is the plan area);
//! * a permanent surface load g (on the surface): −z · g · |a|;
//! * wind p (normal, + toward the inside): −p · a.
//!
//! So the totals are exact for the tributary areas the model builder gives
//! (no further approximation here). Self-weight is the kit's:
//! [`LoadTargets::beam_weight_n_per_mm`] as uniform element loads along −z,
//! and [`LoadTargets::node_weight_n`] at nodes, times the case's factor.
//! Loads at one node (or on one element) are summed into one entry; the
//! lists are sorted by node (element) index, so the output is
//! deterministic.

use crate::error::{Error, Location, Result};
use crate::loads::{Action, Deflection, LoadCase, LoadSpec, Selection, SupportKind, SupportSpec};
use crate::structure::model::{
    Combination, ElementLoad, FrameModel, LimitState, LoadSet, LoadTargets, NodeLoad, PressureLoad,
    Support,
};
use glam::DVec3;
use std::collections::BTreeMap;
use std::sync::Arc;

/// kN/m² → N/mm².
const N_PER_MM2_PER_KN_PER_M2: f64 = 1e-3;
/// kN → N.
const N_PER_KN: f64 = 1e3;
/// kN/m → N/mm.
const N_PER_MM_PER_KN_PER_M: f64 = 1.0;

/// One combination to form: its name, limit state and the factor of each
/// load case in it (case index into [`LoadSpec::cases`], ascending; cases
/// not listed take 0).
#[derive(Debug, Clone, PartialEq)]
pub struct CombinationSpec {
    /// `ULS S + 0.6W+`, `SLS G`, `ULS W- (G inf)`.
    pub name: String,
    /// Where it is checked.
    pub limit_state: LimitState,
    /// (case index, factor), ascending by case.
    pub factors: Vec<(usize, f64)>,
}

/// The combinations of a loads file, ULS then SLS.
///
/// * ULS, EN 1990 (6.10): first `ULS G` (γ_G,sup on the permanent cases
///   alone), then each variable case leading in turn (file order) with γ_Q,
///   and every choice of accompanying cases: for each other variable
///   action that may combine with the leading one ([`crate::loads::Factors::combine`])
///   and has ψ_0 > 0, none or one of its cases (none first, then file
///   order), with γ_Q·ψ_0. Cases of the leading action's own kind never
///   join it (they are alternatives). Permanent cases take γ_G,sup; where
///   a case of the combination can relieve them
///   ([`LoadCase::can_relieve`]: suction, upward loads) the combination is
///   also made with γ_G,inf, named with ` (G inf)`.
/// * SLS characteristic, (6.14b): the same choices, factors 1 and ψ_0.
///
/// Names: the limit state, the leading case, then ` + ψ0·name` per
/// accompanying case (`ULS S + 0.6W+`, `ULS W- + 0.5S (G inf)`); a factor
/// of 1 is not written. Without permanent cases there is no `G`
/// combination and no γ_G,inf variant.
pub fn combinations(spec: &LoadSpec) -> Vec<CombinationSpec> {
    let f = &spec.factors;
    let permanent: Vec<usize> = indices(spec, |c| c.action == Action::Permanent);
    let variable: Vec<usize> = indices(spec, |c| c.action.is_variable());
    let mut out = Vec::new();
    for ls in [LimitState::Ultimate, LimitState::Serviceability] {
        let uls = ls == LimitState::Ultimate;
        let gamma_q = if uls { f.gamma_q } else { 1.0 };
        let g_sup = if uls { f.gamma_g_sup } else { 1.0 };
        let with_g = |g: f64, mut list: Vec<(usize, f64)>| {
            list.extend(permanent.iter().map(|&i| (i, g)));
            list.sort_by_key(|&(i, _)| i);
            list
        };
        if !permanent.is_empty() {
            out.push(CombinationSpec {
                name: format!("{} G", ls.as_str()),
                limit_state: ls,
                factors: with_g(g_sup, Vec::new()),
            });
        }
        for &lead in &variable {
            let lead_action = spec.cases[lead].action;
            // The accompanying actions: one option list per action.
            let options: Vec<Vec<usize>> = Action::ALL
                .iter()
                .filter(|&&a| a.is_variable() && f.combine(lead_action, a) && f.psi0(a) > 0.0)
                .map(|&a| indices(spec, |c| c.action == a))
                .filter(|list| !list.is_empty())
                .collect();
            for choice in choices(&options) {
                let acc: Vec<usize> = choice.into_iter().flatten().collect();
                let compatible = acc.iter().enumerate().all(|(k, &i)| {
                    acc[..k]
                        .iter()
                        .all(|&j| f.combine(spec.cases[i].action, spec.cases[j].action))
                });
                if !compatible {
                    continue;
                }
                let mut name = format!("{} {}", ls.as_str(), spec.cases[lead].name);
                let mut list = vec![(lead, gamma_q)];
                for &i in &acc {
                    let psi = f.psi0(spec.cases[i].action);
                    name.push_str(&format!(" + {}{}", factor_text(psi), spec.cases[i].name));
                    list.push((i, gamma_q * psi));
                }
                out.push(CombinationSpec {
                    name: name.clone(),
                    limit_state: ls,
                    factors: with_g(g_sup, list.clone()),
                });
                let relieves = std::iter::once(lead)
                    .chain(acc.iter().copied())
                    .any(|i| spec.cases[i].can_relieve());
                if uls && relieves && !permanent.is_empty() {
                    out.push(CombinationSpec {
                        name: format!("{name} (G inf)"),
                        limit_state: ls,
                        factors: with_g(f.gamma_g_inf, list),
                    });
                }
            }
        }
    }
    out
}

fn indices(spec: &LoadSpec, keep: impl Fn(&LoadCase) -> bool) -> Vec<usize> {
    (0..spec.cases.len())
        .filter(|&i| keep(&spec.cases[i]))
        .collect()
}

/// Every choice of none or one entry per list, the first list varying
/// slowest, none before the entries.
fn choices(options: &[Vec<usize>]) -> Vec<Vec<Option<usize>>> {
    let mut out: Vec<Vec<Option<usize>>> = vec![Vec::new()];
    for list in options {
        let mut next = Vec::with_capacity(out.len() * (list.len() + 1));
        for prefix in &out {
            for pick in std::iter::once(None).chain(list.iter().copied().map(Some)) {
                let mut p = prefix.clone();
                p.push(pick);
                next.push(p);
            }
        }
        out = next;
    }
    out
}

/// A combination factor as a name writes it: none for 1, else `0.6`.
fn factor_text(x: f64) -> String {
    if x == 1.0 {
        String::new()
    } else {
        format!("{x}")
    }
}

/// The sums of loads per node and per element (by index: a big grid's
/// 2.5 million elements summed in ordered maps took 13 s for the 19
/// combinations), then the lists, ascending.
#[derive(Default)]
struct Sums {
    nodes: Vec<(DVec3, DVec3)>,
    beams: Vec<DVec3>,
}

/// `v[i]`, `v` grown with zeros to hold it.
fn slot<T: Default + Clone>(v: &mut Vec<T>, i: usize) -> &mut T {
    if i >= v.len() {
        v.resize(i + 1, T::default());
    }
    &mut v[i]
}

impl Sums {
    fn node(&mut self, node: usize, force_n: DVec3) {
        slot(&mut self.nodes, node).0 += force_n;
    }

    fn moment(&mut self, node: usize, moment_nmm: DVec3) {
        slot(&mut self.nodes, node).1 += moment_nmm;
    }

    fn beam(&mut self, beam: usize, force_n_per_mm: DVec3) {
        *slot(&mut self.beams, beam) += force_n_per_mm;
    }

    fn into_set(self, name: &str) -> LoadSet {
        LoadSet {
            name: name.to_string(),
            nodes: self
                .nodes
                .into_iter()
                .enumerate()
                .filter(|(_, (f, m))| *f != DVec3::ZERO || *m != DVec3::ZERO)
                .map(|(node, (force_n, moment_nmm))| NodeLoad {
                    node,
                    force_n,
                    moment_nmm,
                })
                .collect(),
            beams: self
                .beams
                .into_iter()
                .enumerate()
                .filter(|(_, q)| *q != DVec3::ZERO)
                .map(|(beam, force_n_per_mm)| ElementLoad {
                    beam,
                    force_n_per_mm,
                })
                .collect(),
            pressures: Vec::new(),
            parts: Vec::new(),
        }
    }
}

/// The targets must list one entry per model node and element.
fn check_targets(spec: &LoadSpec, model: &FrameModel, targets: &LoadTargets) -> Result<()> {
    let n = model.nodes_mm.len();
    let b = model.beams.len();
    for (what, len, want) in [
        ("tributary areas", targets.tributary_mm2.len(), n),
        ("node weights", targets.node_weight_n.len(), n),
        ("node weight levers", targets.node_weight_lever_mm.len(), n),
        ("element weights", targets.beam_weight_n_per_mm.len(), b),
    ] {
        if len != want {
            return Err(Error::input(
                &spec.source,
                Location::File,
                format!("the frame model's load targets list {len} {what} for {want} entries of the model"),
            ));
        }
    }
    if let Some(&bad) = targets
        .node_ids
        .values()
        .chain(&targets.boundary_nodes)
        .find(|&&i| i >= n)
    {
        return Err(Error::input(
            &spec.source,
            Location::File,
            format!("the frame model's load targets name node {bad} of {n}"),
        ));
    }
    Ok(())
}

/// The unfactored load cases, one [`LoadSet`] per case of `spec` (same
/// order, named as the case), in N and mm (see the module documentation
/// for each load). An unknown network node id or strip id is an error
/// naming the loads file, the field (`cases[1].point_loads[0].node`) and
/// the id.
pub fn load_cases(
    spec: &LoadSpec,
    model: &FrameModel,
    targets: &LoadTargets,
) -> Result<Vec<Arc<LoadSet>>> {
    check_targets(spec, model, targets)?;
    spec.cases
        .iter()
        .enumerate()
        .map(|(i, case)| load_case(spec, i, case, model, targets).map(Arc::new))
        .collect()
}

fn load_case(
    spec: &LoadSpec,
    i: usize,
    case: &LoadCase,
    model: &FrameModel,
    targets: &LoadTargets,
) -> Result<LoadSet> {
    let mut sums = Sums::default();
    let down = DVec3::NEG_Z;
    if case.self_weight != 0.0 {
        for (b, &w) in targets.beam_weight_n_per_mm.iter().enumerate() {
            if w != 0.0 {
                sums.beam(b, down * (case.self_weight * w));
            }
        }
        for (n, &w) in targets.node_weight_n.iter().enumerate() {
            if w != 0.0 {
                let f = down * (case.self_weight * w);
                sums.node(n, f);
                let lever = targets.node_weight_lever_mm[n];
                if lever != DVec3::ZERO {
                    sums.moment(n, lever.cross(f));
                }
            }
        }
    }
    let g = case.surface_kn_per_m2 * N_PER_MM2_PER_KN_PER_M2;
    let s = case.snow_kn_per_m2 * N_PER_MM2_PER_KN_PER_M2;
    let p = case.wind_kn_per_m2 * N_PER_MM2_PER_KN_PER_M2;
    if g != 0.0 || s != 0.0 || p != 0.0 {
        for (n, &a) in targets.tributary_mm2.iter().enumerate() {
            if a == DVec3::ZERO {
                continue;
            }
            let f = down * (g * a.length() + s * a.z.abs()) - a * p;
            sums.node(n, f);
        }
    }
    for (j, pl) in case.point_loads.iter().enumerate() {
        let Some(&n) = targets.node_ids.get(&pl.node) else {
            return Err(Error::input(
                &spec.source,
                Location::Field(format!("cases[{i}].point_loads[{j}].node")),
                format!("no joint `{}` in the network", pl.node),
            ));
        };
        sums.node(n, pl.force_kn * N_PER_KN);
    }
    for (j, ll) in case.line_loads.iter().enumerate() {
        let field = || Location::Field(format!("cases[{i}].line_loads[{j}].strip"));
        let Some(beams) = targets.strip_beams.get(&ll.strip) else {
            return Err(Error::input(
                &spec.source,
                field(),
                format!("no strip `{}` in the network", ll.strip),
            ));
        };
        if beams.is_empty() {
            return Err(Error::input(
                &spec.source,
                field(),
                format!("strip `{}` has no element in the frame model", ll.strip),
            ));
        }
        for &b in beams {
            if b >= model.beams.len() {
                return Err(Error::input(
                    &spec.source,
                    Location::File,
                    format!(
                        "the frame model's load targets give strip `{}` element {b} of {}",
                        ll.strip,
                        model.beams.len()
                    ),
                ));
            }
            sums.beam(b, ll.force_kn_per_m * N_PER_MM_PER_KN_PER_M);
        }
    }
    Ok(sums.into_set(&case.name))
}

/// The factored sum of `cases` (indices as in [`LoadSpec::cases`], so
/// `cases` is [`load_cases`]' result): the cases shared as its parts with
/// their factors ([`LoadSet::parts`]), none of their loads copied.
pub fn combine(cases: &[Arc<LoadSet>], spec: &CombinationSpec) -> Combination {
    let parts = spec
        .factors
        .iter()
        .filter_map(|&(i, factor)| Some((cases.get(i)?.clone(), factor)))
        .collect();
    Combination {
        loads: LoadSet {
            name: spec.name.clone(),
            parts,
            ..Default::default()
        },
        limit_state: spec.limit_state,
    }
}

/// The loads of `set` and its parts as one set of its own, factored:
/// loads at one node or element added up, sorted by index, the pressures
/// listed (as a script for another program wants a combination).
pub fn flattened(set: &LoadSet) -> LoadSet {
    let mut sums = Sums::default();
    set.for_each_node_load(|l, factor| {
        let e = slot(&mut sums.nodes, l.node);
        e.0 += l.force_n * factor;
        e.1 += l.moment_nmm * factor;
    });
    set.for_each_beam_load(|l, factor| sums.beam(l.beam, l.force_n_per_mm * factor));
    let mut flat = sums.into_set(&set.name);
    set.for_each_pressure(|p, factor| {
        flat.pressures.push(PressureLoad {
            n_per_mm: p.n_per_mm * factor,
            ..*p
        })
    });
    flat
}

/// The supports of `spec` on the model: every entry's selection of joints
/// with its kind, a later entry overriding an earlier one at a joint it
/// selects again; sorted by node. A selection that picks no joint, or an
/// unknown node id, is an error naming the field.
///
/// Kinds: fixed — all six degrees of freedom; pinned — ux, uy, uz; roller
/// — translation along its direction only: along a global axis as that
/// axis's flag, otherwise as [`Support::along`].
pub fn supports(
    spec: &LoadSpec,
    model: &FrameModel,
    targets: &LoadTargets,
) -> Result<Vec<Support>> {
    check_targets(spec, model, targets)?;
    let defaulted = spec.supports == SupportSpec::default_list();
    let mut held: BTreeMap<usize, SupportKind> = BTreeMap::new();
    for (i, entry) in spec.supports.iter().enumerate() {
        let picked: Vec<usize> = match &entry.at {
            Selection::Boundary => targets.boundary_nodes.clone(),
            Selection::Lowest { band_mm } => {
                let z = |n: usize| model.nodes_mm[n].z;
                let lowest = targets
                    .node_ids
                    .values()
                    .map(|&n| z(n))
                    .fold(f64::INFINITY, f64::min);
                let mut v: Vec<usize> = targets
                    .node_ids
                    .values()
                    .copied()
                    .filter(|&n| z(n) <= lowest + band_mm)
                    .collect();
                v.sort_unstable();
                v.dedup();
                v
            }
            Selection::Nodes(ids) => {
                let mut v = Vec::with_capacity(ids.len());
                for (j, id) in ids.iter().enumerate() {
                    match targets.node_ids.get(id) {
                        Some(&n) => v.push(n),
                        None => {
                            return Err(Error::input(
                                &spec.source,
                                Location::Field(format!("supports[{i}].nodes[{j}]")),
                                format!("no joint `{id}` in the network"),
                            ))
                        }
                    }
                }
                v
            }
        };
        if picked.is_empty() {
            let what = if defaulted {
                "the network has no boundary joint to pin (the default supports): give a `supports` section".to_string()
            } else {
                "selects no joint of the network".to_string()
            };
            return Err(Error::input(
                &spec.source,
                Location::Field(if defaulted {
                    "supports".into()
                } else {
                    format!("supports[{i}].at")
                }),
                what,
            ));
        }
        for n in picked {
            held.insert(n, entry.kind);
        }
    }
    Ok(held
        .into_iter()
        .map(|(node, kind)| support_of(node, kind))
        .collect())
}

fn support_of(node: usize, kind: SupportKind) -> Support {
    let t = true;
    let f = false;
    match kind {
        SupportKind::Fixed => Support {
            node,
            fixed: [t; 6],
            along: None,
        },
        SupportKind::Pinned => Support {
            node,
            fixed: [t, t, t, f, f, f],
            along: None,
        },
        SupportKind::Roller { direction: d } => {
            let comps = d.to_array();
            let axis = (0..3).find(|&k| (0..3).all(|m| m == k || comps[m] == 0.0));
            match axis {
                Some(k) => {
                    let mut fixed = [f; 6];
                    fixed[k] = t;
                    Support {
                        node,
                        fixed,
                        along: None,
                    }
                }
                None => Support {
                    node,
                    fixed: [f; 6],
                    along: Some(d),
                },
            }
        }
    }
}

/// The span the deflection limit divides, mm: the largest plan (x–y)
/// distance between two supported nodes; where every support stands on one
/// vertical (a cantilever, or a single support), twice the largest plan
/// distance from it to any node of the model. 0 without supports.
pub fn deflection_span_mm(model: &FrameModel, supports: &[Support]) -> f64 {
    let plan: Vec<glam::DVec2> = supports
        .iter()
        .filter_map(|s| model.nodes_mm.get(s.node))
        .map(|p| p.truncate())
        .collect();
    let mut span: f64 = 0.0;
    for (k, a) in plan.iter().enumerate() {
        for b in &plan[k + 1..] {
            span = span.max(a.distance(*b));
        }
    }
    /// Below this, supports stand on one vertical, mm.
    const ONE_POINT_MM: f64 = 1e-6;
    if span <= ONE_POINT_MM {
        if let Some(a) = plan.first() {
            span = 2.0
                * model
                    .nodes_mm
                    .iter()
                    .map(|p| p.truncate().distance(*a))
                    .fold(0.0, f64::max);
        }
    }
    span
}

/// The SLS deflection limit, mm: `limit_mm` as given, or
/// [`deflection_span_mm`] / `span_over`.
pub fn deflection_limit_mm(spec: &LoadSpec, model: &FrameModel, supports: &[Support]) -> f64 {
    match spec.deflection {
        Deflection::LimitMm(d) => d,
        Deflection::SpanOver(n) => deflection_span_mm(model, supports) / n,
    }
}
