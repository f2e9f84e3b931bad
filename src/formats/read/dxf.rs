//! DXF input: 3D POLYLINE, LWPOLYLINE, LINE and SPLINE entities, as exported
//! from Rhino. The layer name gives the family (A…, B…, edge…); SPLINEs are
//! evaluated as NURBS, not taken as their control points.

use crate::error::{Error, Location, Result};
use crate::geom::nurbs::Nurbs;
use crate::network::{Family, RawCurve, RawNetwork, Unit};
use dxf::entities::EntityType;
use dxf::enums::Units;
use glam::DVec3;
use std::collections::BTreeMap;
use std::path::Path;

/// Samples per non-empty knot span when evaluating a SPLINE.
pub const SPLINE_SAMPLES_PER_SPAN: usize = 24;

/// Read a DXF file. `unit_override` is used when given, otherwise `$INSUNITS`
/// (unitless files are read as mm).
pub fn read(path: &Path, unit_override: Option<Unit>) -> Result<RawNetwork> {
    let meta = std::fs::metadata(path).map_err(|e| Error::io(path, e))?;
    if meta.len() == 0 {
        return Err(Error::input(path, Location::File, "the file is empty"));
    }
    let max_bytes = super::yaml_guard::MAX_NETWORK_FILE_BYTES;
    if meta.len() > max_bytes {
        return Err(Error::input(
            path,
            Location::File,
            format!(
                "{} bytes is more than the {} MiB lamella reads in such a file",
                meta.len(),
                max_bytes >> 20
            ),
        ));
    }
    let drawing = dxf::Drawing::load_file(path)
        .map_err(|e| Error::input(path, Location::File, format!("invalid DXF: {e}")))?;
    let unit = match unit_override {
        Some(u) => u,
        None => match drawing.header.default_drawing_units {
            Units::Unitless | Units::Millimeters => Unit::Mm,
            Units::Centimeters => Unit::Cm,
            Units::Meters => Unit::M,
            Units::Inches => Unit::In,
            Units::Feet => Unit::Ft,
            other => {
                return Err(Error::input(
                    path,
                    Location::Field("$INSUNITS".into()),
                    format!(
                    "unsupported drawing unit {other:?} (use mm, cm, m, in or ft, or pass --units)"
                ),
                ))
            }
        },
    };
    let mut counters: BTreeMap<String, usize> = BTreeMap::new();
    let mut curves = Vec::new();
    for entity in drawing.entities() {
        let layer = entity.common.layer.clone();
        // Entities on other layers (annotations, the surface, layer 0) are not curves of the network.
        let Some(family) = Family::from_prefix(&layer) else {
            continue;
        };
        let points: Vec<DVec3> = match &entity.specific {
            EntityType::Polyline(p) => {
                if p.is_polyface_mesh() || p.is_3d_polygon_mesh() {
                    continue;
                }
                let mut pts: Vec<DVec3> = if p.is_3d_polyline() {
                    p.vertices().map(|v| to_vec(&v.location)).collect()
                } else {
                    // A 2D polyline: vertices in its object coordinates at its elevation.
                    let ocs = Ocs::new(to_vec3(&p.normal));
                    let z = p.location.z;
                    p.vertices()
                        .map(|v| ocs.to_world(DVec3::new(v.location.x, v.location.y, z)))
                        .collect()
                };
                if p.is_closed() {
                    if let Some(&first) = pts.first() {
                        pts.push(first);
                    }
                }
                pts
            }
            EntityType::LwPolyline(p) => {
                let ocs = Ocs::new(to_vec3(&p.extrusion_direction));
                let z = entity.common.elevation;
                let n = p.vertices.len();
                let segments = if p.is_closed() {
                    n
                } else {
                    n.saturating_sub(1)
                };
                let mut pts: Vec<DVec3> = Vec::with_capacity(n);
                for k in 0..segments {
                    let (a, b) = (&p.vertices[k], &p.vertices[(k + 1) % n]);
                    let (pa, pb) = (glam::DVec2::new(a.x, a.y), glam::DVec2::new(b.x, b.y));
                    for q in bulge_arc(pa, pb, a.bulge) {
                        pts.push(ocs.to_world(q.extend(z)));
                    }
                }
                if let Some(last) = p.vertices.get(if p.is_closed() {
                    0
                } else {
                    n.saturating_sub(1)
                }) {
                    pts.push(ocs.to_world(DVec3::new(last.x, last.y, z)));
                }
                pts
            }
            EntityType::Line(l) => vec![to_vec(&l.p1), to_vec(&l.p2)],
            EntityType::Spline(s) => {
                let id_hint = format!(
                    "{} spline #{}",
                    layer,
                    counters.get(&layer).copied().unwrap_or(0) + 1
                );
                spline_points(s)
                    .map_err(|what| Error::input(path, Location::Curve(id_hint), what))?
            }
            _ => continue,
        };
        let n = counters.entry(layer.clone()).or_insert(0);
        *n += 1;
        let handle = entity.common.handle.0;
        let id = if handle != 0 {
            format!("{layer}-{handle:X}")
        } else {
            format!("{layer}-{n:03}")
        };
        curves.push(RawCurve {
            id,
            family,
            points,
            normals: None,
        });
    }
    if curves.is_empty() {
        return Err(Error::input(
            path,
            Location::File,
            "no POLYLINE, LWPOLYLINE, LINE or SPLINE entities on layers A…, B… or edge…",
        ));
    }
    Ok(RawNetwork {
        name: crate::formats::read::default_name(path),
        unit,
        tolerance: None,
        precision: None,
        curves,
    })
}

fn to_vec(p: &dxf::Point) -> DVec3 {
    DVec3::new(p.x, p.y, p.z)
}
fn to_vec3(v: &dxf::Vector) -> DVec3 {
    DVec3::new(v.x, v.y, v.z)
}

/// Points from `a` up to (not including) `b` along a polyline segment with a
/// bulge (tan of a quarter of the included angle; 0 is straight), sampled
/// every 5° of arc.
fn bulge_arc(a: glam::DVec2, b: glam::DVec2, bulge: f64) -> Vec<glam::DVec2> {
    if bulge.abs() < 1e-12 || a.distance(b) == 0.0 {
        return vec![a];
    }
    let theta = 4.0 * bulge.atan(); // signed included angle
    let chord = b - a;
    let half = chord.length() / 2.0;
    let radius = half / (theta / 2.0).sin();
    let mid = (a + b) / 2.0;
    // Centre: from the chord's midpoint along its left normal (for a positive bulge).
    let normal = glam::DVec2::new(-chord.y, chord.x) / chord.length();
    let centre = mid + normal * (radius * (theta / 2.0).cos());
    let start = (a - centre).to_angle();
    let steps = ((theta.abs().to_degrees() / 5.0).ceil() as usize).max(2);
    std::iter::once(a)
        .chain((1..steps).map(|i| {
            let ang = start + theta * i as f64 / steps as f64;
            centre + glam::DVec2::from_angle(ang) * radius.abs()
        }))
        .collect()
}

/// The DXF arbitrary-axis algorithm: object coordinates → world.
struct Ocs {
    ax: DVec3,
    ay: DVec3,
    az: DVec3,
}

impl Ocs {
    fn new(normal: DVec3) -> Ocs {
        let az = if normal.length() > 0.0 {
            normal.normalize()
        } else {
            DVec3::Z
        };
        let ax = if az.x.abs() < 1.0 / 64.0 && az.y.abs() < 1.0 / 64.0 {
            DVec3::Y.cross(az).normalize()
        } else {
            DVec3::Z.cross(az).normalize()
        };
        let ay = az.cross(ax).normalize();
        Ocs { ax, ay, az }
    }
    fn to_world(&self, p: DVec3) -> DVec3 {
        self.ax * p.x + self.ay * p.y + self.az * p.z
    }
}

/// Evaluate a DXF SPLINE (NURBS) densely along its knot spans.
fn spline_points(s: &dxf::entities::Spline) -> std::result::Result<Vec<DVec3>, String> {
    let ctrl: Vec<DVec3> = s.control_points.iter().map(to_vec).collect();
    if ctrl.is_empty() {
        // A fit-point-only spline: the fit points are the samples.
        let fit: Vec<DVec3> = s.fit_points.iter().map(to_vec).collect();
        if fit.len() < 2 {
            return Err("spline has neither control points nor fit points".into());
        }
        return Ok(fit);
    }
    let degree =
        usize::try_from(s.degree_of_curve).map_err(|_| "negative spline degree".to_string())?;
    let knots = &s.knot_values;
    let weights: Vec<f64> = if s.weight_values.len() == ctrl.len() {
        s.weight_values.clone()
    } else {
        vec![1.0; ctrl.len()]
    };
    let nurbs = Nurbs::new(degree, knots.clone(), ctrl, weights)?;
    Ok(nurbs.sample(SPLINE_SAMPLES_PER_SPAN))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bulge_arcs_lie_on_their_circle() {
        // A quarter circle of radius 1 about the origin, counter-clockwise.
        let pts = bulge_arc(
            glam::DVec2::X,
            glam::DVec2::Y,
            (std::f64::consts::PI / 8.0).tan(),
        );
        assert!(pts.len() >= 2 && pts[0] == glam::DVec2::X);
        for p in &pts {
            assert!((p.length() - 1.0).abs() < 1e-12, "{p}");
            assert!(p.x >= -1e-12 && p.y >= -1e-12, "the short way round: {p}");
        }
        // Clockwise: a negative bulge from (1, 0) to (0, -1).
        for p in bulge_arc(
            glam::DVec2::X,
            -glam::DVec2::Y,
            -(std::f64::consts::PI / 8.0).tan(),
        ) {
            assert!((p.length() - 1.0).abs() < 1e-12 && p.y <= 1e-12);
        }
        assert_eq!(
            bulge_arc(glam::DVec2::ZERO, glam::DVec2::X, 0.0),
            vec![glam::DVec2::ZERO]
        );
    }
}
