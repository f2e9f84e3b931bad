//! A sheet drawing as DXF for laser and waterjet software: R2000 (the
//! oldest version ezdxf and AutoCAD LT both read from the dxf crate),
//! millimetres (`$INSUNITS` = 4, `$MEASUREMENT` = 1), one layer per
//! operation with its colour (the `SHEET` layer not plotted), closed
//! LWPOLYLINEs per contour with arcs as bulges, round holes as CIRCLEs,
//! engraving as open LWPOLYLINEs, no blocks or splines. The header's dates
//! and GUIDs are fixed so the same sheet gives the same bytes.

use super::drawing::{Layer, Shape, SheetDrawing};
use dxf::entities::{Circle, Entity, EntityType, LwPolyline};
use dxf::enums::{AcadVersion, DrawingUnits, Units};
use dxf::tables::Layer as DxfLayer;
use dxf::{Color, Drawing, LwPolylineVertex, Point};

/// The DXF text of one sheet.
pub fn to_dxf(sheet: &SheetDrawing) -> std::result::Result<Vec<u8>, String> {
    let mut d = Drawing::new();
    let h = &mut d.header;
    h.version = AcadVersion::R2000;
    h.default_drawing_units = Units::Millimeters;
    h.drawing_units = DrawingUnits::Metric;
    // Fixed, so equal sheets give equal bytes (the defaults are "now" and
    // random GUIDs). DXF counts local dates from 1900-01-01 local time, so
    // that date is the one that reads the same in every time zone.
    let epoch = chrono::NaiveDate::from_ymd_opt(1900, 1, 1)
        .and_then(|d| d.and_hms_opt(0, 0, 0))
        .ok_or("bad fixed date")?;
    let local = epoch
        .and_local_timezone(chrono::Local)
        .earliest()
        .ok_or("no local time for the fixed date")?;
    let utc = epoch.and_utc();
    h.creation_date = local;
    h.update_date = local;
    h.creation_date_universal = utc;
    h.update_date_universal = utc;
    h.fingerprint_guid = uuid::Uuid::nil();
    h.version_guid = uuid::Uuid::nil();
    for layer in Layer::ALL {
        d.add_layer(DxfLayer {
            name: layer.name().to_string(),
            color: Color::from_index(layer.aci()),
            is_layer_plotted: layer != Layer::Sheet,
            ..Default::default()
        });
    }
    add_shape(&mut d, &sheet.outline());
    for part in &sheet.parts {
        for shape in &part.shapes {
            add_shape(&mut d, shape);
        }
    }
    let mut bytes = Vec::new();
    d.save(&mut bytes).map_err(|e| e.to_string())?;
    Ok(bytes)
}

fn add_shape(d: &mut Drawing, shape: &Shape) {
    let (layer, specific) = match shape {
        Shape::Polyline {
            layer,
            closed,
            vertices,
        } => {
            let mut pl = LwPolyline {
                vertices: vertices
                    .iter()
                    .map(|v| LwPolylineVertex {
                        x: v.x_mm,
                        y: v.y_mm,
                        bulge: v.bulge,
                        ..Default::default()
                    })
                    .collect(),
                ..Default::default()
            };
            pl.set_is_closed(*closed);
            (*layer, EntityType::LwPolyline(pl))
        }
        Shape::Circle {
            layer,
            center_mm,
            radius_mm,
        } => (
            *layer,
            EntityType::Circle(Circle::new(
                Point::new(center_mm[0], center_mm[1], 0.0),
                *radius_mm,
            )),
        ),
    };
    let mut e = Entity::new(specific);
    e.common.layer = layer.name().to_string();
    e.common.color = Color::by_layer();
    d.add_entity(e);
}
