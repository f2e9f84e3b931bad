//! The nest's named invariant, checked on any nest.

use super::model::{placed_bbox, Nest};
use super::outline;
use crate::fabricate::Kit;
use crate::geom::plane;
use crate::profile::Profile;
use kurbo::Point;

/// Named invariant: every part on a sheet of its own stock group (the
/// material and thickness the profile cuts it from), inside its sheet's
/// margins, in an allowed rotation, placed exactly its count of times, and
/// no two parts' true outlines closer than kerf + spacing (polygon-to-polygon
/// distance, where their bounding boxes come closer than that; boxes apart
/// means the true shapes are); the group's cutting on its sheets.
pub fn check_nest(kit: &Kit, nest: &Nest, profile: &Profile) -> std::result::Result<(), String> {
    let groups = profile.stock_groups();
    let eps = 1e-6;
    let mut placed: Vec<u32> = vec![0; kit.parts.len()];
    let mut seen: std::collections::HashSet<(usize, u32)> = std::collections::HashSet::new();
    for (sheet_index, s) in nest.sheets.iter().enumerate() {
        let Some(group) = nest.groups.iter().find(|g| g.sheets.contains(&sheet_index)) else {
            return Err(format!("{}: in no stock group", s.id));
        };
        let c = &group.cutting;
        let m = c.edge_margin_mm;
        let g = c.kerf_mm + c.part_spacing_mm;
        let mut boxes: Vec<((f64, f64, f64, f64), usize)> = Vec::with_capacity(s.placements.len());
        let mut outlines: Vec<Option<Vec<Point>>> = vec![None; s.placements.len()];
        for (k, pl) in s.placements.iter().enumerate() {
            let p = &kit.parts[pl.part];
            let own = &groups[Profile::group_of(&groups, p.kind.piece())];
            if own.material != group.material || own.thickness_mm != group.thickness_mm {
                return Err(format!(
                    "{}: {} is {} mm of {}, on a sheet of the {} group ({} mm of {})",
                    s.id,
                    p.id,
                    own.thickness_mm,
                    own.material,
                    group.name,
                    group.thickness_mm,
                    group.material
                ));
            }
            if !c.allowed_rotations_deg.contains(&pl.rotation_deg) {
                return Err(format!(
                    "{}: {} turned {}°, not allowed",
                    s.id, p.id, pl.rotation_deg
                ));
            }
            if !seen.insert((pl.part, pl.copy)) || pl.copy >= p.count {
                return Err(format!(
                    "{}: {} copy {} placed twice or beyond its count",
                    s.id, p.id, pl.copy
                ));
            }
            placed[pl.part] += 1;
            let b = placed_bbox(p, pl);
            if b.0 < m - eps
                || b.1 < m - eps
                || b.2 > s.length_mm - m + eps
                || b.3 > s.width_mm - m + eps
            {
                return Err(format!(
                    "{}: {} at {:?} is outside the margins",
                    s.id, p.id, b
                ));
            }
            boxes.push((b, k));
        }
        // Sweep along x: boxes whose x-extents come within the gap.
        boxes.sort_by(|a, b| a.0 .0.total_cmp(&b.0 .0));
        let mut active: Vec<((f64, f64, f64, f64), usize)> = Vec::new();
        for (b, k) in boxes {
            active.retain(|a| a.0 .2 + g > b.0 + eps);
            for &(a, j) in &active {
                let apart_y = a.3 + g <= b.1 + eps || b.3 + g <= a.1 + eps;
                let apart_x = a.2 + g <= b.0 + eps;
                if apart_y || apart_x {
                    continue;
                }
                // Boxes closer than the gap: the true outlines decide.
                for q in [j, k] {
                    if outlines[q].is_none() {
                        let pl = &s.placements[q];
                        outlines[q] = Some(outline::placed_outline(&kit.parts[pl.part], pl));
                    }
                }
                let (Some(oa), Some(ob)) = (&outlines[j], &outlines[k]) else {
                    continue;
                };
                let d = plane::polygon_distance(oa, ob, g);
                if d < g - eps {
                    return Err(format!(
                        "{}: {} is {d:.3} mm from {}, closer than {g} mm",
                        s.id,
                        kit.parts[s.placements[k].part].id,
                        kit.parts[s.placements[j].part].id
                    ));
                }
            }
            active.push((b, k));
        }
    }
    for (i, p) in kit.parts.iter().enumerate() {
        if placed[i] != p.count {
            return Err(format!(
                "{}: placed {} times, count {}",
                p.id, placed[i], p.count
            ));
        }
    }
    Ok(())
}
