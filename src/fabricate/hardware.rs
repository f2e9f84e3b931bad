//! What the workshop buys rather than cuts, and the cut parts it fits to:
//! node bolts and nuts, star washers, shear-block bolts, splice bolts,
//! studs and their fasteners, counted from the kit (docs/fabrication.md,
//! "Joints"). Grip lengths follow the joint stacks:
//!
//! * node bolt (along the surface normal, through the gap square between
//!   the four lamellas): lamella height h + the star washers on it,
//!   `per_node` × washer thickness;
//! * shear-block bolt (across a doubled strip): lamella, block (as thick
//!   as the gap), lamella: 2t + gap;
//! * splice bolt (through a lamella and its plate): 2t;
//! * stud fastener (across one level's doubled strip and the stud): 2t + gap.

use crate::profile::Profile;

/// One line of hardware.
#[derive(Debug, Clone, PartialEq)]
pub struct Hardware {
    /// What it is: `node bolt`, `node nut`, `star washer`, `shear-block
    /// bolt`, `splice bolt`, `stud`, `stud fastener`.
    pub item: &'static str,
    /// Size and standard (`M8 ISO 4017 8.8`, `M5`, `10 × 10 × 120 mm`).
    pub designation: String,
    /// Clamped thickness for bolts, mm.
    pub grip_mm: Option<f64>,
    /// How many.
    pub count: u64,
    /// Whether lamella cuts it (star washers, studs: see the parts) rather
    /// than a supplier delivering it.
    pub made: bool,
}

/// What the kit counts: grid nodes, shear blocks, splice plates, washers
/// and studs (pieces).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Counts {
    /// A×B nodes of the grid.
    pub grid_nodes: u64,
    /// Shear blocks.
    pub shear_blocks: u64,
    /// Splice plates (one per lamella per splice).
    pub splice_plates: u64,
    /// Star washers.
    pub washers: u64,
    /// Studs.
    pub studs: u64,
}

/// The hardware list of a kit for `profile`, in a fixed order; items with
/// a zero count are left out.
pub fn hardware(profile: &Profile, n: Counts) -> Vec<Hardware> {
    let (t, h, gap) = (
        profile.section.thickness_mm,
        profile.section.height_mm,
        profile.section.gap_mm,
    );
    let mut out = Vec::new();
    let mut push = |item, designation: String, grip_mm, count: u64, made| {
        if count > 0 {
            out.push(Hardware {
                item,
                designation,
                grip_mm,
                count,
                made,
            });
        }
    };
    if let Some(b) = &profile.node_bolt {
        let washers = profile
            .washer
            .as_ref()
            .map_or(0.0, |w| f64::from(w.per_node) * w.thickness_mm);
        push(
            "node bolt",
            b.designation.clone(),
            Some(h + washers),
            n.grid_nodes,
            false,
        );
        push(
            "node nut",
            format!("M{}", fmt_mm(b.diameter_mm)),
            None,
            n.grid_nodes,
            false,
        );
    }
    if let Some(w) = &profile.washer {
        push(
            "star washer",
            format!(
                "{} mm, arms {} mm",
                fmt_mm(w.thickness_mm),
                fmt_mm(w.arm_length_mm)
            ),
            None,
            n.washers,
            true,
        );
    }
    if let Some(b) = &profile.shear_block {
        push(
            "shear-block bolt",
            format!("M{}", fmt_mm(b.bolt_diameter_mm)),
            Some(2.0 * t + gap),
            n.shear_blocks,
            false,
        );
    }
    if let Some(s) = &profile.splice {
        push(
            "splice bolt",
            format!("M{}", fmt_mm(s.bolt_diameter_mm)),
            Some(2.0 * t),
            n.splice_plates * 2 * u64::from(s.bolts_per_side.max(1)),
            false,
        );
    }
    if let Some(s) = &profile.stud {
        push(
            "stud",
            format!("{0} × {0} × {1} mm", fmt_mm(gap), fmt_mm(s.length_mm)),
            None,
            n.studs,
            true,
        );
        push(
            "stud fastener",
            format!("ø{} mm", fmt_mm(s.fastener_diameter_mm)),
            Some(2.0 * t + gap),
            2 * n.studs,
            false,
        );
    }
    out
}

/// A length without trailing zeros: 8, 1.5.
fn fmt_mm(x: f64) -> String {
    let s = format!("{x:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::read::profile_file;

    /// The steel prototype: M8 node bolts through 50 mm lamellas and two
    /// 3 mm star washers (grip 56 mm), M5 shear-block bolts through
    /// 1.5 + 10 + 1.5 mm, M6 splice bolts 2 per side through 1.5 + 1.5 mm.
    #[test]
    fn steel_profile_hardware_by_hand() {
        let p = profile_file::load(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/profiles/steel-1.5.yaml"
        )))
        .expect("profile");
        let hw = hardware(
            &p,
            Counts {
                grid_nodes: 10,
                shear_blocks: 7,
                splice_plates: 3,
                washers: 20,
                studs: 0,
            },
        );
        let find = |item: &str| hw.iter().find(|h| h.item == item).expect(item);
        assert_eq!(find("node bolt").count, 10);
        assert_eq!(find("node bolt").grip_mm, Some(56.0));
        assert_eq!(find("node nut").designation, "M8");
        assert_eq!(find("shear-block bolt").grip_mm, Some(13.0));
        assert_eq!(find("splice bolt").count, 12);
        assert_eq!(find("splice bolt").designation, "M6");
        assert_eq!(find("star washer").count, 20);
        assert!(hw.iter().all(|h| h.item != "stud"));
    }
}
