//! Star washers (docs/fabrication.md, "Joints"): at every A×B node of an
//! interlocking grid whose profile has a `washer`, a star of four arms that
//! lie along the two strips, each arm in the gap between the two lamellas of
//! its strip; tightened by the node bolt, it fixes the crossing angle.
//!
//! Geometry, in the washer's own frame (centre at the origin): arms along
//! the directions 0°, φ, 180° and 180° + φ, φ the node's acute crossing
//! angle; each arm a bar `arm_width_mm` (w) wide whose square tip lies
//! `arm_length_mm` (L) from the centre. The outline is the union of the two
//! bars, exactly: 12 vertices, the two tip corners of each arm and one
//! re-entrant corner between neighbouring arms, on their bisector at
//! (w/2)/sin(α/2) from the centre (α = φ or 180° − φ, the angle between the
//! two arms). That corner lies (w/2)/tan(α/2) along each of the two arms;
//! the union is this star only while that is short of the tip, L.
//! The central hole (bolt diameter + hole clearance) must leave both sides
//! of every arm standing: its diameter is below the arm width.
//!
//! Washers are grouped into angle classes: nodes whose acute angle rounds to
//! the same 0.5° share one part (`W90`, `W87.5`, …), drawn at the class
//! angle; `count` = nodes × `per_node`. Classes come by descending angle.
//!
//! Part frame: the star is shifted so that its outline's bounding box starts
//! at the origin (x from 0 to `length_mm`, y from 0 to `height_mm`); arm 0
//! points along +x from the hole's centre. Engraving stays empty (labels are
//! added later).

use crate::analysis::Analysis;
use crate::error::{Error, Result};
use crate::fabricate::part::{Feature, FeatureKind, HoleUse, Part, PartKind};
use crate::geom::plane::bounds;
use crate::network::Family;
use crate::profile::{JointSystem, Profile};
use kurbo::{Point, Vec2};
use std::collections::BTreeMap;

/// An A×B node as the washer and stud builders see it: plain data taken
/// from the topology and the strips.
#[derive(Debug, Clone, PartialEq)]
pub struct GridNode {
    /// The node's id (its plan.json id).
    pub id: usize,
    /// Id of its family-A strip.
    pub strip_a: String,
    /// Id of its family-B strip.
    pub strip_b: String,
    /// Acute crossing angle, degrees.
    pub angle_deg: f64,
}

/// The A×B nodes of an analysis, in topology order (A×edge and B×edge
/// nodes are left out).
pub fn grid_nodes(analysis: &Analysis) -> Vec<GridNode> {
    let strips = &analysis.strips;
    analysis
        .topology
        .nodes
        .iter()
        .filter(|n| {
            strips.get(n.a).map(|s| s.family) == Some(Family::A)
                && strips.get(n.b).map(|s| s.family) == Some(Family::B)
        })
        .map(|n| GridNode {
            id: n.id,
            strip_a: strips[n.a].id.clone(),
            strip_b: strips[n.b].id.clone(),
            angle_deg: n.angle_deg,
        })
        .collect()
}

/// The angle class of an acute angle: rounded to the nearest 0.5°, degrees.
pub fn angle_class_deg(angle_deg: f64) -> f64 {
    (angle_deg * 2.0).round() / 2.0
}

/// Part id of a washer class: `W` and the class angle (`W90`, `W87.5`).
pub fn washer_id(class_deg: f64) -> String {
    format!("W{class_deg}")
}

/// The star's outline in the washer frame (centre at the origin, arm 0
/// along +x), counter-clockwise, 12 vertices: for each arm (0°, φ, 180°,
/// 180° + φ) its two tip corners, then the re-entrant corner towards the
/// next arm. Valid (the exact union of the two bars) when
/// [`reentrant_reach_mm`] is below `arm_length_mm` for both neighbouring
/// angles; see [`washer_part`].
pub fn star_outline(angle_deg: f64, arm_length_mm: f64, arm_width_mm: f64) -> Vec<Point> {
    let phi = angle_deg.to_radians();
    let pi = std::f64::consts::PI;
    let arms = [0.0, phi, pi, pi + phi];
    let half_w = 0.5 * arm_width_mm;
    let mut out = Vec::with_capacity(12);
    for (i, &th) in arms.iter().enumerate() {
        let u = Vec2::new(th.cos(), th.sin());
        let n = Vec2::new(-th.sin(), th.cos());
        // Right tip corner, then left (counter-clockwise about the centre).
        out.push((u * arm_length_mm - n * half_w).to_point());
        out.push((u * arm_length_mm + n * half_w).to_point());
        let next = if i + 1 < arms.len() {
            arms[i + 1]
        } else {
            arms[0] + std::f64::consts::TAU
        };
        let alpha = next - th;
        let bisector = th + 0.5 * alpha;
        let d = half_w / (0.5 * alpha).sin();
        out.push(Point::new(d * bisector.cos(), d * bisector.sin()));
    }
    out
}

/// How far along each of two arms, `alpha_deg` apart, their re-entrant
/// corner lies from the centre: (w/2)/tan(α/2), mm.
pub fn reentrant_reach_mm(alpha_deg: f64, arm_width_mm: f64) -> f64 {
    0.5 * arm_width_mm / (0.5 * alpha_deg.to_radians()).tan()
}

/// One washer part of angle class `class_deg` (acute, degrees), `count`
/// times: the star outline, the bolt hole (clockwise) and a hole feature
/// ([`HoleUse::Node`], no node: the part is shared). No checks: see
/// [`washers`].
pub fn washer_part(
    class_deg: f64,
    arm_length_mm: f64,
    arm_width_mm: f64,
    hole_diameter_mm: f64,
    count: u32,
) -> Part {
    let star = star_outline(class_deg, arm_length_mm, arm_width_mm);
    let bbox = bounds(&star);
    let shift = Vec2::new(-bbox.x0, -bbox.y0);
    let centre = Point::ORIGIN + shift;
    Part {
        id: washer_id(class_deg),
        kind: PartKind::Washer,
        strip: None,
        lamella: None,
        count,
        length_mm: bbox.width(),
        height_mm: bbox.height(),
        station_start_mm: None,
        outline_part_mm: star.iter().map(|p| *p + shift).collect(),
        holes_part_mm: Vec::new(),
        engraving: Vec::new(),
        features: vec![Feature {
            kind: FeatureKind::Hole,
            hole_use: Some(HoleUse::Node),
            node: None,
            crossing: None,
            center_part_mm: centre,
            width_mm: hole_diameter_mm,
            depth_mm: 0.0,
            edge: None,
            angle_range_deg: None,
            station_mm: None,
        }],
    }
}

/// The star washers of a grid: one part per angle class (descending angle),
/// or none when the profile has no washer, its joint is not interlocking
/// (a two-level grid has studs instead) or the grid has no A×B node.
///
/// Errors (one line naming the profile, the strip and the node): a strip
/// without a gap wide enough for the arms (`arm_width_mm` > `gap_mm`, or
/// single lamellas), a bolt hole (bolt + hole clearance) as wide as an arm
/// or wider (it would cut the arm in two), and a node so acute that the
/// re-entrant corner of neighbouring arms lies at or beyond the arm tips.
pub fn washers(profile: &Profile, nodes: &[GridNode]) -> Result<Vec<Part>> {
    let Some(washer) = &profile.washer else {
        return Ok(Vec::new());
    };
    let Some(first) = nodes.first() else {
        return Ok(Vec::new());
    };
    if profile.joint.system != JointSystem::Interlocking {
        return Ok(Vec::new());
    }
    let fail = |n: &GridNode, what: String| {
        Err(Error::fabrication(
            &profile.source,
            &n.strip_a,
            Some(n.id),
            what,
        ))
    };
    let (w, l) = (washer.arm_width_mm, washer.arm_length_mm);
    let section = &profile.section;
    if section.per_strip < 2 {
        return fail(
            first,
            format!(
                "a washer's arms sit in the gap between a strip's two lamellas, \
                 but the strips are single (lamella.per_strip {})",
                section.per_strip
            ),
        );
    }
    if w > section.gap_mm {
        return fail(
            first,
            format!(
                "washer arms {w} mm wide do not fit the {} mm gap between the lamellas",
                section.gap_mm
            ),
        );
    }
    // The validated profile has a node bolt whenever it has a washer.
    let hole_mm = profile
        .node_bolt
        .as_ref()
        .map_or(0.0, |b| b.diameter_mm + b.hole_clearance_mm);
    if hole_mm >= w {
        return fail(
            first,
            format!("the {hole_mm} mm bolt hole cuts the {w} mm wide washer arms in two"),
        );
    }
    let mut classes: BTreeMap<i64, u32> = BTreeMap::new();
    for n in nodes {
        let class = angle_class_deg(n.angle_deg);
        let alpha = class.min(180.0 - class);
        let reach = reentrant_reach_mm(alpha, w);
        if !(alpha > 0.0 && reach < l) {
            return fail(
                n,
                format!(
                    "crossing with {} at {:.1}° is too acute for the star washer: \
                     neighbouring {w} mm arms meet {reach:.1} mm from the centre, \
                     beyond their {l} mm length",
                    n.strip_b, n.angle_deg
                ),
            );
        }
        *classes.entry((class * 2.0) as i64).or_default() += 1;
    }
    Ok(classes
        .iter()
        .rev()
        .map(|(&key, &nodes)| {
            washer_part(
                key as f64 / 2.0,
                l,
                w,
                hole_mm,
                nodes.saturating_mul(washer.per_node),
            )
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::read::profile_file;
    use crate::geom::plane::signed_area_mm2;
    use std::path::Path;

    fn steel() -> Profile {
        profile_file::load(Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/profiles/steel-1.5.yaml"
        )))
        .expect("steel profile")
    }

    fn node(id: usize, angle_deg: f64) -> GridNode {
        GridNode {
            id,
            strip_a: format!("A{id:02}"),
            strip_b: "B07".into(),
            angle_deg,
        }
    }

    /// Arm tips: the midpoint of each arm's two tip corners and its
    /// direction from the centre.
    fn arm_midlines(outline: &[Point], centre: Point) -> Vec<(f64, f64)> {
        (0..4)
            .map(|k| {
                let m = outline[3 * k].midpoint(outline[3 * k + 1]) - centre;
                (m.hypot(), m.y.atan2(m.x).to_degrees().rem_euclid(360.0))
            })
            .collect()
    }

    #[test]
    fn right_angle_star_is_a_symmetric_cross() {
        let (l, w) = (45.0, 9.6);
        let star = star_outline(90.0, l, w);
        assert_eq!(star.len(), 12);
        let area = signed_area_mm2(&star);
        assert!(
            (area - (2.0 * (2.0 * l * w) - w * w)).abs() < 1e-9,
            "{area}"
        );
        // Symmetric under both mirrors and the quarter turn.
        let has = |q: Point| star.iter().any(|p| p.distance(q) < 1e-9);
        for p in &star {
            assert!(has(Point::new(-p.x, p.y)));
            assert!(has(Point::new(p.x, -p.y)));
            assert!(has(Point::new(-p.y, p.x)));
        }
        // The re-entrant corners are those of the central w × w square.
        for k in 0..4 {
            let r = star[3 * k + 2];
            assert!((r.x.abs() - w / 2.0).abs() < 1e-12 && (r.y.abs() - w / 2.0).abs() < 1e-12);
        }
    }

    #[test]
    fn arms_lie_along_the_strips_at_the_node_angle() {
        let (l, w) = (45.0, 9.6);
        for phi in [90.0, 72.5, 60.0, 30.0] {
            let star = star_outline(phi, l, w);
            assert!(signed_area_mm2(&star) > 0.0);
            let want = [0.0, phi, 180.0, 180.0 + phi];
            for (k, (r, a)) in arm_midlines(&star, Point::ORIGIN).into_iter().enumerate() {
                assert!((r - l).abs() < 1e-9, "φ {phi}, arm {k}: reach {r}");
                assert!((a - want[k]).abs() < 1e-9, "φ {phi}, arm {k}: {a}");
                // The tip is square and w wide.
                assert!((star[3 * k].distance(star[3 * k + 1]) - w).abs() < 1e-9);
            }
            // Area of the union: two bars minus their rhombic overlap.
            let s = phi.to_radians().sin();
            let want_area = 2.0 * (2.0 * l * w) - w * w / s;
            assert!((signed_area_mm2(&star) - want_area).abs() < 1e-9);
        }
    }

    #[test]
    fn washers_group_by_half_degree_and_count_per_node() {
        let p = steel();
        let nodes = [
            node(0, 90.0),
            node(1, 89.8),
            node(2, 60.0),
            node(3, 87.6),
            node(4, 87.4),
        ];
        let parts = washers(&p, &nodes).expect("washers");
        let ids: Vec<&str> = parts.iter().map(|x| x.id.as_str()).collect();
        assert_eq!(ids, ["W90", "W87.5", "W60"]);
        let counts: Vec<u32> = parts.iter().map(|x| x.count).collect();
        assert_eq!(counts, [4, 4, 2]);
        let w60 = &parts[2];
        assert_eq!(w60.kind, PartKind::Washer);
        assert!(w60.engraving.is_empty());
        // Drawn at the class angle, arms along 0, 60, 180, 240 from the hole.
        let c = w60.features[0].center_part_mm;
        let want = [0.0, 60.0, 180.0, 240.0];
        for (k, (r, a)) in arm_midlines(&w60.outline_part_mm, c)
            .into_iter()
            .enumerate()
        {
            assert!((r - 45.0).abs() < 1e-9 && (a - want[k]).abs() < 1e-9);
        }
        // Bounding box at the origin; the hole is clockwise, M8 + 1 mm.
        let min_x = w60
            .outline_part_mm
            .iter()
            .map(|p| p.x)
            .fold(f64::INFINITY, f64::min);
        let min_y = w60
            .outline_part_mm
            .iter()
            .map(|p| p.y)
            .fold(f64::INFINITY, f64::min);
        assert!(min_x.abs() < 1e-12 && min_y.abs() < 1e-12);
        assert!((w60.features[0].width_mm - 9.0).abs() < 1e-12);
        // The hole only as its feature; its polygon built on demand.
        assert!(w60.holes_part_mm.is_empty());
        assert_eq!(w60.round_holes(), [(c, 4.5)]);
        let holes = w60.hole_polygons();
        assert!(signed_area_mm2(&holes[0]) < 0.0);
        for q in &holes[0] {
            assert!((q.distance(c) - 4.5).abs() < 1e-9);
        }
        // The W87.5 class is drawn at 87.5°.
        let w875 = &parts[1];
        let c = w875.features[0].center_part_mm;
        let (_, a) = arm_midlines(&w875.outline_part_mm, c)[1];
        assert!((a - 87.5).abs() < 1e-9);
    }

    #[test]
    fn no_washer_no_parts() {
        let mut p = steel();
        p.washer = None;
        assert!(washers(&p, &[node(0, 90.0)]).expect("ok").is_empty());
        assert!(washers(&steel(), &[]).expect("ok").is_empty());
    }

    #[test]
    fn errors_name_the_strip_and_node() {
        let mut p = steel();
        p.source = "steel.yaml".into();
        let msg =
            |p: &Profile, nodes: &[GridNode]| washers(p, nodes).expect_err("must fail").to_string();
        // Arms wider than the gap.
        let mut wide = p.clone();
        if let Some(w) = wide.washer.as_mut() {
            w.arm_width_mm = 10.5;
        }
        let m = msg(&wide, &[node(3, 90.0)]);
        assert!(m.starts_with("steel.yaml: strip A03, node 3: "), "{m}");
        assert!(m.contains("gap") && !m.contains('\n'), "{m}");
        // Single lamellas: no gap at all.
        let mut single = p.clone();
        single.section.per_strip = 1;
        assert!(msg(&single, &[node(0, 90.0)]).contains("single"));
        // A bolt hole as wide as the arm.
        let mut hole = p.clone();
        if let Some(b) = hole.node_bolt.as_mut() {
            b.hole_clearance_mm = 1.6;
        }
        let m = msg(&hole, &[node(1, 90.0)]);
        assert!(m.contains("node 1") && m.contains("cuts"), "{m}");
        // Too acute: (w/2)/tan(α/2) ≥ L. With w = 9.6, L = 45: α < 12.2°.
        let m = msg(&p, &[node(0, 90.0), node(5, 12.0)]);
        assert!(m.starts_with("steel.yaml: strip A05, node 5: "), "{m}");
        assert!(m.contains("acute") && m.contains("B07"), "{m}");
        assert!(washers(&p, &[node(5, 12.5)]).is_ok());
        assert!(msg(&p, &[node(6, 0.1)]).contains("acute"));
    }
}
