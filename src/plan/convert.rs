//! From the stages' outputs to the plan: ids for indices, numbers rounded
//! to fixed decimals. Nothing is computed here that a stage could compute
//! (the finished model is [`super::model::Model`]).

use super::*;
use crate::analysis::Analysis;
use crate::check::{CheckReport, LamellaCheck, StripCheck, Suggestion};
use crate::network::Network;
use crate::plan::model::Model;
use crate::profile::{JointSystem, Profile};
use rayon::prelude::*;
use std::path::Path;

/// Add the flat state to a plan.
pub fn add_flat(plan: &mut Plan, pr: &crate::flat::FlatProblem, st: &crate::flat::FlatState) {
    plan.flat = Some(PlanFlat {
        converged: st.converged,
        iterations: st.iterations,
        energy: round(st.energy_nmm, 6),
        start_energy: round(st.start_energy_nmm, 6),
        gradient_norm: st.gradient_norm,
        max_length_error: st.max_length_error,
        max_rotation_deg: round(
            st.max_rotation()
                .map_or(0.0, |i| st.nodes[i].rotation_deg.abs()),
            DEG,
        ),
        footprint_mm: [round(st.footprint_mm[0], MM), round(st.footprint_mm[1], MM)],
        nodes: st
            .nodes
            .iter()
            .map(|n| PlanFlatNode {
                node: n.node,
                position_mm: [round(n.position_mm[0], MM), round(n.position_mm[1], MM)],
                angle_deg: round(n.angle_deg, DEG),
                rotation_deg: round(n.rotation_deg, DEG),
                angle_range_deg: {
                    let (a, b) = (n.angle_deg, n.angle_deg + n.rotation_deg);
                    [round(a.min(b), DEG), round(a.max(b), DEG)]
                },
            })
            .collect(),
        strips: st
            .strips
            .iter()
            .map(|s| PlanFlatStrip {
                strip: s.strip.clone(),
                max_bending_stress_mpa: round(s.max_bending_stress_mpa, MPA),
                utilization: round(s.utilization, UTIL),
            })
            .collect(),
        drawing: FlatDrawing {
            strips: pr
                .strips
                .iter()
                .map(|s| FlatDrawingStrip {
                    id: s.id.clone(),
                    family_a: s.family == crate::network::Family::A,
                    nodes: s.nodes.clone(),
                    lengths_mm: s.lengths_mm.clone(),
                })
                .collect(),
            nodes: st
                .nodes
                .iter()
                .map(|n| FlatDrawingNode {
                    node: n.node,
                    position_mm: n.position_mm,
                    rotation_deg: n.rotation_deg,
                })
                .collect(),
        },
    });
}

/// Round to `decimals` places (and drop negative zero) for stable output.
pub fn round(x: f64, decimals: i32) -> f64 {
    let f = 10f64.powi(decimals);
    let r = (x * f).round() / f;
    if r == 0.0 {
        0.0
    } else {
        r
    }
}

const MM: i32 = 4;

const DEG: i32 = 6;

const CURV: i32 = 6;

fn v3(v: glam::DVec3, d: i32) -> [f64; 3] {
    [round(v.x, d), round(v.y, d), round(v.z, d)]
}

/// Format a finished model as a plan: ids for indices, rounded numbers.
/// Nothing is computed here (see [`crate::analysis::lines`]).
pub fn build(net: &Network, an: &Analysis, model: &Model) -> Plan {
    let per_m = 1000.0;
    let id = |i: usize| net.curves[i].id.clone();
    let checks: Vec<Option<&StripCheck>> = {
        let mut v = vec![None; an.strips.len()];
        if let Some(c) = &model.check {
            for sc in &c.report.strips {
                v[sc.strip] = Some(sc);
            }
        }
        v
    };
    // Strips and nodes formatted in parallel (in order).
    let strips: Vec<PlanStrip> = an
        .strips
        .par_iter()
        .zip(model.strips.par_iter())
        .zip(checks.par_iter())
        .map(|((s, m), sc)| {
            let nodes = s
                .nodes
                .iter()
                .map(|cn| PlanStripNode {
                    node: cn.node,
                    crossing: id(cn.crossing),
                    station_mm: round(cn.station_mm, MM),
                    angle_deg: round(an.topology.nodes[cn.node].angle_deg, DEG),
                })
                .collect();
            let lamellas: Vec<PlanLamella> = m
                .lamellas
                .iter()
                .enumerate()
                .map(|(k, line)| PlanLamella {
                    lamella: line.offset.number,
                    dy_mm: round(line.offset.dy_mm, MM),
                    dz_mm: round(line.offset.dz_mm, MM),
                    length_mm: round(line.length_mm, MM),
                    nodes: line
                        .nodes
                        .iter()
                        .map(|n| PlanLamellaNode {
                            node: n.node,
                            station_mm: round(n.station_mm, MM),
                        })
                        .collect(),
                    checked: sc
                        .and_then(|sc| sc.lamellas.get(k))
                        .map(|l| PlanLamellaCheck {
                            min_bending_radius_mm: l.min_bending_radius_mm.map(|r| round(r, MM)),
                            max_twist_deg_per_m: round(l.max_twist_deg_per_m, DEG),
                            sagitta_mm: round(l.sagitta_mm, MM),
                            check: plan_stress(l),
                        }),
                })
                .collect();
            PlanStrip {
                id: s.id.clone(),
                family: s.family.as_str().to_string(),
                length_mm: round(s.length_mm, MM),
                nodes,
                node_to_node_mm: m.node_to_node_mm.iter().map(|&l| round(l, MM)).collect(),
                start_to_first_node_mm: m.start_to_first_node_mm.map(|x| round(x, MM)),
                last_node_to_end_mm: m.last_node_to_end_mm.map(|x| round(x, MM)),
                min_bending_radius_mm: s.min_bending_radius_mm().map(|r| round(r, MM)),
                max_twist_deg_per_m: round(s.max_abs_tg_per_mm.to_degrees() * per_m, DEG),
                max_normal_curvature_per_m: round(s.max_abs_kn_per_mm * per_m, CURV),
                normals: s.normal_source.as_str().to_string(),
                check: sc.map(|sc| {
                    let worst = sc.worst();
                    PlanStripCheck {
                        lamella: worst.line.offset.number,
                        sagitta_mm: round(sc.sagitta_mm(), MM),
                        stress: plan_stress(worst),
                    }
                }),
                lamellas: (!lamellas.is_empty()).then_some(lamellas),
            }
        })
        .collect();
    let nodes: Vec<PlanNode> = an
        .topology
        .nodes
        .par_iter()
        .map(|n| PlanNode {
            id: n.id,
            a: id(n.a),
            b: id(n.b),
            station_a_mm: round(n.station_a_mm, MM),
            station_b_mm: round(n.station_b_mm, MM),
            position_mm: v3(n.position_world_mm, MM),
            normal: v3(n.normal_world, 7),
            angle_deg: round(n.angle_deg, DEG),
            oriented_angle_deg: round(n.oriented_angle_deg, DEG),
            gap_mm: round(n.gap_mm, MM),
            joint: String::new(),
        })
        .collect();
    let sm = &model.summary;
    let summary = Summary {
        curves: sm.curves,
        nodes: sm.nodes,
        total_length_mm: round(sm.total_length_mm, MM),
        shortest_node_to_node_mm: sm.shortest_node_to_node_mm.map(|x| round(x, MM)),
        longest_node_to_node_mm: sm.longest_node_to_node_mm.map(|x| round(x, MM)),
        max_normal_curvature_per_m: round(sm.max_normal_curvature_per_mm * per_m, CURV),
        min_angle_deg: sm.min_angle_deg.map(|x| round(x, DEG)),
        max_angle_deg: sm.max_angle_deg.map(|x| round(x, DEG)),
    };
    let warnings = an
        .warnings()
        .iter()
        .map(|w| PlanWarning {
            kind: w.kind.as_str().into(),
            message: w.message.clone(),
            curves: w.curves.iter().map(|&c| id(c)).collect(),
            station_mm: w.station_mm.map(|x| round(x, MM)),
        })
        .collect();
    let (profile, check) = match &model.check {
        Some(c) => (
            Some(plan_profile(c.profile, c.resolved)),
            Some(plan_check(c.report, c.suggestion)),
        ),
        None => (None, None),
    };
    Plan {
        schema: SCHEMA.into(),
        generator: format!("lamella {}", env!("CARGO_PKG_VERSION")),
        units: "mm".into(),
        network: NetworkSummary {
            name: net.name.clone(),
            source: file_name(&net.source),
            file_units: net.file_unit.as_str().into(),
            tolerance_mm: round(net.tolerance_mm, MM),
        },
        summary,
        strips,
        nodes,
        warnings,
        profile,
        check,
        parts: None,
        parts_summary: None,
        engraving_font: None,
        sheets: None,
        nesting: None,
        flat: None,
        structure: None,
        curves: Vec::new(),
        takeoff: None,
        shape: None,
        joints: Vec::new(),
    }
}

/// Add a nest to a plan (formatting only).
pub fn add_nest(plan: &mut Plan, kit: &crate::fabricate::Kit, nest: &crate::nest::Nest) {
    let stock_use = |u: &crate::nest::StockUse| PlanStockUse {
        stock: u.stock.clone(),
        sheets: u.sheets,
        width_mm: round(u.width_mm, MM),
        length_mm: round(u.length_mm, MM),
        price_per_unit: u.price_per_unit.map(money),
        cost: u.cost.map(money),
    };
    plan.sheets = Some(
        nest.sheets
            .iter()
            .enumerate()
            .map(|(k, s)| PlanSheet {
                id: s.id.clone(),
                width_mm: round(s.width_mm, MM),
                length_mm: round(s.length_mm, MM),
                utilization: round(s.utilization(), 6),
                stock: s.stock.clone(),
                group: nest.groups[nest.group_of_sheet(k)].name.clone(),
                material: nest.groups[nest.group_of_sheet(k)].material.clone(),
                thickness_mm: round(nest.groups[nest.group_of_sheet(k)].thickness_mm, MM),
                form: nest.groups[nest.group_of_sheet(k)].form.as_str().into(),
                price_per_unit: s.price_per_unit.map(money),
                placements: s
                    .placements
                    .iter()
                    .map(|p| PlanPlacement {
                        part: kit.parts[p.part].id.clone(),
                        copy: p.copy,
                        x_mm: round(p.x_mm, MM),
                        y_mm: round(p.y_mm, MM),
                        rotation_deg: p.rotation_deg,
                    })
                    .collect(),
            })
            .collect(),
    );
    let n = &nest.summary;
    plan.nesting = Some(PlanNesting {
        sheets_used: n.sheets_used,
        lower_bound_sheets: n.lower_bound_sheets,
        area_bound_sheets: n.area_bound_sheets,
        lane_bound_sheets: n.lane_bound_sheets,
        lanes_per_sheet: n.lanes_per_sheet,
        lanes_used: n.lanes_used,
        lane_bound_lanes: n.lane_bound_lanes,
        utilization: round(n.utilization, 6),
        stock_used: nest.stock_used.iter().map(stock_use).collect(),
        total_cost: n.cost.map(money),
        cost_bound: n.cost_bound.map(money),
        currency: nest.currency.clone(),
        coil_length_mm: n.length_used_mm.map(|x| round(x, MM)),
        coil_length_bound_mm: n.length_bound_mm.map(|x| round(x, MM)),
        groups: nest
            .groups
            .iter()
            .map(|g| {
                let mut kinds: Vec<&str> = nest.sheets[g.sheets.clone()]
                    .iter()
                    .flat_map(|s| s.placements.iter())
                    .map(|pl| kit.parts[pl.part].kind)
                    .collect::<std::collections::BTreeSet<_>>()
                    .into_iter()
                    .map(|k| k.as_str())
                    .collect();
                kinds.dedup();
                let ids = &nest.sheets[g.sheets.clone()];
                PlanGroupNesting {
                    group: g.name.clone(),
                    material: g.material.clone(),
                    thickness_mm: round(g.thickness_mm, MM),
                    form: g.form.as_str().into(),
                    kinds: kinds.into_iter().map(String::from).collect(),
                    sheet_ids: ids
                        .first()
                        .into_iter()
                        .chain(ids.last())
                        .map(|s| s.id.clone())
                        .collect(),
                    sheets_used: g.summary.sheets_used,
                    lower_bound_sheets: g.summary.lower_bound_sheets,
                    area_bound_sheets: g.summary.area_bound_sheets,
                    lane_bound_sheets: g.summary.lane_bound_sheets,
                    utilization: round(g.summary.utilization, 6),
                    stock_used: g.stock_used.iter().map(stock_use).collect(),
                    total_cost: g.summary.cost.map(money),
                    cost_bound: g.summary.cost_bound.map(money),
                }
            })
            .collect(),
    });
}

/// A price rounded to 1e-4 of its unit (cents and below stay exact).
fn money(x: f64) -> f64 {
    round(x, 4)
}

/// Add a kit's parts to a plan (formatting only: rounding to 1e-4 mm).
pub fn add_parts(plan: &mut Plan, kit: &crate::fabricate::Kit, profile: &Profile) {
    set_parts(plan, plan_parts(kit), kit, profile);
}

/// The font entry of every character and mark the parts engrave.
fn engraving_font(parts: &[PlanPart]) -> PlanFont {
    use crate::fabricate::font;
    let glyph = |width: f64, strokes: Vec<Vec<kurbo::Point>>| PlanGlyph {
        width,
        strokes: strokes
            .iter()
            .map(|s| s.iter().map(|p| [p.x, p.y]).collect())
            .collect(),
    };
    let mut chars = std::collections::BTreeSet::new();
    let mut marks = std::collections::BTreeMap::new();
    for e in parts.iter().flat_map(|p| &p.engraving) {
        chars.extend(e.text.iter().flat_map(|t| t.chars()));
        if e.mark.as_deref() == Some(ORIENTATION_MARK) && marks.is_empty() {
            marks.insert(
                ORIENTATION_MARK.to_string(),
                glyph(
                    font::ORIENTATION_MARK_LENGTH,
                    font::orientation_mark_strokes(1.0),
                ),
            );
        }
    }
    let glyphs = chars
        .into_iter()
        .map(|c| {
            (
                c.to_string(),
                glyph(font::glyph_width(c), font::glyph_strokes(c)),
            )
        })
        .collect();
    PlanFont {
        name: font::NAME.into(),
        letter_spacing: font::LETTER_SPACING,
        glyphs,
        marks,
    }
}

/// Every part of `kit` as plan.json writes it, in order (converted in
/// parallel; the kit is left as it is).
pub fn plan_parts(kit: &crate::fabricate::Kit) -> Vec<PlanPart> {
    use rayon::prelude::*;
    kit.parts.par_iter().map(plan_part).collect()
}

/// Put `parts` (from [`plan_parts`] of `kit`) into the plan, each with
/// its stock group of `profile`, and the engraving font and the kit's
/// summary: what [`add_parts`] does.
pub fn set_parts(
    plan: &mut Plan,
    mut parts: Vec<PlanPart>,
    kit: &crate::fabricate::Kit,
    profile: &Profile,
) {
    let groups = profile.stock_groups();
    for (part, made) in parts.iter_mut().zip(&kit.parts) {
        if let Some(g) = groups.get(Profile::group_of(&groups, made.kind.piece())) {
            part.group = g.name.clone();
            part.material = g.material.clone();
            part.thickness_mm = round(g.thickness_mm, MM);
        }
    }
    plan.parts = Some(parts);
    add_kit_summary(plan, kit);
    add_joints(plan);
}

/// Name each node's joint ([`PlanNode::joint`]) from the profile's joint
/// system and the parts made: the star washer's class of the node's
/// (rounded) angle where the kit has washers, a stud where it has studs.
fn add_joints(plan: &mut Plan) {
    use crate::fabricate::washer::{angle_class_deg, washer_id};
    let system = plan
        .profile
        .as_ref()
        .map(|p| p.joint_system.as_str())
        .unwrap_or("");
    let has = |kind: &str| {
        plan.parts
            .as_ref()
            .is_some_and(|p| p.iter().any(|q| q.kind == kind))
    };
    let (washers, studs) = (has("washer"), has("stud"));
    let family: std::collections::HashMap<&str, &str> = plan
        .strips
        .iter()
        .map(|s| (s.id.as_str(), s.family.as_str()))
        .collect();
    // Edge nodes with a hole in their band: bolted; the others slotted.
    let bolted: std::collections::HashSet<usize> = plan
        .parts
        .iter()
        .flatten()
        .flat_map(|q| &q.features)
        .filter(|f| f.hole_use == Some(PlanHoleUse::EdgeNode))
        .filter_map(|f| f.node)
        .collect();
    let joints: Vec<String> = plan
        .nodes
        .iter()
        .map(|n| {
            let grid =
                family.get(n.a.as_str()) == Some(&"A") && family.get(n.b.as_str()) == Some(&"B");
            if !grid {
                if bolted.contains(&n.id) {
                    "edge bolt".to_string()
                } else {
                    "edge slot".to_string()
                }
            } else if washers {
                washer_id(angle_class_deg(n.angle_deg))
            } else if studs {
                "ST".to_string()
            } else if system == "interlocking" {
                "slots".to_string()
            } else {
                "bolt".to_string()
            }
        })
        .collect();
    for (n, j) in plan.nodes.iter_mut().zip(joints) {
        n.joint = j;
    }
}

/// Add the network's curves (their points, world frame) for the drawings
/// of the whole grid.
pub fn add_curves(plan: &mut Plan, curves: Vec<crate::network::Curve>) {
    plan.curves = curves
        .into_iter()
        .map(|c| PlanCurve {
            id: c.id,
            points_mm: c.points_world_mm.iter().map(|p| [p.x, p.y, p.z]).collect(),
        })
        .collect();
}

/// Add the material takeoff of the kit as nested.
pub fn add_takeoff(
    plan: &mut Plan,
    kit: &crate::fabricate::Kit,
    nest: &crate::nest::Nest,
    profile: &Profile,
) {
    let mut takeoff = super::takeoff::takeoff(&plan.network.name, kit, nest, profile);
    if let Some(b) = plan.structure.as_ref().and_then(|s| s.bracing.as_ref()) {
        takeoff.bracing = b.takeoff_lines();
    }
    plan.takeoff = Some(takeoff);
    let hardware = super::takeoff::hardware_lines(kit);
    let edge_nodes = kit.parts.iter().any(|p| {
        p.features
            .iter()
            .any(|f| f.edge == Some(crate::fabricate::part::SlotEdge::End))
    });
    plan.joints = super::joints::joints(profile, &hardware, edge_nodes);
}

/// One part as plan.json writes it (rounded); its round holes only as
/// its `hole` features.
fn plan_part(p: &crate::fabricate::part::Part) -> PlanPart {
    use crate::fabricate::part::{round_hole, Engraved, FeatureKind, HoleUse, SlotEdge};
    let pt = |p: &kurbo::Point| [round(p.x, MM), round(p.y, MM)];
    let poly = |v: &[kurbo::Point]| v.iter().map(pt).collect::<Vec<_>>();
    PlanPart {
        id: p.id.clone(),
        kind: p.kind.as_str().into(),
        group: String::new(),
        material: String::new(),
        thickness_mm: 0.0,
        strip: p.strip.clone(),
        lamella: p.lamella,
        count: p.count,
        length_mm: round(p.length_mm, MM),
        height_mm: round(p.height_mm, MM),
        station_start_mm: p.station_start_mm.map(|s| round(s, MM)),
        outline: poly(&p.outline_part_mm),
        holes: p
            .holes_part_mm
            .iter()
            .filter(|h| round_hole(p, h).is_none())
            .map(|h| poly(h))
            .collect(),
        engraving: p
            .engraving
            .iter()
            .map(|e| {
                let (text, mark) = match &e.what {
                    Engraved::Text(t) => (Some(t.clone()), None),
                    Engraved::OrientationMark => (None, Some(ORIENTATION_MARK.into())),
                };
                PlanEngraving {
                    text,
                    mark,
                    at_mm: pt(&e.at_part_mm),
                    height_mm: round(e.height_mm, MM),
                }
            })
            .collect(),
        features: p
            .features
            .iter()
            .map(|f| PlanFeature {
                kind: match f.kind {
                    FeatureKind::Slot => PlanFeatureKind::Slot,
                    FeatureKind::Hole => PlanFeatureKind::Hole,
                },
                hole_use: f.hole_use.map(|u| match u {
                    HoleUse::Node => PlanHoleUse::Node,
                    HoleUse::ShearBlock => PlanHoleUse::ShearBlock,
                    HoleUse::Splice => PlanHoleUse::Splice,
                    HoleUse::EdgeNode => PlanHoleUse::EdgeNode,
                    HoleUse::CablePin => PlanHoleUse::CablePin,
                }),
                node: f.node,
                crossing: f.crossing.clone(),
                center_mm: pt(&f.center_part_mm),
                width_mm: round(f.width_mm, MM),
                depth_mm: round(f.depth_mm, MM),
                edge: f.edge.map(|e| match e {
                    SlotEdge::Top => PlanSlotEdge::Top,
                    SlotEdge::Bottom => PlanSlotEdge::Bottom,
                    SlotEdge::End => PlanSlotEdge::End,
                }),
                angle_range_deg: f
                    .angle_range_deg
                    .map(|(a, b)| [round(a, DEG), round(b, DEG)]),
                station_mm: f
                    .station_mm
                    .map(|s| round(s - p.station_start_mm.unwrap_or(0.0), MM)),
                line_station_mm: f.station_mm.map(|s| round(s, MM)),
            })
            .collect(),
    }
}

fn add_kit_summary(plan: &mut Plan, kit: &crate::fabricate::Kit) {
    plan.engraving_font = plan.parts.as_deref().map(engraving_font);
    plan.parts_summary = Some(PlanKitSummary {
        kinds: kit
            .summary
            .kinds
            .iter()
            .map(|&(k, parts, count)| PlanKindCount {
                kind: k.as_str().into(),
                parts,
                count,
            })
            .collect(),
        lamella_length_mm: round(kit.summary.lamella_length_mm, MM),
        mass_kg: round(kit.summary.mass_kg, 3),
        hardware: super::takeoff::hardware_lines(kit),
    });
}

fn file_name(p: &Path) -> String {
    p.file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

const MPA: i32 = 4;

const UTIL: i32 = 6;

fn plan_stress(l: &LamellaCheck) -> PlanStress {
    PlanStress {
        utilization: round(l.utilization, UTIL),
        governing_station_mm: round(l.governing_station_mm, MM),
        bending_stress_mpa: round(l.stresses.bending_stress_mpa, MPA),
        torsion_shear_mpa: round(l.stresses.torsion_shear_mpa, MPA),
        trapeze_stress_mpa: round(l.stresses.trapeze_stress_mpa, MPA),
        combined_stress_mpa: round(l.stresses.combined_stress_mpa, MPA),
        governs: l.governs.as_str().into(),
    }
}

fn plan_profile(p: &Profile, resolved: &serde_json::Value) -> PlanProfile {
    PlanProfile {
        name: p.name.clone(),
        source: file_name(&p.source),
        material: p.material.name.clone(),
        thickness_mm: p.section.thickness_mm,
        height_mm: p.section.height_mm,
        lamellas_per_strip: p.section.per_strip,
        gap_mm: p.section.gap_mm,
        youngs_modulus_mpa: p.material.youngs_modulus_mpa,
        shear_modulus_mpa: p.material.shear_modulus_mpa,
        characteristic_strength_mpa: p.material.characteristic_strength_mpa,
        partial_factor: p.material.partial_factor,
        modification_factor: p.material.modification_factor,
        design_strength_mpa: round(p.design_strength_mpa(), MPA),
        joint_system: match p.joint.system {
            JointSystem::Interlocking => "interlocking".into(),
            JointSystem::TwoLevel => "two_level".into(),
        },
        level_offset_mm: p.joint.level_offset_mm,
        resolved: resolved.clone(),
    }
}

fn plan_check(report: &CheckReport, suggestion: Option<&Suggestion>) -> PlanCheckSummary {
    PlanCheckSummary {
        passes: report.passes(),
        strips_overstressed: report.overstressed(),
        strips_bowed: report.bowed(),
        max_sagitta_mm: round(report.most_bowed().map_or(0.0, StripCheck::sagitta_mm), MM),
        limit_sagitta_mm: round(report.limit_sagitta_mm, MM),
        max_utilization: round(report.max_utilization(), UTIL),
        limit_bending_radius_mm: round(report.limit_bending_radius_mm, MM),
        limit_twist_deg_per_m: round(report.limit_twist_deg_per_m, DEG),
        suggestion: suggestion.map(|s| PlanSuggestion {
            max_thickness_mm: s.max_thickness_mm.map(|x| round(x, MM)),
            max_height_mm: s.max_height_mm.map(|x| round(x, MM)),
            height_mm_with_thickness_mm: s
                .height_and_thickness_mm
                .map(|(h, t)| [round(h, MM), round(t, MM)]),
        }),
    }
}
