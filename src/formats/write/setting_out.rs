//! `DIR/setting-out.csv`: every node's position and unit surface normal
//! in the network's own frame (the coordinates the network file gives,
//! in mm), for a total station or a jig. One header row; the node id, its
//! two strips and its joint as the node schedule names them; the numbers
//! as plan.json rounds them (positions 4 decimals, normals 7).

use crate::plan::Plan;
use serde::Serialize;

/// One row of the CSV.
#[derive(Serialize)]
struct Row<'a> {
    node: usize,
    strip_a: &'a str,
    strip_b: &'a str,
    x_mm: f64,
    y_mm: f64,
    z_mm: f64,
    normal_x: f64,
    normal_y: f64,
    normal_z: f64,
    joint: &'a str,
}

/// The setting-out table as CSV, nodes in id order.
pub fn to_csv(plan: &Plan) -> std::result::Result<Vec<u8>, String> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for n in &plan.nodes {
        w.serialize(Row {
            node: n.id,
            strip_a: &n.a,
            strip_b: &n.b,
            x_mm: n.position_mm[0],
            y_mm: n.position_mm[1],
            z_mm: n.position_mm[2],
            normal_x: n.normal[0],
            normal_y: n.normal[1],
            normal_z: n.normal[2],
            joint: &n.joint,
        })
        .map_err(|e| e.to_string())?;
    }
    w.into_inner().map_err(|e| e.to_string())
}
