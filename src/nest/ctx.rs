//! What one nest needs to know, built once from the kit and the profile:
//! the stock sizes, the lamella copies for the lanes, the other parts in
//! their order, the washers' lattice blocks; and the refusals of a kit the
//! stock cannot hold.

use super::lattice::{self, lattice_blocks};
use super::model::bbox;
use super::stock::{by_value, fits, Size};
use crate::error::{Error, Result};
use crate::fabricate::part::PartKind;
use crate::fabricate::{net_area_mm2, Kit};
use crate::profile::Profile;

/// What one nest needs to know, built once.
pub(super) struct Ctx<'a> {
    /// The parts to nest.
    pub(super) kit: &'a Kit,
    /// The stock, the cutting parameters and the lamella section.
    pub(super) profile: &'a Profile,
    /// Edge margin all round a sheet, mm.
    pub(super) margin: f64,
    /// Kerf + part spacing between parts, mm.
    pub(super) gap: f64,
    /// The lamellas' height (the section's), the width of a lane, mm.
    pub(super) height: f64,
    /// The allowed rotations, degrees.
    pub(super) rotations: Vec<u32>,
    /// The rotation the lamellas lie in along the sheet: 0°, else 180°.
    pub(super) lamella_rot: u32,
    /// The profile's stock sizes, in its order.
    pub(super) sizes: Vec<Size>,
    /// Sizes by cost per usable area, ties by index.
    pub(super) by_value: Vec<usize>,
    /// (part, copy) of every lamella copy.
    pub(super) items: Vec<(usize, u32)>,
    /// Item sizes for the lanes: length + gap.
    pub(super) item_len: Vec<f64>,
    /// Other parts, largest bounding box first.
    pub(super) others: Vec<usize>,
    /// Per part: the lattice blocks its copies may go in, for star
    /// washers that pack denser with their arms interleaved
    /// ([`lattice`]); empty for every other part.
    pub(super) blocks: Vec<Vec<lattice::Block>>,
    /// Per part: its net area, mm² (`net_area_mm2`, taken once).
    pub(super) areas: Vec<f64>,
}

impl<'a> Ctx<'a> {
    /// The context of `kit` on `profile`'s stock; the refusal of a part
    /// that fits no stock size in an allowed rotation, and of lamellas no
    /// size has lanes for.
    pub(super) fn new(kit: &'a Kit, profile: &'a Profile) -> Result<Ctx<'a>> {
        let c = &profile.cutting;
        let m = c.edge_margin_mm;
        let g = c.kerf_mm + c.part_spacing_mm;
        let h = profile.section.height_mm;
        let st = &profile.stock;
        let sizes: Vec<Size> = st.sizes.iter().map(|z| Size::new(z, m, g, h)).collect();
        let by_value = by_value(&sizes);
        let rotations = c.allowed_rotations_deg.clone();
        refuse_unfit_parts(kit, profile, &sizes)?;
        let mut items: Vec<(usize, u32)> = Vec::new();
        for (i, p) in kit.parts.iter().enumerate() {
            if p.kind == PartKind::Lamella {
                for copy in 0..p.count {
                    items.push((i, copy));
                }
            }
        }
        let item_len: Vec<f64> = items
            .iter()
            .map(|&(i, _)| kit.parts[i].length_mm + g)
            .collect();
        refuse_unfit_lamellas(kit, profile, &sizes, &items, &item_len)?;
        let mut others: Vec<usize> = (0..kit.parts.len())
            .filter(|&i| kit.parts[i].kind != PartKind::Lamella)
            .collect();
        let area = |i: usize| {
            let (x0, y0, x1, y1) = bbox(&kit.parts[i]);
            (x1 - x0) * (y1 - y0)
        };
        others.sort_by(|&a, &b| area(b).total_cmp(&area(a)).then(a.cmp(&b)));
        let blocks = kit
            .parts
            .iter()
            .map(|p| lattice_blocks(p, g, &rotations, &sizes))
            .collect();
        Ok(Ctx {
            kit,
            profile,
            margin: m,
            gap: g,
            height: h,
            lamella_rot: if rotations.contains(&0) { 0 } else { 180 },
            rotations,
            sizes,
            by_value,
            items,
            item_len,
            others,
            blocks,
            areas: kit.parts.iter().map(net_area_mm2).collect(),
        })
    }

    /// The one-line error of a kit the stock cannot hold.
    pub(super) fn fail_stock(&self, what: String) -> Error {
        Error::Fabrication {
            profile: self.profile.source.clone(),
            at: "stock".into(),
            node: None,
            what: crate::error::one_line(&what),
        }
    }

    /// `max_count 3 of 3000 × 1500, …` for the sizes with a limit.
    pub(super) fn limits(&self) -> String {
        let list: Vec<String> = self
            .sizes
            .iter()
            .filter(|z| z.limit < usize::MAX)
            .map(|z| format!("{} of {}", z.limit, z.label))
            .collect();
        format!("max_count {}", list.join(", "))
    }
}

/// The refusal of the first part that fits no stock size in an allowed
/// rotation.
fn refuse_unfit_parts(kit: &Kit, profile: &Profile, sizes: &[Size]) -> Result<()> {
    let m = profile.cutting.edge_margin_mm;
    let st = &profile.stock;
    let rotations = &profile.cutting.allowed_rotations_deg;
    let fail = |part: &str, what: String| Error::fabrication_part(&profile.source, part, what);
    // Every part must fit some size in an allowed rotation.
    for p in &kit.parts {
        let (x0, y0, x1, y1) = bbox(p);
        let (w, ht) = (x1 - x0, y1 - y0);
        if !st.holds(w, ht, m, rotations) {
            let usable = if sizes.len() == 1 {
                format!(
                    "the {:.0} × {:.0} mm usable sheet",
                    sizes[0].lu, sizes[0].wu
                )
            } else {
                let list: Vec<String> = sizes
                    .iter()
                    .map(|s| format!("{}: {:.0} × {:.0} mm", s.label, s.lu, s.wu))
                    .collect();
                format!("the usable area of any stock size ({})", list.join(", "))
            };
            return Err(fail(
                &p.id,
                format!(
                    "{w:.0} × {ht:.0} mm does not fit {usable} in any allowed rotation \
                     ({rotations:?}°)"
                ),
            ));
        }
    }
    Ok(())
}

/// The refusal of lamellas the stock has no lanes for: where no allowed
/// rotation lays them along the sheet, no size has a lane across it, or
/// one is longer than every size's lanes (`items`, `item_len`: the
/// lamella copies and their lengths + gap).
fn refuse_unfit_lamellas(
    kit: &Kit,
    profile: &Profile,
    sizes: &[Size],
    items: &[(usize, u32)],
    item_len: &[f64],
) -> Result<()> {
    let h = profile.section.height_mm;
    let rotations = &profile.cutting.allowed_rotations_deg;
    let fail = |part: &str, what: String| Error::fabrication_part(&profile.source, part, what);
    if let Some(&(first, _)) = items.first() {
        let id = &kit.parts[first].id;
        if !rotations.iter().any(|r| r % 180 == 0) {
            return Err(fail(
                id,
                "lamellas lie along the sheet, but the profile allows neither 0° nor 180°".into(),
            ));
        }
        if sizes.iter().all(|s| s.lanes == 0) {
            let wu = sizes.iter().map(|s| s.wu).fold(0.0, f64::max);
            return Err(fail(
                id,
                format!("a {h} mm lamella does not fit across the {wu:.0} mm usable sheet"),
            ));
        }
        // Each lamella into the lanes of some size.
        for (k, &(i, _)) in items.iter().enumerate() {
            if !sizes
                .iter()
                .any(|s| s.lanes > 0 && fits(item_len[k], s.cap))
            {
                return Err(fail(
                    &kit.parts[i].id,
                    format!(
                        "a {:.0} mm lamella fits the lanes of no stock size",
                        kit.parts[i].length_mm
                    ),
                ));
            }
        }
    }
    Ok(())
}
