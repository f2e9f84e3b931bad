//! The kit as strip-packing instances for sparrow (jagua-rs 0.7 JSON), one
//! per stock group:
//! `{name, strip_height, items: [{id, demand, allowed_orientations: [deg…],
//! shape: {type: "simple_polygon", data: [[x, y]…]}}]}`. The strip height is
//! the group's sheet width less its margins; every part's outline is grown
//! by half the group's kerf plus part spacing, so parts that merely touch in sparrow's
//! nest are the right distance apart when cut. Holes are dropped (jagua-rs
//! items have none); slots narrower than the growth close.

use crate::fabricate::part::Part;
use crate::fabricate::Kit;
use crate::nest::outline::grown_outline;
use crate::profile::{Cutting, Profile, Stock, StockForm};
use serde::Serialize;

/// The instance file.
#[derive(Debug, Serialize)]
pub struct Instance {
    /// Instance name (the network's, then the group's).
    pub name: String,
    /// Usable sheet width, mm.
    pub strip_height: f64,
    /// One per distinct part.
    pub items: Vec<Item>,
}

/// One distinct part.
#[derive(Debug, Serialize)]
pub struct Item {
    /// Index in the kit's parts (plan.json's `parts`).
    pub id: usize,
    /// Copies wanted.
    pub demand: u32,
    /// Allowed rotations, degrees.
    pub allowed_orientations: Vec<f64>,
    /// The grown outline.
    pub shape: Shape,
}

/// A polygon shape.
#[derive(Debug, Serialize)]
pub struct Shape {
    /// Always `simple_polygon`.
    #[serde(rename = "type")]
    pub kind: String,
    /// Vertices, counter-clockwise, mm.
    pub data: Vec<[f64; 2]>,
}

/// One instance per stock group of `profile` that has parts in the kit
/// and is nested in two dimensions (a bar group is a cut list, not
/// exported), with the group's name: its parts only (each item's `id`
/// the part's index in the kit), its stock's strip height (with several
/// sizes, the widest size's usable width), its kerf, spacing and
/// rotations. Named `NAME GROUP`.
pub fn instances(name: &str, kit: &Kit, profile: &Profile) -> Vec<(String, Instance)> {
    let groups = profile.stock_groups();
    groups
        .iter()
        .enumerate()
        .filter(|(_, g)| g.form != StockForm::Bar)
        .filter_map(|(gi, g)| {
            let members: Vec<(usize, &Part)> = kit
                .parts
                .iter()
                .enumerate()
                .filter(|(_, p)| Profile::group_of(&groups, p.kind.piece()) == gi)
                .collect();
            (!members.is_empty()).then(|| {
                let inst = instance(
                    &format!("{name} {}", g.name),
                    &members,
                    &g.stock,
                    &g.cutting,
                );
                (g.name.clone(), inst)
            })
        })
        .collect()
}

/// The instance of `parts` (each with its index in the kit) for a stock
/// cut with `cutting`.
fn instance(name: &str, parts: &[(usize, &Part)], stock: &Stock, c: &Cutting) -> Instance {
    let d = 0.5 * (c.kerf_mm + c.part_spacing_mm);
    let round = |x: f64| (x * 1e4).round() / 1e4 + 0.0;
    Instance {
        name: name.to_string(),
        strip_height: round(stock.widest_usable_mm(c.edge_margin_mm)),
        items: parts
            .iter()
            .map(|&(i, p)| Item {
                id: i,
                demand: p.count,
                allowed_orientations: c
                    .allowed_rotations_deg
                    .iter()
                    .map(|&r| f64::from(r))
                    .collect(),
                shape: Shape {
                    kind: "simple_polygon".into(),
                    data: grown_outline(p, d)
                        .iter()
                        .map(|q| [round(q.x), round(q.y)])
                        .collect(),
                },
            })
            .collect(),
    }
}
