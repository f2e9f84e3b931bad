//! plan.json, schema `lamella-plan/2`: the single source of truth every later
//! output is drawn from. Later stages add fields; they never rename these.
//! Numbers are rounded to fixed precision so the file is byte-stable.

use crate::analysis::model::Model;
use crate::analysis::Analysis;
use crate::check::{CheckReport, LamellaCheck, StripCheck, Suggestion};
use crate::error::{Error, Result};
use crate::io::profile_file::JointSystem;
use crate::network::Network;
use crate::profile::Profile;
use serde::{Deserialize, Serialize};
use std::path::Path;

pub const SCHEMA: &str = "lamella-plan/2";

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Plan {
    pub schema: String,
    pub generator: String,
    pub units: String,
    pub network: NetworkSummary,
    pub summary: Summary,
    pub strips: Vec<PlanStrip>,
    pub nodes: Vec<PlanNode>,
    pub warnings: Vec<PlanWarning>,
    /// The resolved material profile (added by `check`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<PlanProfile>,
    /// The elastic check's verdict (added by `check`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub check: Option<PlanCheckSummary>,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanProfile {
    pub name: String,
    pub source: String,
    pub material: String,
    pub thickness_mm: f64,
    pub height_mm: f64,
    pub lamellas_per_strip: u32,
    pub gap_mm: f64,
    pub youngs_modulus_mpa: f64,
    pub shear_modulus_mpa: f64,
    pub characteristic_strength_mpa: f64,
    pub partial_factor: f64,
    pub modification_factor: f64,
    pub design_strength_mpa: f64,
    pub joint_system: String,
    pub level_offset_mm: f64,
    /// The whole profile as read (every field, for later stages).
    pub resolved: serde_json::Value,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanCheckSummary {
    pub passes: bool,
    pub strips_overstressed: usize,
    pub max_utilization: f64,
    /// The profile's limits: bending radius in pure bending, twist in pure twist.
    pub limit_bending_radius_mm: f64,
    pub limit_twist_deg_per_m: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub suggestion: Option<PlanSuggestion>,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanSuggestion {
    pub max_thickness_mm: Option<f64>,
    pub max_height_mm: Option<f64>,
    pub height_mm_with_thickness_mm: Option<[f64; 2]>,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanStress {
    pub utilization: f64,
    /// On the lamella's own line.
    pub governing_station_mm: f64,
    pub bending_stress_mpa: f64,
    pub torsion_shear_mpa: f64,
    pub trapeze_stress_mpa: f64,
    pub combined_stress_mpa: f64,
    /// bending, torsion or trapeze.
    pub governs: String,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanStripCheck {
    /// The worst lamella's number.
    pub lamella: u32,
    #[serde(flatten)]
    pub stress: PlanStress,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanWarning {
    /// near_tangent, overlap, close_nodes or isolated_curve.
    pub kind: String,
    pub message: String,
    /// Ids of the curves concerned.
    pub curves: Vec<String>,
    /// Station on the first curve, where the warning has one.
    pub station_mm: Option<f64>,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanLamella {
    pub lamella: u32,
    pub dy_mm: f64,
    pub dz_mm: f64,
    pub length_mm: f64,
    /// The strip's nodes at their stations on this lamella's own line.
    pub nodes: Vec<PlanLamellaNode>,
    /// The elastic check of this lamella (added by `check`).
    #[serde(flatten, default, skip_serializing_if = "Option::is_none")]
    pub checked: Option<PlanLamellaCheck>,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanLamellaNode {
    pub node: usize,
    pub station_mm: f64,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanLamellaCheck {
    pub min_bending_radius_mm: Option<f64>,
    pub max_twist_deg_per_m: f64,
    pub check: PlanStress,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct NetworkSummary {
    pub name: String,
    /// The file name (not the full path, so plans are portable).
    pub source: String,
    pub file_units: String,
    pub tolerance_mm: f64,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Summary {
    pub curves: usize,
    pub nodes: usize,
    pub total_length_mm: f64,
    pub shortest_node_to_node_mm: Option<f64>,
    pub longest_node_to_node_mm: Option<f64>,
    pub max_normal_curvature_per_m: f64,
    pub min_angle_deg: Option<f64>,
    pub max_angle_deg: Option<f64>,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanStrip {
    pub id: String,
    pub family: String,
    pub length_mm: f64,
    pub nodes: Vec<PlanStripNode>,
    /// Lengths between consecutive nodes.
    pub node_to_node_mm: Vec<f64>,
    /// From the strip's start to its first node, and from its last node to its end.
    pub start_to_first_node_mm: Option<f64>,
    pub last_node_to_end_mm: Option<f64>,
    /// None for a straight strip.
    pub min_bending_radius_mm: Option<f64>,
    pub max_twist_deg_per_m: f64,
    pub max_normal_curvature_per_m: f64,
    /// Where the surface normals came from: file, binormal, binormal+nodes, nodes.
    pub normals: String,
    /// The worst lamella's elastic check (added by `check`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub check: Option<PlanStripCheck>,
    /// Every lamella on its own offset line (A and B strips): the centre line
    /// without a profile, the profile's lamellas with `check`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lamellas: Option<Vec<PlanLamella>>,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanStripNode {
    pub node: usize,
    /// Id of the crossing curve.
    pub crossing: String,
    pub station_mm: f64,
    pub angle_deg: f64,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanNode {
    pub id: usize,
    /// The A curve (or the B curve of a B×edge node).
    pub a: String,
    /// The B curve (or the edge curve).
    pub b: String,
    pub station_a_mm: f64,
    pub station_b_mm: f64,
    pub position_mm: [f64; 3],
    pub normal: [f64; 3],
    pub angle_deg: f64,
    /// From A's tangent line to B's, counter-clockwise about the normal, [0, 180).
    pub oriented_angle_deg: f64,
    pub gap_mm: f64,
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
/// Nothing is computed here (see [`crate::analysis::model`]).
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
    let strips: Vec<PlanStrip> = an
        .strips
        .iter()
        .zip(&model.strips)
        .zip(&checks)
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
        .iter()
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
            Some(plan_profile(&c.profile)),
            Some(plan_check(&c.report, c.suggestion.as_ref())),
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
    }
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

fn plan_profile(p: &Profile) -> PlanProfile {
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
        resolved: serde_json::to_value(p.resolved()).unwrap_or(serde_json::Value::Null),
    }
}

fn plan_check(report: &CheckReport, suggestion: Option<&Suggestion>) -> PlanCheckSummary {
    PlanCheckSummary {
        passes: report.passes(),
        strips_overstressed: report.overstressed(),
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

/// Serialise a plan (pretty JSON, trailing newline).
pub fn to_json(plan: &Plan) -> String {
    let mut s =
        serde_json::to_string_pretty(plan).unwrap_or_else(|e| format!("{{\"error\":\"{e}\"}}"));
    s.push('\n');
    s
}

/// Write `contents` to `path` atomically: a temporary file beside it, then a
/// rename, so a failure never leaves half a file.
pub fn write_atomic(path: &Path, contents: &[u8]) -> Result<()> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if dir.exists() && !dir.is_dir() {
        return Err(Error::io(
            dir,
            std::io::Error::other("is a file, not a directory: choose another output directory"),
        ));
    }
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = dir.join(format!(".{name}.lamella-tmp"));
    std::fs::write(&tmp, contents).map_err(|e| Error::io(&tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        Error::io(path, e)
    })
}
