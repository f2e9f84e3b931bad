//! The kit as a strip-packing instance for sparrow (jagua-rs 0.7 JSON):
//! `{name, strip_height, items: [{id, demand, allowed_orientations: [deg…],
//! shape: {type: "simple_polygon", data: [[x, y]…]}}]}`. The strip height is
//! the sheet's width less the margins; every part's outline is grown by
//! half the kerf plus part spacing, so parts that merely touch in sparrow's
//! nest are the right distance apart when cut. Holes are dropped (jagua-rs
//! items have none); slots narrower than the growth close.

use crate::fabricate::Kit;
use crate::nest::outline::grown_outline;
use crate::profile::Profile;
use serde::Serialize;

/// The instance file.
#[derive(Debug, Serialize)]
pub struct Instance {
    /// Instance name (the network's).
    pub name: String,
    /// Usable sheet width, mm.
    pub strip_height: f64,
    /// One per distinct part.
    pub items: Vec<Item>,
}

/// One distinct part.
#[derive(Debug, Serialize)]
pub struct Item {
    /// Index in the kit's parts.
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

/// The instance of a kit for a profile's stock (with several sizes, the
/// strip is as high as the widest size's usable width).
pub fn instance(name: &str, kit: &Kit, profile: &Profile) -> Instance {
    let c = &profile.cutting;
    let d = 0.5 * (c.kerf_mm + c.part_spacing_mm);
    let round = |x: f64| (x * 1e4).round() / 1e4 + 0.0;
    Instance {
        name: name.to_string(),
        strip_height: round(profile.stock.widest_usable_mm(c.edge_margin_mm)),
        items: kit
            .parts
            .iter()
            .enumerate()
            .map(|(i, p)| Item {
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
